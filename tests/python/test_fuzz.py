"""The binding's fuzz test: random kinds and shapes of argument through every function, one
argument at a time from a cheap valid call. Each call returns or raises ValueError or TypeError:
never another exception, a crash or a hang (pytest's process would die or time out)."""
import os
import pickle
import random
import subprocess
import sys
import tracemalloc

import numpy as np
import pytest

STRANGE = [None, "", "x", "lobe: c^", "ggx", 0, -1, 0.5, 2, 1e300, -1e300, float("nan"), float("inf"), True, 2**64,
           [], [1.0], [[0, 0, 1]], [0, 0, 1], {"alpha": [0.1]}, {"n": "x"}, object(), b"bytes",
           np.empty(0), np.empty((0, 3)), np.zeros((2, 2)), np.zeros((2, 3), dtype=np.float32),
           np.full(3, np.nan), np.arange(6.0).reshape(2, 3)[:, ::2], np.array(["a", "b"]), np.zeros((3, 4, 3)),
           np.array([1 + 2j]), np.ones(7, dtype=np.int8)]


def calls(specula):
    """Each function with a cheap valid call: (name, function, positional arguments, keywords)."""
    ggx = specula.model("ggx", alpha=0.3)
    log = specula.model("log", n=20)
    x = np.linspace(0.5, 2, 12)
    return [
        ("model", specula.model, ["log"], {"n": 20}),
        ("model form", specula.model, ["log"], {"form": "nh"}),
        ("model coef", specula.model, ["log"], {"coef": 2.0}),
        ("lobe", log.lobe, [np.linspace(0, 1, 5)], {"tier": "fast"}),
        ("call", ggx, [[0, 0, 1], [0, 0.6, 0.8]], {"n": [0, 0, 1]}),
        ("eval", ggx.eval, [[0, 0, 1], [0, 0.6, 0.8]], {}),
        ("sample", ggx.sample, [[0, 0, 1], 0.5, 0.5], {}),
        ("pdf", ggx.pdf, [[0, 0, 1], [0, 0.6, 0.8]], {}),
        ("normalize", specula.normalize, ["log", [1, 20]], {"method": "exact"}),
        ("albedo", specula.albedo, [ggx, [0, 60]], {"method": "monte-carlo", "samples": 1000}),
        ("error", specula.error, ["log"], {"reference": "phong", "n": [20], "zone": 0.5}),
        ("check", specula.check, [ggx], {"pairs": 10, "step": 30, "grazing": [89]}),
        ("check_sampling", specula.check_sampling, [ggx], {"theta": [30], "samples": 1000, "bins": 4}),
        ("lut", specula.lut, [ggx], {"mu": [0.5, 1], "sweep": {"alpha": [0.2, 0.4]}, "average": False}),
        ("render", specula.render, [ggx], {"size": 4, "env": "white", "samples": 2, "seed": 1}),
        ("render lights", specula.render, [ggx], {"size": 4, "lights": [{"direction": (0, 0, 1)}]}),
        ("glsl", specula.glsl, [ggx], {"dialect": "webgl2"}),
        ("export", specula.export, [ggx, "hlsl"], {}),
        ("load_models", specula.load_models, ["[[model]]\nid = 'm'\nname = 'm'\nkind = 'lobe'\nform = 'rv'\nlobe = 'c'\nnormalization = 'none'\n"], {}),
        ("fit", specula.fit, [x, x * x], {"generations": 1, "time": 1, "threads": 1, "max_size": 5, "ops": "+,*"}),
        ("design", specula.design, ["phong"], {"range": (1, 10), "ops": "mul", "max_cost": 1, "measure_cost": False,
                                               "threads": 1, "time": 5}),
    ]


def fuzz(cases, rng):
    """Each case's call with each argument replaced by strange values in turn: (calls tried, the
    calls that raised something other than ValueError or TypeError)."""
    tried, failures = 0, []
    for name, function, args, kwargs in cases:
        function(*args, **kwargs)  # the baseline holds
        slots = [("arg", i) for i in range(len(args))] + [("kw", k) for k in kwargs]
        for kind, slot in slots:
            for value in rng.sample(STRANGE, 12):
                if name == "design" and slot == "time" and isinstance(value, (int, float)):
                    continue  # a valid time up to 1e300 s is a budget, not bad input
                a, kw = list(args), dict(kwargs)
                if kind == "arg":
                    a[slot] = value
                else:
                    kw[slot] = value
                tried += 1
                try:
                    function(*a, **kw)
                except (ValueError, TypeError):
                    pass
                except Exception as e:  # noqa: BLE001 - anything else is a finding
                    failures.append(f"{name}({kind} {slot} = {value!r}): {type(e).__name__}: {e}")
    return tried, failures


