"""Sampling, tables, pictures, fit and design from Python against the CLI of the same build (the
same numbers to the last digit where the path is the same) and against independent references
(the albedo, a formula's own Python code, a furnace). Each check has its negative control."""
import io
import math
import os
import re

import numpy as np
import pytest

from conftest import cli, cli_error, cli_text, column, read_exr
from test_specula import close, same


def csv_rows(text):
    lines = text.strip().splitlines()
    return lines[0].split(","), np.array([[float(x) for x in line.split(",")] for line in lines[1:]])


def incidence(theta_deg):
    t = math.radians(theta_deg)
    return np.array([math.sin(t), 0.0, math.cos(t)])


# --- sampling ---

def test_pdf_and_weights_are_the_clis_samples(specula):
    header, rows = csv_rows(cli_text("sample", "--model", "ggx", "-p", "alpha=0.2", "--theta-i", "60", "--count",
                                     "3000", "--seed", "3"))
    assert header == ["x", "y", "z", "pdf", "weight"]
    m = specula.model("ggx", alpha=0.2)
    wi = incidence(60)
    kept = rows[:, 3] > 0
    wo = rows[kept, :3]
    close(m.pdf(wi, wo), rows[kept, 3], 1e-12)
    close(m.eval(wi, wo) * wo[:, 2] / rows[kept, 3], rows[kept, 4], 1e-12)
    with pytest.raises(AssertionError):  # control: another model's densities differ
        close(specula.model("ggx", alpha=0.25).pdf(wi, wo), rows[kept, 3], 1e-6)


@pytest.mark.parametrize("model_id, params", [("ggx", {"alpha": 0.3}), ("log-normalized", {"n": 50}),
                                              ("blinn-phong-normalized", {"n": 100}), ("lambert", {})])
def test_samples_have_the_stated_density_and_weight(specula, model_id, params):
    m = specula.model(model_id, **params)
    rng = np.random.default_rng(7)
    count = 100_000
    wi = incidence(30)
    wo, pdf, weight = m.sample(wi, rng.random(count), rng.random(count))
    assert wo.shape == (count, 3) and pdf.shape == weight.shape == (count,)
    kept = pdf > 0
    close(m.pdf(wi, wo[kept]), pdf[kept], 1e-9)
    close(weight[kept], m.eval(wi, wo[kept]) * wo[kept, 2] / pdf[kept], 1e-9)
    assert np.all(weight[~kept] == 0)
    albedo = float(specula.albedo(m, [30])[0])  # independent: the cubature
    se = weight.std() / math.sqrt(count)
    assert abs(weight.mean() - albedo) < 5 * se + 1e-12, (weight.mean(), albedo, se)
    assert abs(weight.mean() * 0.9 - albedo) > 5 * se  # control: a mean 10 % off fails


def test_sampling_broadcasts_and_takes_no_sample_below_the_horizon(specula):
    m = specula.model("phong-normalized", n=20)
    u = np.full((4, 5), 0.5)
    wo, pdf, weight = m.sample([0, 0, 1], u, u.T[:1].T)  # (4, 5) and (4, 1) against one direction
    assert wo.shape == (4, 5, 3) and pdf.shape == (4, 5)
    wo, pdf, weight = m.sample([[0, 0, -1], [0, 0, 2], [np.nan, 0, 1], [0, 0, 0]], 0.3, 0.6)
    assert list(pdf > 0) == [False, True, False, False]  # (0, 0, 2) is normalized
    assert np.all(weight[[0, 2, 3]] == 0)
    assert m.pdf([0, 0, 1], [0, 0, -1]) == 0
    assert m.sample(np.empty((0, 3)), np.empty(0), np.empty(0))[0].shape == (0, 3)
    with pytest.raises(ValueError, match="u1 must be in \\[0, 1\\)"):
        m.sample([0, 0, 1], 1.0, 0.5)
    with pytest.raises(ValueError, match="u2"):
        m.sample([0, 0, 1], 0.5, np.nan)
    with pytest.raises(ValueError, match="wi"):
        m.sample([0, 1], 0.5, 0.5)
    with pytest.raises(ValueError, match="broadcast"):
        m.sample(np.zeros((3, 3)) + [0, 0, 1], np.zeros(4), np.zeros(4))


