"""dlw: sensing continuum-robot joints, from Python.

The same library as the ``dlw`` command: design geometry (``Design``), bench recordings
(``read_recording``, ``simulate``), sensor fits (``fit``), the runtime estimator
(``Estimator``), characterization (``characterize``) and discovery (``discover``). Bad input raises ``ValueError`` with the command's
message. See docs/python.md.
"""

from ._dlw import (
    Design,
    Estimator,
    Fit,
    __version__,
    characterize,
    discover,
    fit,
    read_recording,
    simulate,
)

__all__ = [
    "Design",
    "Estimator",
    "Fit",
    "__version__",
    "characterize",
    "discover",
    "fit",
    "read_recording",
    "simulate",
]