def test_every_function_takes_any_argument_without_crashing(specula):
    tried, failures = fuzz(calls(specula), random.Random(20261203))
    assert tried > 400
    assert not failures, "\n".join(failures)


def test_the_fuzz_test_reports_an_unexpected_exception():
    """The control: a function that raises RuntimeError for a string is reported; one that raises
    TypeError for it is not."""
    def fragile(x=1):
        if isinstance(x, str):
            raise RuntimeError("boom")

    def sound(x=1):
        if isinstance(x, str):
            raise TypeError("x must be a number")
    tried, failures = fuzz([("fragile", fragile, [], {"x": 1})] * 4, random.Random(3))
    assert tried == 48 and any("RuntimeError: boom" in f for f in failures)
    assert fuzz([("sound", sound, [], {"x": 1})] * 4, random.Random(3)) == (48, [])


# --- What a hostile caller finds beyond bad arguments: pickling at every protocol, instances made
# without a constructor, Ctrl-C in long array calls, huge broadcasts. A crash must fail the test,
# not kill pytest: those run in a Python of their own.

def run_child(code, *args, timeout=300):
    """`code` run by a Python of its own with `args` (an abort or a segfault there fails the test
    instead of killing pytest): its standard output's lines, once it exited with 0."""
    path = os.pathsep.join(os.path.abspath(p) for p in os.environ["PYTHONPATH"].split(os.pathsep))
    env = dict(os.environ, PYTHONPATH=path)
    done = subprocess.run([sys.executable, "-c", code, *map(str, args)], capture_output=True, text=True,
                          timeout=timeout, env=env)
    assert done.returncode == 0, f"exit {done.returncode}:\n{done.stdout}\n{done.stderr[-3000:]}"
    return done.stdout.splitlines()


def test_a_child_that_crashes_fails_the_test():  # the control of the tests below
    with pytest.raises(AssertionError, match="exit -6"):
        run_child("import os; print('started'); os.abort()")
    assert run_child("import sys; print(sys.argv[1:])", 1, "x") == ["['1', 'x']"]


BOUND_CLASSES = r'''
import specula, specula._specula as bound
classes = sorted(name for name, value in vars(bound).items()
                 if isinstance(value, type) and type(value).__name__ == "pybind11_type")
'''

PICKLING = BOUND_CLASSES + r'''
import pickle
import numpy as np
x = np.linspace(1, 2, 8)
fit = specula.fit(x, x * x, generations=1, time=5, threads=1, max_size=5, ops="+,*")
instances = {"CheckResult": specula.check("ggx", pairs=10, step=30, grazing=[89]), "FitResult": fit,
             "Formula": fit.best}
models = [specula.model("log", n=7), specula.model("lobe: c^n", n=3, form="nh"), specula.model("ggx+ms", alpha=0.4),
          specula.model("phong", n=2, coef=3.0)]
print("classes", *classes)
for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
    for m in models:
        back = pickle.loads(pickle.dumps(m, protocol=protocol))
        same = repr(back) == repr(m) and np.array_equal(back([0, 0, 1], [0.6, 0, 0.8]), m([0, 0, 1], [0.6, 0, 0.8]))
        print(protocol, "Model", "round trip" if same else f"differs: {back!r}")
    for name, value in instances.items():
        try:
            pickle.dumps(value, protocol=protocol)
            print(protocol, name, "pickled")
        except TypeError as e:
            print(protocol, name, "refused" if "cannot pickle" in str(e) else e)
'''