def test_check_sampling_is_the_clis(specula):
    ref = cli("check", "--model", "ggx", "-p", "alpha=0.2", "--sampling", "--theta-i", "30,70", "--samples", "20000",
              "--bins", "16", "--json")
    r = specula.check_sampling(specula.model("ggx", alpha=0.2), theta=[30, 70], samples=20000, bins=16)
    assert r.passes == ref["passes"] and r.method == ref["method"]
    for mine, theirs in zip(r.angles, ref["angles"], strict=True):
        for key in ["chi2", "p_value", "mean_weight", "albedo", "pdf_integral", "max_weight"]:
            same(mine[key], theirs[key])
        assert mine["samples"] == theirs["samples"] and mine["observed"].shape == (16 * 32,)
    other = specula.check_sampling(specula.model("ggx", alpha=0.2), theta=[30, 70], samples=20000, bins=16, seed=2)
    with pytest.raises(AssertionError):  # control: another seed's statistic differs
        same(other.angles[0]["chi2"], ref["angles"][0]["chi2"])


def test_check_sampling_fails_a_negative_model_and_refuses_bad_sizes(specula):
    negative = specula.model("lobe: 2*c - 1.5")  # f < 0 off the peak: the check must fail
    assert not specula.check_sampling(negative, theta=[0], samples=10_000).passes
    with pytest.raises(ValueError, match="samples"):
        specula.check_sampling("ggx", theta=[0, 30], samples=20_000_000)
    with pytest.raises(ValueError, match="theta"):
        specula.check_sampling("ggx", theta=list(range(21)))
    with pytest.raises(ValueError):
        specula.check_sampling("ggx", theta=[95])


# --- lut ---

def test_lut_is_the_clis(specula):
    ref = cli("lut", "--model", "ggx", "--sweep", "alpha=0.1,0.5", "--mu", "0.25,0.5,1", "--average",
              "--format", "json")
    e, e_avg = specula.lut(specula.model("ggx"), mu=[0.25, 0.5, 1], sweep={"alpha": [0.1, 0.5]}, average=True)
    assert e.shape == (2, 3) and e_avg.shape == (2,)
    same(e.ravel(), column(ref, "E"))
    same(np.repeat(e_avg, 3), column(ref, "E_avg"))
    one = specula.lut(specula.model("ggx", alpha=0.5), mu=[0.25, 0.5, 1])
    same(one, e[1])  # the sweep's row is the model at that value
    with pytest.raises(AssertionError):
        same(one, e[0])  # control
    default = specula.lut("lambert")
    assert default.shape == (32,) and np.allclose(default, 1, atol=1e-8)  # Lambert reflects everything


def test_walk_is_the_clis(specula):
    ref = cli("walk", "--alpha", "0.7", "--theta", "40", "-f", "one", "-f", "schlick:f0=0.04", "--paths", "32768",
              "--format", "json")
    w = specula.walk(0.7, 40, fresnel=["one", "schlick:f0=0.04"], paths=32768)
    assert w["order"].shape == (2, 4) and w["total"].shape == (2,)
    same(w["order"][:, 0], column(ref, "order1"))
    same(w["total"], column(ref, "total"))
    same(w["multiple_se"], column(ref, "multiple_se"))
    assert abs(w["total"][0] - 1) < 3 * w["total_se"][0]  # F = 1 reflects everything
    glass = specula.walk(0.3, 60, dielectric=1.5, paths=32768)
    assert glass["total"].shape == (3,) and abs(glass["total"][2] - 1) < 3 * glass["total_se"][2] + 1e-10
    with pytest.raises(ValueError, match="f0"):
        specula.walk(0.5, 0, fresnel=["schlick:f0=2"], paths=32768)
    with pytest.raises(ValueError, match="theta"):
        specula.walk(0.5, 90, paths=32768)
    with pytest.raises(ValueError, match="paths"):
        specula.walk(0.5, 0, paths=10)
    with pytest.raises(ValueError, match="distribution"):
        specula.walk(0.5, 0, distribution="phong", paths=32768)


def test_lut_refuses_bad_grids(specula):
    assert "outside" in cli_error("lut", "--model", "ggx", "--mu", "0,1")
    with pytest.raises(ValueError, match="mu"):
        specula.lut("ggx", mu=[0, 1])
    with pytest.raises(ValueError, match="increase"):
        specula.lut("ggx", mu=[1, 0.5])
    with pytest.raises(ValueError, match="cells"):
        specula.lut("ggx", mu=np.linspace(0.01, 1, 1000), sweep={"alpha": np.linspace(0.05, 1, 100)})
    with pytest.raises(ValueError, match="sweep"):
        specula.lut("ggx", sweep=[0.1, 0.2])
    with pytest.raises(ValueError, match="alpha"):
        specula.lut("ggx", mu=[1], sweep={"alpha": [-1, 0.5]})


# --- render ---

def test_render_is_the_clis_image(specula, tmp_path):
    path = tmp_path / "ggx.exr"
    cli_text("render", "--model", "ggx", "-p", "alpha=0.2", "--size", "24x16", "--exr-pixel", "float", "-o", str(path))
    ref, channels = read_exr(path)
    assert channels == ["B", "G", "R"]
    image = specula.render(specula.model("ggx", alpha=0.2), size=(24, 16))
    assert image.shape == (16, 24, 3) and image.dtype == np.float32
    same(image, ref[:, :, ::-1])
    with pytest.raises(AssertionError):  # control: another roughness
        same(specula.render(specula.model("ggx", alpha=0.3), size=(24, 16)), ref[:, :, ::-1])


