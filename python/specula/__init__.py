"""specula from Python: fast, energy-conserving specular lobes over NumPy arrays (docs/python.md).

>>> import specula
>>> m = specula.model("log-normalized", n=20)
>>> m.lobe([1.0, 0.99])            # F(c), the bare lobe, through the SIMD batch path
array([1.        , 0.81631928])
>>> specula.normalize("log", n=[1, 20])
array([0.48274948, 4.19275612])
"""
import math

import numpy as np

from ._specula import (CheckResult, FitResult, Formula, Model, albedo, check, clear_models, error, export, glsl,
                       load_models, lut, model, models, normalize, render, walk)
from ._specula import _check_sampling, _design, _fit

__all__ = ["CheckResult", "DesignResult", "FitResult", "Formula", "Model", "albedo", "check", "check_sampling", "clear_models",
           "design", "error", "export", "fit", "glsl", "load_models", "lut", "model", "models", "normalize", "walk",
           "render", "SamplingCheck"]


def _real(name, x):
    """x as a float64 array; TypeError for complex numbers, strings or objects."""
    a = np.asarray(x)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{name} must be real numbers, got an array of {a.dtype}")
    return a.astype(np.float64, copy=False)


def _as_vectors(name, x):
    a = _real(name, x)
    if a.ndim == 0 or a.shape[-1] != 3:
        raise ValueError(f"{name} must be an array of 3-vectors, shape (..., 3), got shape {a.shape}")
    return a


MAX_BROADCAST = 2**28
"""The most directions (elements of the broadcast shape) one call of a model, sample() or pdf()
takes: its results stay within 2 GiB (a model's values) to 10 GiB (sample's)."""


def _broadcast(named):
    """The arrays of `named` ((name, array, is_vector) triples) broadcast to one shape: (shape,
    views), read-only views of that shape (+ (3,) for vectors) that copy nothing. ValueError when
    they do not broadcast, or broadcast to more than MAX_BROADCAST directions."""
    shapes = [a.shape[:-1] if vector else a.shape for _, a, vector in named]
    names, listed = ", ".join(n for n, _, _ in named), ", ".join(str(s) for s in shapes)
    try:
        shape = np.broadcast_shapes(*shapes)
    except ValueError:
        raise ValueError(f"{names} must broadcast to one shape, got shapes {listed}") from None
    if math.prod(shape) > MAX_BROADCAST:
        raise ValueError(f"{names} of shapes {listed} broadcast to shape {shape}: {math.prod(shape)} directions, "
                         f"more than the {MAX_BROADCAST} (MAX_BROADCAST) a call takes")
    return shape, [np.broadcast_to(a, shape + ((3,) if vector else ())) for _, a, vector in named]


def _call(self, l, v, n=None, tier="exact", out=None):
    """f(N, L, V) over arrays of unit directions of shape (..., 3), broadcast against each other:
    l toward the light, v toward the viewer, n the normal (default +z, the local frame), at most
    MAX_BROADCAST directions. Returns an array of the broadcast shape without the last axis (or
    fills `out`, a C-contiguous float64 array of that shape). tier: 'exact' or 'fast'.

    >>> specula.model("lambert")([0, 0, 1], [[0, 0, 1], [0.6, 0, 0.8]])
    array([0.31830989, 0.31830989])
    """
    named = [("l", l), ("v", v)] + ([] if n is None else [("n", n)])
    shape, views = _broadcast([(name, _as_vectors(name, x), True) for name, x in named])
    if out is not None:
        if not isinstance(out, np.ndarray) or out.dtype != np.float64:
            raise TypeError("out must be a float64 array")
        if out.shape != shape or not out.flags.c_contiguous or not out.flags.writeable:
            raise ValueError(f"out must be a writable C-contiguous array of shape {shape}, got {out.shape}")
    values = self._directions(views[0], views[1], views[2] if n is not None else None, tier,
                              None if out is None else out.reshape(-1))
    return values.reshape(shape) if out is None else out


def _eval(self, wi, wo, tier="exact", out=None):
    """f(wi, wo) in the local frame (N = +z): wi toward the light, wo toward the viewer, arrays of
    shape (..., 3). The same as model(wi, wo)."""
    return _call(self, wi, wo, None, tier, out)


Model.__call__ = _call
Model.eval = _eval


def _sample(self, wi, u1, u2):
    """Importance samples ω_o for ω_i from two uniform numbers in [0, 1) each (docs/sampling.md):
    wi of shape (..., 3) toward the light (normalized here), u1 and u2 broadcast against it.
    Returns (wo, pdf, weight): wo (..., 3), its density per solid angle and f·cos θ_o / pdf. A draw
    that leaves the hemisphere, or a wi at or below the horizon, is pdf = weight = 0 ("no sample").

    >>> m = specula.model("lambert")                   # cosine-weighted: weight = ρ = 1
    >>> wo, pdf, weight = m.sample([0, 0, 1], [0.5, 0.25], [0.5, 0.5])
    >>> weight.round(6), wo.shape
    (array([1., 1.]), (2, 3))
    """
    shape, (wi, u1, u2) = _broadcast([("wi", _as_vectors("wi", wi), True),
                                      ("u1", _real("u1", u1), False),
                                      ("u2", _real("u2", u2), False)])
    wo, pdf, weight = self._sample(wi, u1, u2)
    return wo.reshape(shape + (3,)), pdf.reshape(shape), weight.reshape(shape)


