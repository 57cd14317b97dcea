# The public surface of `detach` with its types; the docstrings are in
# `__init__.py` (`help(detach.Scene.pave)`).
import decimal
import fractions
import os
from typing import Any, Callable, Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

class DetachError(ValueError):
    """An input refused (an option, a parameter, a name) or a failed run."""

class SceneFileError(DetachError):
    """A scene file or TOML text that is not one."""

class ProofRejected(DetachError):
    """The checker rejects a proof, or cannot check it; nothing is written."""

#: A parameter or a window end: decimal text (`"1.5"`, `"pi/2"` for windows),
#: an int, a `Decimal`, or a rational with a finite decimal expansion.
Number = Union[str, int, decimal.Decimal, fractions.Fraction]
Window = tuple[Number, Number]
PathLike = Union[str, "os.PathLike[str]"]
Eps = Union[float, int, fractions.Fraction, str]
ClassName = Literal[
    "omega_and_omega0",
    "not_omega_and_not_omega0",
    "not_omega_and_omega0",
    "omega_and_not_omega0",
    "undecided",
    "undefined",
]
SetName = Union[ClassName, Literal["omega", "omega0"]]
Method = Literal["natural", "centred", "contract", "slices"]
Variant = Literal["derived", "printed"]
Stop = Literal["all_decided", "resolution", "double_precision_limit", "budget", "interrupted"]

LABELS: tuple[str, str, str, str]
STATUSES: tuple[str, str, str]
CLASSES: tuple[ClassName, ...]
FATES: tuple[str, str, str]

def scenes() -> list[str]: ...
def palette() -> dict[ClassName, tuple[str, str, str]]: ...
def verify(path: PathLike) -> Verification: ...

class Interrupted(KeyboardInterrupt):
    result: Union[Paving, ParamAtlas]
    def __init__(self, result: Union[Paving, ParamAtlas]) -> None: ...

class Scene:
    @classmethod
    def load(cls, name: str, variant: Variant = "derived", **params: Number) -> Scene: ...
    @classmethod
    def from_file(cls, path: PathLike, **params: Number) -> Scene: ...
    @classmethod
    def from_toml(cls, text: str, **params: Number) -> Scene: ...
    @classmethod
    def from_sympy(cls, omega: Any, omega0: Any = None, **kwargs: Any) -> Scene: ...
    @property
    def name(self) -> str: ...
    @property
    def title(self) -> str: ...
    @property
    def variant(self) -> Variant: ...
    @property
    def params(self) -> dict[str, str]: ...
    @property
    def domain(self) -> dict[str, tuple[str, str]]: ...
    @property
    def toml(self) -> Optional[str]: ...
    @property
    def warnings(self) -> list[str]: ...
    def pave(
        self,
        *,
        eps: Eps = ...,
        method: Method = "slices",
        region: Optional[SetName] = None,
        theta: Optional[Window] = None,
        theta_dot: Optional[Window] = None,
        max_boxes: int = 4_000_000,
        progress: Optional[Callable[[int, int, int], object]] = None,
    ) -> Paving: ...
    def param_atlas(
        self,
        x: Union[str, tuple[str, Number, Number]],
        y: Union[None, str, tuple[str, Number, Number]] = None,
        *,
        sets: Union[SetName, Sequence[SetName]] = ...,
        eps: Optional[Eps] = None,
        max_boxes: int = 100_000,
        progress: Optional[Callable[[int, int, int], object]] = None,
    ) -> ParamAtlas: ...
    def flow(
        self,
        start: tuple[Union[Number, Window], Union[Number, Window]],
        t: Number,
        *,
        until: str = "cell,domain",
        order: int = 20,
        proof: bool = False,
    ) -> Trajectory: ...
    def explore(self, *, port: int = 0) -> Explorer: ...
    def reach(
        self,
        t: Number,
        *,
        until: str = "cell",
        theta: Optional[Window] = None,
        theta_dot: Optional[Window] = None,
        eps: Eps = ...,
        max_boxes: int = 100_000,
        proof: bool = False,
    ) -> Reach: ...
    def singular_points(
        self,
        *,
        theta: Optional[Window] = None,
        theta_dot: Optional[Window] = None,
        x: Union[None, str, tuple[str, Number, Number]] = None,
        eps: Optional[Eps] = None,
    ) -> dict[str, Any]: ...
    def area(self, *, digits: int = 10) -> dict[str, Area]: ...

