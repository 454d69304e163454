"""The paper's numerical examples as reproducible studies (``rancf example``, ``rancf report``)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from rancf.studies.common import EXAMPLES, StudyResult

__all__ = ["EXAMPLES", "study_runner"]


def study_runner(name: str) -> Callable[[str | Path, bool], StudyResult]:
    """The ``run_study(out, quick)`` function of an example."""
    if name == "planar-pendulum":
        from rancf.studies.planar_pendulum import run_study
    elif name == "spatial-pendulum":
        from rancf.studies.spatial_pendulum import run_study
    elif name == "arc-vibration":
        from rancf.studies.arc_vibration import run_study
    else:
        from rancf.errors import InputError

        raise InputError("example", name, f"one of {', '.join(EXAMPLES)}")
    return run_study