def test_every_bound_class_pickles_or_refuses_at_every_protocol():
    """A Model pickles and comes back the same at protocols 0 to 5 (0 and 1 aborted the interpreter
    in copyreg); the result classes refuse with TypeError at every protocol, as Python does at 2."""
    lines = run_child(PICKLING)
    assert lines[0] == "classes CheckResult FitResult Formula Model", lines[0]  # a new class needs its line here
    protocols = range(pickle.HIGHEST_PROTOCOL + 1)
    expected = [f"{p} Model round trip" for p in protocols for _ in range(4)]
    expected += [f"{p} {name} refused" for p in protocols for name in ("CheckResult", "FitResult", "Formula")]
    assert sorted(lines[1:]) == sorted(expected)


UNINITIALISED = BOUND_CLASSES + r'''
import copy, pickle
import numpy as np
z = np.array([[0.0, 0.0, 1.0]])
# Each method a class defines (its own __dict__), called with good arguments: a new method needs a line here.
METHODS = {
    "Model": {"lobe": ([1.0],), "eval": ([0, 0, 1], [0, 0, 1]), "__call__": ([0, 0, 1], [0, 0, 1]),
              "sample": ([0, 0, 1], 0.5, 0.5), "pdf": ([0, 0, 1], [0, 0, 1]),
              "_directions": (z, z, None, "exact", None), "_sample": (z, np.array([0.5]), np.array([0.5])),
              "_pdf": (z, z), "__repr__": (), "__getstate__": (), "__reduce__": ()},
    "CheckResult": {"__bool__": (), "__repr__": (), "__reduce__": ()},
    "Formula": {"code": ("cpp",), "__call__": (np.ones(3),), "_evaluate": ([np.ones(3)],), "__str__": (),
                "__repr__": (), "__reduce__": ()},
    "FitResult": {"__repr__": (), "__reduce__": ()},
}
# The functions that take a model, each with good arguments but the model.
FUNCTIONS = {"check": {"pairs": 10}, "glsl": {}, "export": {"format": "hlsl"}, "normalize": {"n": [1]},
             "albedo": {"theta": [0]}, "error": {}, "lut": {"mu": [1.0]}, "render": {"size": 2},
             "check_sampling": {"theta": [0], "samples": 10}}

def outcome(use):
    try:
        use()
    except TypeError as e:
        return None if "without a constructor" in str(e) or "cannot pickle" in str(e) else f"TypeError: {e}"
    except Exception as e:
        return f"{type(e).__name__}: {e}"
    return "no error"

def uses(cls, obj):
    """(what, use) for every use of an instance: its properties, its methods, str, pickling, copying."""
    for name in dir(cls):
        if isinstance(getattr(cls, name), property):
            yield name, lambda name=name: getattr(obj, name)
    for name, value in vars(cls).items():
        # __init__ is pybind11's "No constructor defined!"; __setstate__ is how pickle makes one.
        if callable(value) and name not in ("__init__", "__setstate__"):
            args = METHODS[cls.__name__][name]
            yield name, lambda name=name, args=args: getattr(obj, name)(*args)
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        yield f"pickle protocol {protocol}", lambda protocol=protocol: pickle.dumps(obj, protocol=protocol)
    yield "str", lambda: str(obj)
    yield "copy", lambda: copy.copy(obj)
    yield "deepcopy", lambda: copy.deepcopy(obj)

checked = 0
for cls in (getattr(bound, name) for name in classes):
    obj = cls.__new__(cls)
    for what, use in uses(cls, obj):
        checked += 1
        if (found := outcome(use)) is not None:
            print(f"{cls.__name__} {what}: {found}")
model = specula.Model.__new__(specula.Model)
for name, kwargs in FUNCTIONS.items():
    checked += 1
    if (found := outcome(lambda: getattr(specula, name)(model, **kwargs))) is not None:
        print(f"specula.{name}(uninitialised model): {found}")
print("checked", checked)
'''


def test_an_instance_made_without_a_constructor_raises_type_error():
    """cls.__new__(cls) makes an instance whose C++ object pybind11 never constructed: every use of
    it (properties, methods, str, pickling, copying, as a model argument) is TypeError, for every
    bound class (was a segfault, a bus error or uninitialised memory read as numbers)."""
    lines = run_child(UNINITIALISED)
    assert lines[-1].startswith("checked ") and int(lines[-1].split()[1]) > 60, lines
    assert lines[:-1] == []


