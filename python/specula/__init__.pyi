# Type stubs of specula (docs/python.md). ArrayLike: anything numpy.asarray takes.
from typing import Any, Literal, Sequence, overload

import numpy as np
import numpy.typing as npt

Tier = Literal["exact", "fast"]

MAX_BROADCAST: int

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
                 tier: Tier = ..., out: npt.NDArray[np.float64] | None = ...) -> npt.NDArray[np.float64]: ...
    def eval(self, wi: npt.ArrayLike, wo: npt.ArrayLike, tier: Tier = ...,
             out: npt.NDArray[np.float64] | None = ...) -> npt.NDArray[np.float64]: ...
    def sample(self, wi: npt.ArrayLike, u1: npt.ArrayLike, u2: npt.ArrayLike) -> tuple[
        npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def pdf(self, wi: npt.ArrayLike, wo: npt.ArrayLike) -> Any: ...

class SamplingCheck:
    passes: bool
    method: str
    table_error: float
    bins: int
    angles: list[dict[str, Any]]
    def __bool__(self) -> bool: ...

class Formula:
    formula: str
    text: str
    variables: list[str]
    size: int
    train_error: float
    test_error: float | None
    def __call__(self, X: npt.ArrayLike | dict[str, npt.ArrayLike]) -> npt.NDArray[np.float64]: ...
    def code(self, language: Literal["cpp", "glsl", "latex", "python"], name: str = ...) -> str: ...

class FitResult:
    front: list[Formula]
    chosen: int
    best: Formula
    evaluations: int
    generations: int
    seconds: float
    stopped_by: str

class DesignResult:
    front: list[dict[str, Any]]
    references: list[dict[str, Any]]
    refused: list[dict[str, Any]]
    toml: str
    csv: str
    json: str
    table: str
    forms_screened: int
    forms_total: int
    seconds: float
    cancelled: bool
    cost_note: str
    def models(self) -> list[Model]: ...

ModelLike = Model | str

def models() -> list[dict[str, Any]]: ...
def model(id: str, *, form: Literal["rv", "nh"] | None = ..., coef: float | None = ..., **params: float) -> Model: ...
def load_models(path_or_toml: str) -> list[str]: ...
def clear_models() -> None: ...
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
def check_sampling(model: ModelLike, theta: npt.ArrayLike = ..., samples: int = ..., seed: int = ..., bins: int = ...,
                   alpha: float = ...) -> SamplingCheck: ...
@overload
def lut(model: ModelLike, mu: npt.ArrayLike | None = ..., sweep: dict[str, npt.ArrayLike] | None = ...,
        average: Literal[False] = ...) -> npt.NDArray[np.float64]: ...
@overload
def lut(model: ModelLike, mu: npt.ArrayLike | None = ..., sweep: dict[str, npt.ArrayLike] | None = ..., *,
        average: Literal[True]) -> tuple[npt.NDArray[np.float64], Any]: ...
def walk(alpha: float, theta: float, fresnel: Sequence[str] = ..., distribution: Literal["ggx", "beckmann"] = ...,
         paths: int = ..., seed: int = ..., dielectric: float | None = ...) -> dict[str, npt.NDArray[np.float64]]: ...
def render(model: ModelLike, size: int | tuple[int, int] = ..., lights: Sequence[dict[str, Any]] | None = ...,
           env: str | npt.ArrayLike | None = ..., samples: int = ..., seed: int = ...,
           diffuse: Sequence[float] | None = ..., specular: Sequence[float] | None = ...,
           ambient: Sequence[float] | None = ..., mesh: str | None = ...) -> npt.NDArray[np.float32]: ...
def fit(X: npt.ArrayLike | dict[str, npt.ArrayLike], y: npt.ArrayLike, *, variables: Sequence[str] | None = ...,
        ops: str = ..., constants: Literal["fitted", "integer", "none"] = ..., max_size: int = ...,
        size_weights: str = ..., metric: Literal["rms", "mae", "max-abs", "max-rel", "mean-relative", "r2"] = ...,
        test_fraction: float = ..., split: Literal["random", "last"] = ..., seed: int = ..., time: float = ...,
        generations: int | None = ..., evaluations: int | None = ..., target_error: float | None = ...,
        threads: int = ..., islands: int = ..., population: int = ..., enumerate_size: int = ...,
        choose: Literal["parsimonious", "knee", "best"] = ..., choose_factor: float = ..., snap: bool = ...,
        starts: Sequence[str] = ...) -> FitResult: ...
def design(target: str = ..., *, vars: list[str] | None = ..., params: dict[str, float] | None = ..., form: Literal["rv", "nh"] | None = ...,
           param: str | None = ..., range: tuple[float, float] | None = ..., objective: Literal["max-abs", "max-rel", "both"] = ...,
           zone: float = ..., ops: str = ..., max_cost: int = ..., max_forms: int | None = ..., time: float = ...,
           seed: int = ..., threads: int = ..., measure_cost: bool = ...,
           precision: Literal["double", "float", "half"] = ...) -> DesignResult: ...