def test_the_white_furnace_shows_the_albedo(specula):
    m = specula.model("phong-normalized", n=20)
    image = specula.render(m, size=33, env="white", samples=4096)
    centre = image[16, 16]  # the sphere's normal faces the viewer there: ρ(θ ≈ 0)
    albedo = float(specula.albedo(m, [0])[0])
    assert np.all(np.abs(centre - albedo) < 0.03), (centre, albedo)
    assert np.all(image[0, 0] == 1)  # the background: the white environment itself
    dark = specula.render(specula.model("phong", n=20), size=33, env="white", samples=4096)
    assert np.all(np.abs(dark[16, 16] - albedo) > 0.3)  # control: the bare lobe reflects less


def test_render_lights_environments_and_bad_input(specula):
    lit = specula.render("lambert", size=8, lights=[{"direction": (0, 0, 1), "color": (1, 0, 0), "intensity": 2}],
                         diffuse=(1, 1, 1), ambient=(0, 0, 0))
    assert lit[4, 4, 0] > 0 and lit[4, 4, 1] == lit[4, 4, 2] == 0  # a red light alone
    env = np.ones((8, 16, 3))
    same(specula.render("lambert", size=9, env=env, samples=16, seed=3),
         specula.render("lambert", size=9, env=env, samples=16, seed=3))
    with pytest.raises(ValueError, match="size"):
        specula.render("ggx", size=0)
    with pytest.raises(ValueError, match="size"):
        specula.render("ggx", size=(10, 10, 10))
    with pytest.raises(ValueError, match="lights"):
        specula.render("ggx", lights=[{"direction": (0, 0, 0)}])
    with pytest.raises(ValueError, match="lights"):
        specula.render("ggx", lights=[{"dir": (0, 0, 1)}])
    with pytest.raises(TypeError):
        specula.render("ggx", lights="dir:0,0,1")
    with pytest.raises(ValueError, match="env"):
        specula.render("ggx", env=np.ones((4, 4)))
    with pytest.raises(ValueError):
        specula.render("ggx", env=np.full((4, 8, 3), np.nan))
    with pytest.raises(ValueError, match="samples"):
        specula.render("ggx", env="white", samples=0)
    with pytest.raises(ValueError):
        specula.render("ggx", mesh="/nonexistent.obj")


# --- fit ---

def test_fit_is_the_clis_and_its_formulas_compute(specula, tmp_path):
    # A small search, the same on each side: the search's sizes are options of both (the default's
    # enumeration of 20 000 forms was 9 s of each side's 10 s under the sanitizers).
    x = np.linspace(0.5, 3, 40)
    y = 2.5 * x * x + 1 / x
    data = tmp_path / "data.csv"
    data.write_text("x,y\n" + "".join(f"{a!r},{b!r}\n" for a, b in zip(x, y)))
    ref = cli("fit", "--data", str(data), "--target", "y", "--format", "json", "--generations", "4", "--threads", "1",
              "--time", "300", "--islands", "2", "--population", "50", "--enumerate-size", "7")
    r = specula.fit({"x": x}, y, generations=4, threads=1, time=300, islands=2, population=50, enumerate_size=7)
    assert [f.formula for f in r.front] == [e["formula"] for e in ref["front"]]
    same([f.train_error for f in r.front], [e["train_error"] for e in ref["front"]])
    assert r.best.formula == ref["chosen"]["formula"]
    # The formula called from Python against its own Python code (a second way to compute it).
    scope = {}
    exec(r.best.code("python", name="y").replace("import math", "import numpy as math"), scope)
    close(r.best(x), scope["fitted_y"](x), 1e-12)
    close(r.best(x.reshape(-1, 1)), r.best({"x": x}), 0)
    with pytest.raises(AssertionError):
        close(r.best(x), y * 1.01, 1e-3)  # control
    assert r.best.variables == ["x"] and str(r.best) == r.best.text


def test_fit_refuses_bad_data_and_options(specula):
    x = np.linspace(0, 1, 10)
    with pytest.raises(ValueError, match="rows"):
        specula.fit(x, x[:5])
    with pytest.raises(ValueError, match="max_size"):
        specula.fit(x, x, max_size=1000)
    with pytest.raises(ValueError):
        specula.fit(x, np.full(10, np.nan), time=1)
    with pytest.raises(ValueError):
        specula.fit(x, x, ops="+,%")
    with pytest.raises(ValueError, match="shape"):
        specula.fit(np.zeros((2, 2, 2)), x)
    with pytest.raises(ValueError):
        specula.fit(x, x, generations=1).best.code("fortran")