CTRL_C = r'''
import os, signal, sys, threading, time
import numpy as np
import specula

lobe = "c"
for _ in range(250):
    lobe = f"({lobe})^c"
m = specula.model("lobe: " + lobe)  # microseconds a value: a long call needs few values

def call(count):
    """The call asked for over about `count` values: (function, arguments, values), the arrays made
    beforehand."""
    side = int(np.ceil(np.sqrt(count)))
    u = np.random.default_rng(1).random((side, side))
    if sys.argv[1] == "lobe":
        return m.lobe, [u.astype(np.float32).reshape(-1)], u.size
    if sys.argv[1] == "call":  # (side, 1, 3) against (1, side, 3): side² directions
        return m, [np.array([0, 0.6, 0.8]) + 0 * u[:, :1, None], np.array([0, 0, 1.0]) + 0 * u[:1, :, None]], u.size
    return m.sample, [[0, 0.6, 0.8], u[:, :1], u[:1, :]], u.size

function, args, _ = call(10)
function(*args)  # the sampler's tables are built at the first call
function, args, values = call(32768)  # enough for every thread
start = time.perf_counter()
function(*args)
per_value = (time.perf_counter() - start) / values
function, args, _ = call(int(6 / per_value))  # six seconds of work in one call: over 5 s undivided
threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()
start = time.monotonic()
try:
    function(*args)
    print("finished", time.monotonic() - start)
except KeyboardInterrupt:
    print("interrupted", time.monotonic() - start - 0.5)
'''


@pytest.mark.parametrize("call", ["lobe", "call", "sample"])
def test_ctrl_c_stops_a_long_array_call(call):
    """Ctrl-C half a second into an array call of six seconds (sized by this machine's speed, so
    under the sanitizers too) raises KeyboardInterrupt within one chunk's work, not at the end."""
    [line] = run_child(CTRL_C, call)
    outcome, seconds = line.split()
    assert outcome == "interrupted" and float(seconds) < 1.0, line


def test_a_huge_broadcast_is_a_value_error_before_any_allocation(specula):
    """10⁵ × 10⁵ directions (224 GiB of results) are refused by their count against the documented
    cap, naming the shapes, instead of NumPy's MemoryError after trying to allocate them."""
    ggx = specula.model("ggx")
    rows, columns = np.zeros((10**5, 1, 3)), np.zeros((1, 10**5, 3))
    huge = [lambda: ggx(rows, columns), lambda: ggx.eval(rows, columns, out=np.empty(0)),
            lambda: ggx.sample(rows, np.zeros((1, 10**5)), 0.5), lambda: ggx.pdf(rows, columns)]
    for call in huge:
        with pytest.raises(ValueError, match=r"shapes \(100000, 1\), .*broadcast to shape \(100000, 100000\): "
                                             r"10000000000 directions, more than the 268435456"):
            call()
    assert specula.MAX_BROADCAST == 2**28


def peak_bytes(call):
    """The most memory NumPy and Python held at once during `call` beyond what they held before."""
    tracemalloc.start()
    try:
        call()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_broadcast_inputs_are_read_in_place_not_copied(specula):
    """A call's memory is its results: inputs of the broadcast shape, and those broadcast to it
    (the usual single direction against many), are read where they lie (a copy of a light of
    shape (3,) to (N, 3) took 24 bytes a direction)."""
    ggx = specula.model("ggx", alpha=0.3)
    n = 2**20
    v = np.random.default_rng(1).normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2])
    v /= np.linalg.norm(v, axis=1)[:, None]
    light = np.array([0, 0.6, 0.8])
    lights = np.ascontiguousarray(np.broadcast_to(light, v.shape))
    u = np.random.default_rng(2).random(n)
    results = {"same shapes": (lambda: ggx(lights, v), 8 * n),
               "a light against many views": (lambda: ggx(light, v), 8 * n),
               "strided views": (lambda: ggx(light, v[::2]), 4 * n),
               "sample": (lambda: ggx.sample(light, u, 0.5), 40 * n),
               "pdf": (lambda: ggx.pdf(light, v), 8 * n),
               "lobe, strided": (lambda: specula.model("log").lobe(u[::2]), 4 * n)}
    for name, (call, result) in results.items():
        assert result <= peak_bytes(call) < result + n, name  # well under a byte a direction beyond the results
    copy = peak_bytes(lambda: np.ascontiguousarray(np.broadcast_to(light, v.shape)))
    assert copy >= 24 * n  # the control: a copy shows
