"""`import specula` against the CLI of the same build: the same numbers for the same call (to the
last digit where the path is the same), arrays of several shapes and both float types, and bad
input as ValueError/TypeError with the CLI's message. Each comparison has a negative control: the
helper that compares fails on a value one ulp off."""
import math
import os
import pickle
import signal
import time

import numpy as np
import pytest

from conftest import cli, cli_error, column


def same(a, b):
    """Equal to the last digit (NaN equal to NaN)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    assert a.shape == b.shape, (a.shape, b.shape)
    assert np.array_equal(a, b, equal_nan=True), (a, b)


def close(a, b, rel):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    assert a.shape == b.shape, (a.shape, b.shape)
    assert np.all(np.abs(a - b) <= rel * np.abs(b) + 1e-300), (a, b)


def test_the_comparisons_fail_on_a_wrong_value():  # the negative control of every check below
    with pytest.raises(AssertionError):
        same([1.0, 2.0], [1.0, np.nextafter(2.0, 3.0)])
    with pytest.raises(AssertionError):
        close([1.0], [1.0 + 1e-9], 1e-12)
    with pytest.raises(AssertionError):
        same([1.0, 2.0], [[1.0, 2.0]])


def test_models_are_the_catalogue(specula):
    ids = [m["id"] for m in specula.models()]
    assert ids == [m["id"] for m in cli("models", "--json")]
    log = next(m for m in specula.models() if m["id"] == "log")
    assert log["kind"] == "lobe" and log["form"] == "rv"
    assert [p["name"] for p in log["params"]] == ["n"]


def test_a_model_has_the_clis_coefficient_params_and_repr(specula):
    m = specula.model("log-normalized", n=20)
    table = cli("normalize", "-m", "log", "--n", "20", "--format", "json")
    same(m.coef, column(table, "coef")[0])
    assert m.params == {"n": 20.0}
    assert m.form == "rv" and m.kind == "lobe" and m.is_lobe
    assert repr(m) == "specula.model('log-normalized', n=20)"
    assert specula.model("ggx", alpha=0.3).coef is None
    assert specula.model("phong", n=2, form="nh").form == "nh"
    assert specula.model("phong", n=2, coef=3.0).coef == 3.0


def test_models_pickle_through_their_definition(specula):
    for m in [specula.model("log", n=7), specula.model("lobe: c^n", n=3, form="nh"), specula.model("ggx+ms", alpha=0.4)]:
        back = pickle.loads(pickle.dumps(m))
        assert repr(back) == repr(m)
        same(back([0, 0, 1], [0.6, 0, 0.8]), m([0, 0, 1], [0.6, 0, 0.8]))


@pytest.mark.parametrize("model_id,params", [("log", {"n": 20}), ("schlick", {"n": 50}), ("phong", {"n": 1000}),
                                             ("lobe: max(0, 1 - n*(1-c)/4)^4", {"n": 20})])
def test_the_lobe_over_cosines_is_the_clis(specula, model_id, params):
    cosines = [1.0, 0.999, 0.99, 0.9, 0.5, 0.1, 0.0, -0.5]
    table = cli("eval", "-m", model_id, *[f"-p{k}={v}" for k, v in params.items()],
                "--cos", ",".join(map(str, cosines)), "--lobe", "--format", "json")
    m = specula.model(model_id, **params)
    close(m.lobe(cosines), column(table, "value"), 1e-13)  # the exact tier: a few ulp of the scalar lobe
    close(m.lobe(cosines, tier="fast"), column(table, "value"), 1e-3)


def test_arrays_keep_their_shape_and_type(specula):
    m = specula.model("log", n=20)
    c = np.linspace(0, 1, 12).reshape(3, 4)
    assert m.lobe(c).shape == (3, 4) and m.lobe(c).dtype == np.float64
    f32 = m.lobe(c.astype(np.float32))
    assert f32.dtype == np.float32 and f32.shape == (3, 4)
    close(f32, m.lobe(c), 1e-5)
    same(m.lobe(c[:, ::2]), m.lobe(np.ascontiguousarray(c[:, ::2])))  # non-contiguous
    assert m.lobe(np.empty(0)).shape == (0,)
    assert math.isnan(m.lobe([math.nan])[0])
    same(m.lobe(np.arange(3, dtype=np.int64) / 2), m.lobe([0.0, 0.5, 1.0]))


def test_directions_are_the_clis(specula):
    m = specula.model("ggx", alpha=0.3)
    table = cli("eval", "-m", "ggx", "-p", "alpha=0.3", "--theta-i", "45", "--theta-o", "0,30,60", "--phi-o", "180",
                "--format", "json")
    t = math.radians(45)
    light = np.array([math.sin(t), 0, math.cos(t)])
    views = np.array([[-math.sin(math.radians(a)), 0, math.cos(math.radians(a))] for a in (0, 30, 60)])
    close(m(light, views), column(table, "value"), 1e-12)
    close(m.eval(light, views), column(table, "value"), 1e-12)
    same(m(light, views, n=[0, 0, 1]), m(light, views))
    assert m(np.tile(light, (2, 5, 1)), views[0]).shape == (2, 5)


def test_views_are_read_through_their_strides(specula):
    """Inputs are read where they lie, a chunk at a time (docs/python.md): strided, reversed,
    transposed and broadcast views, more than one chunk of them, give the values of their
    contiguous copies; an out= that overlaps the input gets the values of the input as it was."""
    log, ggx = specula.model("log", n=20), specula.model("ggx", alpha=0.3)
    c = np.linspace(0, 1, 3 * 70_001).reshape(3, -1)
    for view in [c[:, ::-3], c.T, c[::-1, 5], np.broadcast_to(c[0, :7], (40_000, 7)), c[1, 2]]:
        same(log.lobe(view), log.lobe(view.copy()))
        same(log.lobe(view.astype(np.float32)[()]), log.lobe(np.array(view, dtype=np.float32)))
    t = np.radians(np.linspace(0, 89, 50_000))
    v = np.stack([np.sin(t), 0 * t, np.cos(t)], axis=-1)
    lights = v[::-7, None, :]   # (7143, 1, 3) against (1, 5, 3): (7143, 5) directions
    views = v[:5][None]
    same(ggx(lights, views), ggx(np.ascontiguousarray(np.broadcast_to(lights, (len(lights), 5, 3))),
                                 np.ascontiguousarray(np.broadcast_to(views, (len(lights), 5, 3)))))
    same(ggx(v.T.copy().T, v[::-1], n=[0, 0, 1]), ggx(v, v[::-1].copy()))
    u = np.linspace(0, 0.999, 40_000)
    tiled = np.tile(v[0], (40_000, 10, 1)), np.repeat(u[:, None], 10, 1), np.tile(u[::-4000], (40_000, 1))
    for got, expected in zip(ggx.sample(v[0], u[:, None], u[None, ::-4000]), ggx.sample(*tiled)):
        same(got, expected)
    same(ggx.pdf(v[0], v[::-2]), ggx.pdf(np.tile(v[0], (25_000, 1)), v[::-2].copy()))
    memory = np.linspace(0, 1, 2 * 70_001)
    before = memory[::-2].copy()
    out = log.lobe(memory[::-2], out=memory[:70_001])   # writes the memory it reads, in another order
    same(out, log.lobe(before))
    inplace = before.copy()
    same(log.lobe(inplace, out=inplace), log.lobe(before))


def test_normalize_albedo_error_check_are_the_clis(specula):
    same(specula.normalize("log", n=[1, 20, 1000]),
         column(cli("normalize", "-m", "log", "--n", "1,20,1000", "--format", "json"), "coef"))
    m = specula.model("phong-normalized", n=20)
    same(specula.albedo(m, [0, 60, 85]),
         column(cli("albedo", "-m", "phong-normalized", "-p", "n=20", "--theta", "0,60,85", "--format", "json"), "albedo"))
    got = specula.error("log", n=[2, 20])
    table = cli("error", "-m", "log", "--n", "2,20", "--format", "json")
    for name in ("n", "max_abs", "argmax_abs_deg", "max_rel_epicenter", "max_rel_attenuation"):
        same(got[name], column(table, name))
    r = specula.check(m, pairs=1000)
    [expected] = cli("check", "-m", "phong-normalized", "--n", "20", "--pairs", "1000", "--json")
    assert (r.conserves_energy, r.reciprocal, r.non_negative) == (True, True, True) and bool(r)
    same([r.albedo_normal, r.max_albedo, r.max_albedo_theta, r.max_asymmetry, r.min_value],
         [expected[k] for k in ("albedo_normal", "max_albedo", "max_albedo_theta_deg", "max_asymmetry", "min_value")])
    assert not specula.check(specula.model("phong", n=20, coef=10.0), pairs=100, step=5)  # k too large: fails


def test_code_is_the_clis(specula):
    import subprocess
    run = lambda *a: subprocess.run([os.environ["SPECULA_CLI"], *a], capture_output=True, text=True).stdout
    assert specula.glsl(specula.model("log-normalized", n=20)).strip() == run("glsl", "-m", "log-normalized", "-p", "n=20").strip()
    assert specula.export("ggx", "hlsl").strip() == run("export", "-m", "ggx", "--format", "hlsl").strip()


def test_bad_input_is_a_value_error_with_the_clis_message(specula):
    with pytest.raises(ValueError) as e:
        specula.model("nope")
    assert str(e.value) == cli_error("eval", "-m", "nope", "--cos", "1")
    with pytest.raises(ValueError, match="n"):
        specula.model("log", n=math.nan)
    with pytest.raises(ValueError, match="column"):
        specula.model("lobe: c^")
    with pytest.raises(ValueError, match="tier"):
        specula.model("log").lobe([1.0], tier="fastest")
    with pytest.raises(ValueError, match="full BRDF"):
        specula.model("ggx").lobe([1.0])
    with pytest.raises(ValueError, match=r"\(\.\.\., 3\)"):
        specula.model("ggx")([[0, 1]], [[0, 1]])
    with pytest.raises(TypeError):
        specula.model("log").lobe("x")
    with pytest.raises(TypeError):
        specula.normalize(3.0, n=[1])
    with pytest.raises(ValueError, match="format"):
        specula.export("ggx", "nope")
    with pytest.raises(ValueError):
        specula.normalize("log", n=[0])


def test_ctrl_c_stops_a_long_call(specula):
    previous = signal.signal(signal.SIGALRM, lambda *_: os.kill(os.getpid(), signal.SIGINT))
    signal.setitimer(signal.ITIMER_REAL, 0.3)
    start = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            specula.albedo("ggx", list(range(0, 89)), method="monte-carlo", samples=10**9)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    assert time.monotonic() - start < 5


def test_load_models_from_text(specula):
    ids = specula.load_models('[[model]]\nid = "py-lobe"\nname = "a test lobe"\nkind = "lobe"\nform = "rv"\n'
                              'lobe = "c^n"\nnormalization = "quadrature"\n[model.params.n]\ndefault = 20\nmin = 1\nmax = 1000\n')
    assert ids == ["py-lobe"]
    close(specula.model("py-lobe", n=20).coef, specula.model("phong-normalized", n=20).coef, 1e-12)
    with pytest.raises(ValueError):
        specula.load_models("[[model]]\nid = \"broken\"\n")


def test_out_receives_the_values(specula):
    m = specula.model("log", n=20)
    c = np.linspace(0, 1, 7, dtype=np.float32)
    out = np.full(7, -1, dtype=np.float32)
    assert m.lobe(c, out=out) is not None
    same(out, m.lobe(c))
    with pytest.raises(TypeError):
        m.lobe(c, out=np.empty(7))          # float64 for float32 values
    with pytest.raises(ValueError, match="shape"):
        m.lobe(c, out=np.empty(6, dtype=np.float32))


def test_the_examples_run_and_type_check(specula, tmp_path):
    import subprocess
    import sys
    examples = os.path.join(os.environ["SPECULA_SOURCE_DIR"], "examples", "python")
    scripts = sorted(os.path.join(examples, f) for f in os.listdir(examples) if f.endswith(".py"))
    assert len(scripts) >= 6
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(os.path.abspath(p) for p in os.environ["PYTHONPATH"].split(os.pathsep)))
    for script in scripts:  # each writes its figures into the directory it is given
        done = subprocess.run([sys.executable, script, str(tmp_path)], capture_output=True, text=True, timeout=300,
                              cwd=tmp_path, env=env)
        assert done.returncode == 0, done.stderr
    figures = sorted(p.name for p in tmp_path.iterdir())
    assert figures == ["albedo.png", "fig2.png", "fig3.png", "fig4.png", "fitted-normalization.png",
                       "sampled-histogram.png"], figures
    assert all((tmp_path / f).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for f in figures)
    # mypy (Debian's) against the package's stubs; without the sanitizers' runtimes, which it does not need.
    env = {k: v for k, v in os.environ.items() if k not in ("LD_PRELOAD", "ASAN_OPTIONS")}
    env["MYPYPATH"] = env["PYTHONPATH"]
    # One mypy run checks the examples and the control together: a script that passes a string
    # where the package's type annotations (.pyi) want numbers. Its error must be the only one.
    control = tmp_path / "control_string_for_a_number.py"
    control.write_text("import specula\nspecula.model('log', n='x')\n")
    done = subprocess.run(["mypy", "--strict", "--no-incremental", *scripts, str(control)], capture_output=True,
                          text=True, timeout=600, env=env)
    errors = [line for line in done.stdout.splitlines() if ": error:" in line]
    assert done.returncode != 0 and errors, done.stdout
    assert all(line.split(":", 1)[0].endswith(control.name) for line in errors), done.stdout


def test_every_function_has_an_example_that_holds(specula):
    import doctest
    public = [getattr(specula, name) for name in specula.__all__] + [
        specula.Model.lobe, specula.Model.__call__, specula.Model.sample, specula.Model.pdf, specula]
    checked = 0
    for obj in public:
        examples = doctest.DocTestParser().get_examples(obj.__doc__ or "")
        if not isinstance(obj, type) and not examples:  # classes are shown by the functions that make them
            pytest.fail(f"{getattr(obj, '__name__', obj)} has no example in its docstring")
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
        test = doctest.DocTest(examples, {"specula": specula, "np": np}, getattr(obj, "__name__", "?"), None, 0, None)
        runner.run(test)
        assert runner.failures == 0, f"{test.name}: an example does not hold"
        checked += len(examples)
    assert checked >= 18
