"""specula from Python: fast, energy-conserving specular lobes over NumPy arrays (docs/python.md).

>>> import specula
>>> m = specula.model("log-normalized", n=20)
>>> m.lobe([1.0, 0.99])            # F(c), the bare lobe, through the SIMD batch path
array([1.        , 0.81631928])
>>> specula.normalize("log", n=[1, 20])
array([0.48274948, 4.19275612])
"""
import numpy as np

from ._specula import (CheckResult, Model, albedo, check, error, export, glsl, load_models, model,
                       models, normalize)

__all__ = ["CheckResult", "Model", "albedo", "check", "error", "export", "glsl", "load_models", "model",
           "models", "normalize"]


def _as_vectors(name, x):
    a = np.asarray(x, dtype=np.float64)
    if a.ndim == 0 or a.shape[-1] != 3:
        raise ValueError(f"{name} must be an array of 3-vectors, shape (..., 3), got shape {a.shape}")
    return a


def _call(self, l, v, n=None, tier="exact"):
    """f(N, L, V) over arrays of unit directions of shape (..., 3), broadcast against each other:
    l toward the light, v toward the viewer, n the normal (default +z, the local frame). Returns
    an array of the broadcast shape without the last axis. tier: 'exact' or 'fast'.

    >>> specula.model("lambert")([0, 0, 1], [[0, 0, 1], [0.6, 0, 0.8]])
    array([0.31830989, 0.31830989])
    """
    vectors = [_as_vectors("l", l), _as_vectors("v", v)] + ([] if n is None else [_as_vectors("n", n)])
    try:
        shape = np.broadcast_shapes(*(a.shape[:-1] for a in vectors))
    except ValueError:
        raise ValueError("l, v and n must broadcast to one shape (..., 3), got shapes "
                         + ", ".join(str(a.shape) for a in vectors)) from None
    flat = [np.ascontiguousarray(np.broadcast_to(a, shape + (3,))).reshape(-1, 3) for a in vectors]
    values = self._directions(flat[0], flat[1], flat[2] if n is not None else None, tier)
    return values.reshape(shape)


def _eval(self, wi, wo, tier="exact"):
    """f(wi, wo) in the local frame (N = +z): wi toward the light, wo toward the viewer, arrays of
    shape (..., 3). The same as model(wi, wo)."""
    return _call(self, wi, wo, None, tier)


Model.__call__ = _call
Model.eval = _eval
