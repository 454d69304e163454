"""The paper's numerical examples as reproducible studies (``rancf example``, ``rancf report``),
and the other shipped scenarios run the same way (``rancf example run NAME``)."""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING

from rancf.studies.catalog import EXAMPLES, SCENARIO_ANALYSES

if TYPE_CHECKING:
    from rancf.studies.common import StudyResult

__all__ = ["EXAMPLES", "SCENARIO_ANALYSES", "study_runner", "runs_a_grid"]

#: Studies whose ``run_study`` takes an executor for its mesh grid.
_GRID_STUDIES = ("planar-pendulum", "spatial-pendulum", "exact-geometry")


def study_runner(name: str) -> Callable[..., StudyResult]:
    """The ``run_study(out, quick[, executor])`` function of an example (a paper study or
    another shipped scenario, :data:`SCENARIO_ANALYSES`)."""
    run_study: Callable[..., StudyResult]
    if name == "planar-pendulum":
        from rancf.studies import planar_pendulum

        run_study = planar_pendulum.run_study
    elif name == "spatial-pendulum":
        from rancf.studies import spatial_pendulum

        run_study = spatial_pendulum.run_study
    elif name == "arc-vibration":
        from rancf.studies import arc_vibration

        run_study = arc_vibration.run_study
    elif name == "exact-geometry":
        from rancf.studies import exact_geometry

        run_study = exact_geometry.run_study
    elif name in SCENARIO_ANALYSES:
        from rancf.studies.scenario_example import run_scenario

        return partial(run_scenario, name)
    else:
        from rancf.errors import InputError

        names = [*EXAMPLES, *SCENARIO_ANALYSES]
        raise InputError("example", name, f"one of {', '.join(names)}")
    return run_study


def runs_a_grid(name: str) -> bool:
    """Whether the study ``name`` sends a mesh grid to an executor (its third argument)."""
    return name in _GRID_STUDIES