class Explorer:
    @property
    def url(self) -> str: ...
    @property
    def state(self) -> dict[str, Any]: ...
    @property
    def params(self) -> dict[str, str]: ...
    def stop(self) -> None: ...
    def __enter__(self) -> Explorer: ...
    def __exit__(self, *exc: object) -> None: ...

class Event:
    kind: str
    time: tuple[float, float]
    theta: tuple[float, float]
    theta_dot: tuple[float, float]
    slope: tuple[float, float]

class Trajectory:
    def json(self) -> dict[str, Any]: ...
    def save_proof(self, path: PathLike) -> None: ...
    @property
    def events(self) -> list[Event]: ...
    @property
    def end_time(self) -> Union[decimal.Decimal, tuple[float, float]]: ...
    @property
    def end(self) -> tuple[tuple[float, float], tuple[float, float]]: ...
    @property
    def stop(self) -> str: ...
    @property
    def steps(self) -> int: ...
    def band(self, pieces: int = 8) -> npt.NDArray[np.void]: ...
    def plot(self, ax: Any = None, pieces: int = 8, color: str = "black") -> Any: ...

class Reach:
    leaves: npt.NDArray[np.void]
    reasons: list[str]
    complete: bool
    def area(self) -> tuple[float, float]: ...
    @property
    def undecided_in_proof(self) -> Optional[int]: ...
    def save_proof(self, path: PathLike) -> None: ...
    def plot(self, ax: Any = None, legend: bool = True) -> Any: ...
    def __len__(self) -> int: ...

class Area:
    name: str
    label: str
    lower: float
    upper: float
    how: str
    @property
    def width(self) -> float: ...

class SetArea:
    name: str
    label: str
    inner: float
    outer: float
    empty: Optional[str]
    @property
    def inner_text(self) -> str: ...
    @property
    def outer_text(self) -> str: ...

class Paving:
    scene: Scene
    @property
    def leaves(self) -> npt.NDArray[np.void]: ...
    @property
    def areas(self) -> dict[str, SetArea]: ...
    @property
    def stop(self) -> Stop: ...
    @property
    def stop_text(self) -> str: ...
    @property
    def complete(self) -> bool: ...
    @property
    def elapsed(self) -> float: ...
    @property
    def eps(self) -> float: ...
    @property
    def root(self) -> tuple[tuple[float, float], tuple[float, float]]: ...
    def __len__(self) -> int: ...
    def to_pandas(self) -> Any: ...
    def save_proof(self, path: PathLike) -> None: ...
    def plot(self, ax: Any = None, legend: bool = True) -> Any: ...

class Verification:
    verdict: Literal["VALID", "INVALID", "UNCHECKED"]
    claim: str
    why: str
    @property
    def valid(self) -> bool: ...
    def __bool__(self) -> bool: ...

class Share:
    name: str
    label: str
    nonempty: float
    empty: float
    undecided: float

class ParamAtlas:
    scene: Scene
    @property
    def axes(self) -> list[tuple[str, str, str]]: ...
    @property
    def sets(self) -> list[str]: ...
    @property
    def bounds(self) -> npt.NDArray[np.float64]: ...
    @property
    def status(self) -> dict[str, npt.NDArray[Any]]: ...
    @property
    def shares(self) -> dict[str, Share]: ...
    @property
    def json(self) -> dict[str, Any]: ...
    @property
    def thresholds(self) -> list[dict[str, Any]]: ...
    @property
    def complete(self) -> bool: ...
    @property
    def elapsed(self) -> float: ...
    @property
    def eps(self) -> float: ...
    def __len__(self) -> int: ...
    def save_proof(self, path: PathLike) -> None: ...
    def plot(self, ax: Any = None, legend: bool = True) -> Any: ...
