"""The paper's numerical examples as reproducible studies (``rancf example``, ``rancf report``)."""

from __future__ import annotations

from collections.abc import Callable

from rancf.studies.common import EXAMPLES, StudyResult

__all__ = ["EXAMPLES", "study_runner", "runs_a_grid"]

#: Studies whose ``run_study`` takes an executor for its mesh grid.
_GRID_STUDIES = ("planar-pendulum", "spatial-pendulum", "exact-geometry")


def study_runner(name: str) -> Callable[..., StudyResult]:
    """The ``run_study(out, quick[, executor])`` function of an example."""
    if name == "planar-pendulum":
        from rancf.studies.planar_pendulum import run_study
    elif name == "spatial-pendulum":
        from rancf.studies.spatial_pendulum import run_study
    elif name == "arc-vibration":
        from rancf.studies.arc_vibration import run_study
    elif name == "exact-geometry":
        from rancf.studies.exact_geometry import run_study
    else:
        from rancf.errors import InputError

        raise InputError("example", name, f"one of {', '.join(EXAMPLES)}")
    return run_study


def runs_a_grid(name: str) -> bool:
    """Whether the study ``name`` sends a mesh grid to an executor (its third argument)."""
    return name in _GRID_STUDIES
