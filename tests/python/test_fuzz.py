"""The binding's fuzz test: random kinds and shapes of argument through every function, one
argument at a time from a cheap valid call. Each call returns or raises ValueError or TypeError:
never another exception, a crash or a hang (pytest's process would die or time out)."""
import random

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
