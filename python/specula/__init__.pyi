# Type stubs of specula (docs/python.md). ArrayLike: anything numpy.asarray takes.
from typing import Any, Literal, Sequence, overload

import numpy as np
import numpy.typing as npt

Tier = Literal["exact", "fast"]

class CheckResult:
    albedo_normal: float
    max_albedo: float
    max_albedo_theta: float
    max_asymmetry: float
    pairs: int
    min_value: float
    conserves_energy: bool
    reciprocal: bool
    non_negative: bool
    all_hold: bool
    def __bool__(self) -> bool: ...

class Model:
    id: str
    kind: Literal["lobe", "brdf"]
    is_lobe: bool
    form: Literal["rv", "nh"] | None
    coef: float | None
    params: dict[str, float]
    info: dict[str, Any]
    @overload
    def lobe(self, c: npt.NDArray[np.float32], tier: Tier = ...,  # type: ignore[misc]
             out: npt.NDArray[np.float32] | None = ...) -> npt.NDArray[np.float32]: ...
    @overload
    def lobe(self, c: npt.ArrayLike, tier: Tier = ...,
             out: npt.NDArray[np.float64] | None = ...) -> npt.NDArray[np.float64]: ...
    def __call__(self, l: npt.ArrayLike, v: npt.ArrayLike, n: npt.ArrayLike | None = ...,
                 tier: Tier = ...) -> npt.NDArray[np.float64]: ...
    def eval(self, wi: npt.ArrayLike, wo: npt.ArrayLike, tier: Tier = ...) -> npt.NDArray[np.float64]: ...

ModelLike = Model | str

def models() -> list[dict[str, Any]]: ...
def model(id: str, *, form: Literal["rv", "nh"] | None = ..., coef: float | None = ..., **params: float) -> Model: ...
def load_models(path_or_toml: str) -> list[str]: ...
def normalize(model: ModelLike, n: npt.ArrayLike,
              method: Literal["auto", "exact", "quadrature"] = ...) -> npt.NDArray[np.float64]: ...
def albedo(model: ModelLike, theta: npt.ArrayLike, method: Literal["cubature", "monte-carlo"] = ...,
           samples: int = ..., seed: int = ...) -> npt.NDArray[np.float64]: ...
def error(model: ModelLike, reference: str = ..., n: npt.ArrayLike = ...,
          zone: float = ...) -> dict[str, npt.NDArray[np.float64]]: ...
def check(model: ModelLike, pairs: int = ..., seed: int = ..., step: float = ...,
          grazing: Sequence[float] = ...) -> CheckResult: ...
def glsl(model: ModelLike, dialect: Literal["glsl330", "gles300", "webgl2"] = ...) -> str: ...
def export(model: ModelLike, format: Literal["hlsl", "msl", "brdf", "cpp"]) -> str: ...
