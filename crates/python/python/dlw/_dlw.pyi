"""Type stubs of the extension module ``dlw._dlw``."""

from os import PathLike
from typing import Any, Dict, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, "PathLike[str]"]
_Floats = Union[npt.NDArray[np.float64], "list[float]"]
RecordingDict = Dict[str, Any]

class Design:
    """A checked design file and the numbers ``dlw inspect`` derives from it."""

    @staticmethod
    def from_file(path: _Path) -> "Design":
        """Reads and checks a design file (TOML); ``ValueError`` names what is wrong."""
    @property
    def name(self) -> str: ...
    def geometry(self) -> Dict[str, Any]:
        """``dlw inspect --json``'s numbers: ``y_bar_mm``, ``y_s_mm``, ``delta_y_mm``,
        ``strain_per_deg``, ``closing_angle_deg``, ``warnings`` …"""

def read_recording(path: _Path) -> RecordingDict:
    """A recording folder as numpy arrays (``time_s``, ``stroke_mm``, ``angle_deg``, ``v1_V``,
    ``v2_V`` where present) and its rig under ``"rig"``."""

class Estimator:
    """The runtime estimator: divider voltages in, the joint angle (°) out."""

    @staticmethod
    def from_config(path: _Path) -> "Estimator": ...
    @staticmethod
    def from_toml(text: str) -> "Estimator": ...
    @property
    def sensors(self) -> int: ...
    @property
    def flags(self) -> int:
        """The flags of the last ``step`` (0: none)."""
    def run(self, v1: _Floats, v2: Optional[_Floats] = None) -> npt.NDArray[np.float64]:
        """Angles over whole arrays from a fresh estimator; equal to ``dlw estimate``'s
        ``estimate_deg``."""
    def step(self, v1: float, v2: Optional[float] = None) -> float:
        """One sample; the angle (°)."""
    def reset(self) -> None: ...

class Fit:
    """A fitted sensor model."""

    def config_toml(self) -> str: ...
    def save(self, path: _Path, force: bool = False) -> None:
        """Writes the config; an existing file only with ``force=True``."""
    def summary(self) -> Dict[str, Any]:
        """The fitted numbers, as ``dlw fit --json``."""
    def estimator(self) -> Estimator: ...

def fit(
    recording: Union[_Path, RecordingDict],
    design: Union[_Path, Design],
    model: str = "pi",
    order: int = 10,
    prefilter: str = "ma:100",
    sensor: Optional[str] = None,
    compare: bool = False,
    validate: Optional[Union[_Path, RecordingDict]] = None,
) -> Fit:
    """Fits ``model`` (``linear``, ``pi``, ``continuous-pi``) as ``dlw fit`` does."""

def simulate(
    design: Union[_Path, Design],
    protocol: str = "random",
    duration_s: float = 60.0,
    seed: int = 1,
    scenario: Optional[_Path] = None,
) -> RecordingDict:
    """A simulated bench run, as ``dlw simulate``; the same dict as ``read_recording``."""

def discover(
    recording: Union[_Path, RecordingDict],
    design: Union[_Path, Design],
    holdout: Optional[Union[_Path, RecordingDict]] = None,
    scenario: Optional[_Path] = None,
) -> Dict[str, Any]:
    """``dlw discover --json``'s dict (without file paths) and ``scenario_toml``."""
