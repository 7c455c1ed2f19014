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

_Rows = Union[npt.NDArray[np.float64], "list[list[float]]", "list[float]"]
_RobotConfig = Union["RobotEstimator", Dict[str, Any], _Path]

class RobotEstimator:
    """The robot's runtime estimator: every sensor's divider voltage in, every joint's angle
    (°) out, the crosstalk undone (docs/robot-runtime.md)."""

    @staticmethod
    def from_config(path: _Path) -> "RobotEstimator":
        """From a robot estimator config file (``.toml`` or ``.json``)."""
    @staticmethod
    def from_toml(text: str) -> "RobotEstimator": ...
    @staticmethod
    def from_dict(config: Dict[str, Any]) -> "RobotEstimator":
        """From the config's tables as a dict (what ``config()`` returns)."""
    def config(self) -> Dict[str, Any]: ...
    def config_toml(self) -> str: ...
    @property
    def joints(self) -> int: ...
    @property
    def sensors(self) -> int: ...
    @property
    def condition_number(self) -> float: ...
    @property
    def flags(self) -> "list[int]":
        """Each joint's flags from the last ``step`` (0: none)."""
    def run(self, volts: _Rows, flags: bool = False) -> Any:
        """Angles (°, shape (n, N)) over voltages (shape (n, M)) from a fresh estimator; with
        ``flags=True`` a tuple ``(angles, flags)``, flags uint32 of shape (n, N)."""
    def step(self, volts: "list[float]") -> "list[float]":
        """One sample: M voltages to N angles (°)."""
    def reset(self) -> None: ...

def tip(angles: _Rows, config: _RobotConfig) -> Dict[str, npt.NDArray[np.float64]]:
    """The tip's pose at joint angles (°, (n, N) or (N,)): ``position_mm`` (n, 3), ``rotation``
    (n, 3, 3), ``quaternion`` (n, 4: w, x, y, z), in the robot's base frame."""

def backbone(angles: _Rows, config: _RobotConfig, points: int = 20) -> npt.NDArray[np.float64]:
    """Backbone points (mm), equally spaced from the base to the tip: (n, points, 3), or
    (points, 3) for one row of angles."""

class Robot:
    """A sensing robot: several joints on one tube, read and checked from a robot file as
    ``dlw inspect ROBOT`` reads it (docs/robots.md)."""

    @staticmethod
    def from_file(path: _Path) -> "Robot": ...
    @property
    def name(self) -> str: ...
    @property
    def path(self) -> _Path: ...
    @property
    def joints(self) -> int: ...
    @property
    def sensors(self) -> int: ...
    def inspect(self) -> Dict[str, Any]:
        """``dlw inspect ROBOT --json``'s dict: ``joints``, ``sensors`` (with ``crosstalk``),
        ``warnings``."""
    def estimator(self, config: Union[_RobotConfig, str]) -> RobotEstimator:
        """The runtime estimator of a config of this robot (a path, TOML text, a dict or a
        ``RobotEstimator``); ``ValueError`` when its joints or sensors are not this robot's."""
    def estimator_config(
        self,
        gauge_factor: Union[float, "list[float]"],
        r0_ohm: Union[float, "list[float]"],
        divider_ohm: Optional[Union[float, "list[float]"]] = None,
        supply_v: float = 5.0,
    ) -> Dict[str, Any]:
        """The nominal linear config ``dlw estimator-config ROBOT`` writes, as a dict: each
        value once for every sensor or once per sensor."""
    def tip(self, angles: _Rows) -> Dict[str, npt.NDArray[np.float64]]:
        """The tip's pose at joint angles (°, (n, N) or (N,)), as ``dlw.tip``."""
    def backbone(self, angles: _Rows, points: int = 20) -> npt.NDArray[np.float64]:
        """Backbone points (mm) from the base to the tip, as ``dlw.backbone``."""