def _pdf(self, wi, wo):
    """The density, per solid angle, that sample() draws wo with for wi: arrays of shape (..., 3)
    (normalized here), broadcast against each other; 0 below the horizon.

    >>> specula.model("lambert").pdf([0, 0, 1], [0, 0, 1]).round(6)   # cos θ_o / π
    0.31831
    """
    shape, (a, b) = _broadcast([("wi", _as_vectors("wi", wi), True), ("wo", _as_vectors("wo", wo), True)])
    return self._pdf(a, b).reshape(shape)[()]


Model.sample = _sample
Model.pdf = _pdf


class SamplingCheck:
    """What check_sampling finds (specula check --sampling): passes (every angle passes; also
    bool(check)), method (how the model is sampled), table_error (a tabulated sampler's L1 error)
    and angles: a dict per angle with the CLI's JSON keys (theta_deg, samples, chi2, dof, p_value,
    alpha, pdf_integral, mean_weight, standard_error, albedo, max_weight, outside, …, passes) and
    the grid's observed and expected counts, bins cells in cos θ_o by 2·bins in φ_o."""

    def __init__(self, fields):
        self.passes, self.method, self.table_error = fields["passes"], fields["method"], fields["table_error"]
        self.bins, self.angles = fields["bins"], fields["angles"]

    def __bool__(self):
        return self.passes

    def __repr__(self):
        worst = min((a["p_value"] for a in self.angles), default=float("nan"))
        return f"SamplingCheck(passes={self.passes}, method={self.method!r}, least p = {worst:.3g})"


def check_sampling(model, theta=(0, 30, 60, 80, 89), samples=1_000_000, seed=1, bins=32, alpha=0.01):
    """The χ² proof of the model's importance sampler at each incidence angle in degrees (specula
    check --sampling, docs/sampling.md): `samples` draws per angle (at most 3e7 over all angles),
    binned on a grid of `bins` cells in cos θ_o by 2·bins in φ_o against the density integrated by
    cubature (Šidák-corrected level alpha), with the weights, the coverage, ∫pdf ≤ 1 and the mean
    weight against the albedo. Returns a SamplingCheck; Ctrl-C stops it.

    >>> specula.check_sampling(specula.model("ggx", alpha=0.2), theta=[30], samples=100_000).passes
    True
    """
    return SamplingCheck(_check_sampling(model, theta, samples, seed, bins, alpha))


def _columns(X, variables=None):
    """X as named columns: a dict {name: column}, a 1-D array (one variable, x) or a 2-D array of
    rows (variables x0, x1, … unless named)."""
    if isinstance(X, dict):
        names = list(X)
        columns = [_real(n, X[n]) for n in names]
        if variables is not None and list(variables) != names:
            raise ValueError("variables must be omitted when X is a dict: its keys name the variables")
    else:
        a = _real("X", X)
        if a.ndim == 1:
            columns = [a]
        elif a.ndim == 2:
            columns = [a[:, j] for j in range(a.shape[1])]
        else:
            raise ValueError(f"X must be a 1-D array, a 2-D array of rows or a dict of columns, got shape {a.shape}")
        names = (["x"] if a.ndim == 1 else [f"x{j}" for j in range(a.shape[1])]) if variables is None else list(variables)
        if len(names) != len(columns):
            raise ValueError(f"variables names {len(names)} variables for {len(columns)} columns of X")
    for n, c in zip(names, columns):
        if c.ndim != 1:
            raise ValueError(f"variable {n} must be a 1-D column, got shape {c.shape}")
    return names, columns