# --- design ---

def test_design_is_the_clis(specula, tmp_path):
    # The first five shapes, the fifth with laws in n (28 s a search under the sanitizers; all eight: 35 s).
    out = tmp_path / "front"
    cli_text("design", "--target", "phong", "--range", "n=1:100", "--ops", "fma,mul", "--max-cost", "2", "--no-timing",
             "--max-forms", "5", "--threads", "1", "-q", "--out", str(out))
    r = specula.design("phong", range=(1, 100), ops="fma,mul", max_cost=2, max_forms=5, measure_cost=False, threads=1)
    cli_csv = (out / "front.csv").read_text()
    assert r.csv == cli_csv
    assert r.toml == (out / "models.toml").read_text()
    assert [l["formula"] for l in r.front] == [row.split(",")[2] for row in cli_csv.splitlines()[1:len(r.front) + 1]]
    assert r.front and all(l["check"] for l in r.front)
    members = r.models()
    assert len(members) == len(r.front)
    close(members[0].lobe([0.5]), [0.5], 0)  # the first member is F = c
    wrong = cli_csv.replace("0.9", "0.8", 1)  # control: one digit off fails the comparison
    assert wrong != cli_csv and r.csv != wrong
    with pytest.raises(ValueError, match="max_cost"):
        specula.design("phong", max_cost=100)
    with pytest.raises(ValueError, match="target"):
        specula.design("ggx")


def test_design_takes_an_engine_term_with_its_own_range(specula):
    # schlick-weight has no parameter: no range is given, and the engines' exp2 form is a reference row.
    r = specula.design("schlick-weight", ops="fma,mul", max_cost=1, measure_cost=False, threads=1, time=30)
    ids = [l["id"] for l in r.references]
    assert ids == ["unreal-exp2", "exact"]
    assert abs(r.references[0]["max_abs"] - 0.00377) < 5e-5
    assert all(l["check"] == "-" for l in r.front)
    with pytest.raises(ValueError, match="range"):
        specula.design("expr: c^eta")  # a parameter without a range of its own
    # In half: each member's constants are half values and its error in half is reported.
    half = specula.design("schlick-weight", ops="fma,mul", max_cost=1, measure_cost=False, threads=1, time=30,
                          precision="half")
    line = half.front[-1]
    assert line["precision_error"] >= 0 and line["formula"] != r.front[-1]["formula"]
    numbers = re.findall(r"\d+\.\d+(?:e[-+]?\d+)?", line["formula"])
    assert numbers and all(float(np.float16(float(x))) == float(x) for x in numbers), line["formula"]
    with pytest.raises(ValueError, match="precision"):
        specula.design("schlick-weight", precision="quad")


def test_design_fits_several_outputs_together_and_bounds_their_error(specula):
    # "expr: c^2; c^3": one member formula in c and output, c² at output = 0 and c³ at output = 1,
    # checked here on a dense grid against the error it claims, which its certified bound covers.
    r = specula.design("expr: c^2; c^3", ops="fma,mul", max_cost=1, measure_cost=False, threads=1, time=30)
    c = np.linspace(1e-6, 1, 20001)
    for m in r.front:
        f = lambda output: eval(m["formula"].replace("^", "**"), {"__builtins__": {}}, {"c": c, "output": output})
        found = max(np.max(np.abs(f(0) - c ** 2)), np.max(np.abs(f(1) - c ** 3)))
        assert found <= m["max_abs"] * (1 + 1e-9) + 1e-12, m["formula"]
        assert m["max_abs_bound"] is None or m["max_abs_bound"] >= m["max_abs"]
    assert any(m["max_abs_bound"] is not None for m in r.front)
    with pytest.raises(ValueError, match="outputs"):
        specula.design("expr: c; c^2; c^3; c^4; c^5")


def test_complex_and_text_arrays_are_type_errors_not_silent_casts(specula):
    m = specula.model("ggx", alpha=0.3)
    for bad in [np.array([0.5 + 1j]), np.array(["0.5"]), [object()]]:
        with pytest.raises(TypeError, match="real numbers"):
            specula.model("log", n=20).lobe(bad)
        with pytest.raises(TypeError, match="real numbers"):
            specula.normalize("log", n=bad)
    with pytest.raises(TypeError, match="wi must be real"):
        m.sample(np.array([0, 0, 1 + 0j]), 0.5, 0.5)
    with pytest.raises(TypeError, match="l must be real"):
        m(np.array([0, 0, 1j]), [0, 0, 1])
    same(specula.model("log", n=20).lobe(np.array([True])), [1.0])  # booleans and integers are numbers
