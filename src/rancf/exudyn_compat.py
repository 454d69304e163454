"""Exudyn's names across its versions, for the comparisons with it (``rancf[bench]``: 1.9 on).

Exudyn 1.12.258 renamed the parameters of ``ObjectANCFCable2D`` (``physicsLength`` → ``length``,
``physicsMassPerLength`` → ``massPerLength``, ...) and members of ``SimulationSettings``
(``displayStatistics`` → ``show.statistics``, ``solutionSettings.writeSolutionToFile`` →
``solution.file.write``, ``linearSolverType`` → ``linearSolver.solverType``, ...); 1.11.0 replaced
``beams.GenerateStraightLineANCFCable2D`` by ``beams.GenerateBeamElementsAlongLine``.  The old
names still work there but emit a ``DeprecationWarning``.  These helpers use the new names where
the installed Exudyn has them and the old ones before, with the same values, so the results do not
depend on which (:func:`item` for any item whose parameters lost the ``physics`` prefix).

Importing this module imports neither Exudyn nor the rest of rancf (``benchmarks/
exudyn_pendulum.py`` times its own start-up); the functions import Exudyn when called.
"""

from __future__ import annotations

import inspect
from collections.abc import Sequence
from typing import Any

__all__ = ["cable2d", "dynamic_settings", "item", "quiet_settings", "straight_cable2d"]


def _old_name(name: str) -> str:
    """``massPerLength`` -> ``physicsMassPerLength`` (the names before Exudyn 1.12.258)."""
    return "physics" + name[0].upper() + name[1:]


def item(name: str, **params: Any) -> Any:
    """The Exudyn item ``exudyn.itemInterface.<name>`` from parameters under their current names.

    A parameter the installed Exudyn does not know under its current name (``mass``, ``length``,
    ``massPerLength``, ...) but under the name with the ``physics`` prefix it had before 1.12.258
    (``physicsMass``, ...) is passed under the old name; other parameters as given.
    """
    from exudyn import itemInterface

    cls = getattr(itemInterface, name)
    known = inspect.signature(cls).parameters
    renamed = {
        (_old_name(k) if k not in known and _old_name(k) in known else k): v
        for k, v in params.items()
    }
    return cls(**renamed)


def cable2d(**params: Any) -> Any:
    """Exudyn's ``Cable2D`` (``ObjectANCFCable2D``) from parameters under their current names.

    ``length``, ``massPerLength``, ``bendingStiffness``, ... are passed as ``physicsLength``,
    ``physicsMassPerLength``, ... to an Exudyn older than 1.12.258 (:func:`item`).
    """
    return item("Cable2D", **params)


def _assign(obj: Any, new: str, old: str, value: Any) -> None:
    """``obj.<new> = value`` where this Exudyn has the dotted member ``new``, else ``obj.<old>``."""
    for path in (new, old):
        *parents, last = path.split(".")
        target = obj
        try:
            for p in parents:
                target = getattr(target, p)
            getattr(target, last)
        except AttributeError:
            continue
        setattr(target, last, value)
        return
    raise AttributeError(f"SimulationSettings has neither {new} nor {old}")


def quiet_settings(sparse: bool = False, sensors_write_period: float | None = None) -> Any:
    """``exu.SimulationSettings()`` that write no solution file and print no statistics or times.

    ``sparse`` selects the EigenSparse linear solver (Exudyn's default is dense);
    ``sensors_write_period`` [s] sets how often sensors store their values.
    """
    import exudyn as exu

    ss = exu.SimulationSettings()
    _assign(ss, "solution.file.write", "solutionSettings.writeSolutionToFile", False)
    _assign(ss, "show.computationTime", "displayComputationTime", False)
    _assign(ss, "show.statistics", "displayStatistics", False)
    if sparse:
        solver = exu.LinearSolverType.EigenSparse
        _assign(ss, "linearSolver.solverType", "linearSolverType", solver)
    if sensors_write_period is not None:
        _assign(
            ss,
            "solution.sensors.writePeriod",
            "solutionSettings.sensorsWritePeriod",
            sensors_write_period,
        )
    return ss


def dynamic_settings(
    t_end: float,
    step: float,
    rho_inf: float,
    sparse: bool = False,
    sensors_write_period: float | None = None,
) -> Any:
    """:func:`quiet_settings` for ``SolveDynamic``: generalized-α with spectral radius ``rho_inf``,
    fixed step ``step`` [s] up to ``t_end`` [s], no per-step output."""
    ss = quiet_settings(sparse, sensors_write_period)
    ss.timeIntegration.numberOfSteps = int(round(t_end / step))
    ss.timeIntegration.endTime = t_end
    ss.timeIntegration.generalizedAlpha.spectralRadius = rho_inf
    ss.timeIntegration.verboseMode = 0
    return ss


def straight_cable2d(
    mbs: Any,
    start: Sequence[float],
    end: Sequence[float],
    elements: int,
    template: Any,
    gravity: Sequence[float] = (0.0, 0.0, 0.0),
    fixed_start: Sequence[int] | None = None,
) -> list[int]:
    """A straight chain of ``template`` cables from ``start`` to ``end`` (3D points, z = 0).

    ``gravity`` is a mass-proportional load; ``fixed_start`` (x, y, x', y': 1 fixed, 0 free)
    constrains the first node to the ground.  Returns the node numbers, first to last.
    """
    from exudyn import beams

    gravity = list(gravity)
    if hasattr(beams, "GenerateBeamElementsAlongLine"):  # Exudyn 1.11.0 and later
        # -1 is "no given node" in every version: 1.11.0 passes the default None on and fails
        return beams.GenerateBeamElementsAlongLine(
            mbs,
            list(start),
            list(end),
            elements,
            template,
            gravity=gravity,
            groundConstraintsStart=fixed_start,
            nodeNumberStart=-1,
            nodeNumberEnd=-1,
        )["nodes"]
    return beams.GenerateStraightLineANCFCable2D(
        mbs,
        list(start),
        list(end),
        elements,
        template,
        massProportionalLoad=gravity,
        fixedConstraintsNode0=fixed_start,
        fixedConstraintsNode1=None,
    )[0]