def fit(X, y, *, variables=None, ops="+,*,/", constants="fitted", max_size=25, size_weights="default",
        metric="rms", test_fraction=0.0, split="random", seed=1, time=60.0, generations=None,
        evaluations=None, target_error=None, threads=0, islands=4, population=200, enumerate_size=11,
        choose="parsimonious", choose_factor=1.5, snap=True, starts=()):
    """Symbolic regression (specula fit, docs/fit.md): formulas y ≈ f(X) over the operators `ops`,
    their constants fitted for `metric`, as a Pareto front of size against error. X: a dict of
    columns, a 1-D array (the variable x) or a 2-D array of rows (x0, x1, …, or `variables`).
    Deterministic for a seed and a budget of generations or evaluations; `time` (seconds) bounds
    it too. Every option is the CLI's, with the CLI's ranges.

    >>> x = np.linspace(1, 4, 30)
    >>> r = specula.fit(x, 3 * x * x + 2, time=60, generations=2)
    >>> r.best.size, r.best.train_error < 1e-12, float(r.best(np.array([2.0]))[0])
    (7, True, 14.0)
    """
    names, columns = _columns(X, variables)
    target = _real("y", y)
    if target.ndim != 1:
        raise ValueError(f"y must be a 1-D array, got shape {target.shape}")
    for n, c in zip(names, columns):
        if c.shape != target.shape:
            raise ValueError(f"variable {n} has {c.shape[0]} rows, y has {target.shape[0]}")
    options = dict(ops=ops, constants=constants, max_size=max_size, size_weights=size_weights, metric=metric,
                   test_fraction=test_fraction, split=split, seed=seed, time=time, generations=generations,
                   evaluations=evaluations, target_error=target_error, threads=threads, islands=islands,
                   population=population, enumerate_size=enumerate_size, choose=choose,
                   choose_factor=choose_factor, snap=snap, starts=list(starts))
    return _fit(names, [c.tolist() for c in columns], target.tolist(), options)


def _formula_call(self, X):
    """The formula on data laid out as fit's X (a dict, a 1-D or a 2-D array): an array of rows."""
    names, columns = _columns(X, None if isinstance(X, dict) else self.variables)
    if isinstance(X, dict):
        missing = [v for v in self.variables if v not in X]
        if missing:
            raise ValueError("X lacks the variables " + ", ".join(missing))
        columns = [_real(v, X[v]) for v in self.variables]
    return self._evaluate([np.ascontiguousarray(c) for c in columns])


Formula.__call__ = _formula_call


class DesignResult:
    """A lobe designer's run (specula design, docs/designer.md): the Pareto front of cost against
    error (front, cheapest first: dicts with id, formula, shape, max_abs, argmax_c, argmax_param,
    max_rel, ops, model_cost, ns_per_eval, timing, spirv_instructions, k, k_formula, check), the
    target's usual approximations measured beside them (references), the members kept off the
    front because their normalized twin fails specula check (refused, its check saying why), and
    the files specula design
    writes, as text: toml (models.toml: every member bare and normalized, for load_models), csv
    (front.csv), json (design.json) and table."""

    def __init__(self, fields):
        self.front = fields["front"]
        self.references = fields["references"]
        self.refused = fields["refused"]
        self.toml, self.csv, self.json, self.table = fields["toml"], fields["csv"], fields["json"], fields["table"]
        self.forms_screened, self.forms_total = fields["forms_screened"], fields["forms_total"]
        self.seconds, self.cancelled, self.cost_note = fields["seconds"], fields["cancelled"], fields["cost_note"]

    def models(self):
        """Loads the members (toml) and returns each normalized one as a Model."""
        return [model(i) for i in load_models(self.toml) if i.endswith("-normalized")]

    def __repr__(self):
        return f"DesignResult({len(self.front)} lobes on the front, {len(self.references)} references)"


def design(target="phong", *, vars=None, params=None, form=None, param=None, range=None, objective="max-abs", zone=0.5,
           ops="all", max_cost=6, max_forms=None, time=540.0, seed=1, threads=0, measure_cost=True, precision="double"):
    """The lobe designer (specula design, docs/designer.md): searches cheap lobe shapes against the
    target over `range` of its parameter `param` (both None: the target's own, n = (1, 1000) for a
    lobe), fits them for `objective` ('max-abs',
    'max-rel' or 'both'), normalizes, checks and times them, and returns the Pareto front as a
    DesignResult. The target is a lobe, a function of c ("expr: (1 - c)^5") or an engine term
    ("fresnel-dielectric", "fresnel-conductor", "schlick-weight", "smith-g2-ggx", "smith-g2-beckmann", "env-brdf-a-ggx", …); vars: a function
    target's per-pixel variables (default c, or the term's: ["NoV", "NoL"]). ops: the operations allowed ('fma,mul,max', …, or 'all'); max_cost: the cost
    model's budget, [1, 24]; max_forms: at most this many shapes (a deterministic budget);
    precision: 'double', 'float' or 'half', the members' constants and arithmetic as a shader has them.

    >>> r = specula.design("phong", range=(1, 100), ops="mul", max_cost=1, measure_cost=False, time=60)
    >>> [lobe["formula"] for lobe in r.front]
    ['c', 'c ^ 2']
    """
    return DesignResult(_design(dict(target=target, vars=None if vars is None else list(vars), params=dict(params if params is not None else {}), form=form, param=param, range=range,
                                      objective=objective, zone=zone, ops=ops, max_cost=max_cost,
                                      max_forms=max_forms, time=time, seed=seed, threads=threads,
                                      measure_cost=measure_cost, precision=precision)))
