"""dlw: sensing continuum-robot joints, from Python.

The same library as the ``dlw`` command: design geometry (``Design``), bench recordings
(``read_recording``, ``simulate``), sensor fits (``fit``), the runtime estimator
(``Estimator``), characterization (``characterize``), robots (``Robot``: a robot file with its
inspection, estimator and kinematics), the robot runtime (``RobotEstimator``, ``tip``,
``backbone``) and discovery (``discover``). Bad input raises ``ValueError`` with the command's
message. See docs/python.md.
"""

from ._dlw import (
    Design,
    Estimator,
    Fit,
    Robot,
    RobotEstimator,
    __version__,
    backbone,
    characterize,
    discover,
    fit,
    read_recording,
    simulate,
    tip,
)

__all__ = [
    "Design",
    "Estimator",
    "Fit",
    "Robot",
    "RobotEstimator",
    "__version__",
    "backbone",
    "characterize",
    "discover",
    "fit",
    "read_recording",
    "simulate",
    "tip",
]
