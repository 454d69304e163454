"""The buckling driver: :func:`run_buckling` (``rancf buckling``, the shipped examples)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.runs.common import refuse_unloaded_reference, static_state
from rancf.solvers.buckling import BucklingResult, linear_buckling
from rancf.solvers.form import find_form

__all__ = ["BucklingRun", "run_buckling"]


@dataclass
class BucklingRun:
    """A buckling analysis: the system, the solver's result, the state it is about (``y is
    None``: the reference) and the warning lines of its static solve."""

    system: Any
    result: BucklingResult
    y: NDArray | None
    warnings: list[str]


def run_buckling(
    sc: Any, count: int = 3, about: Literal["reference", "static"] = "reference"
) -> BucklingRun:
    """The ``count`` smallest critical load factors of scenario ``sc``'s loads, linearized about
    the reference or the static equilibrium (:func:`rancf.solvers.buckling.linear_buckling`).

    Raises
    ------
    InputError
        ``count < 1``.
    """
    if count < 1:
        raise InputError("--count", count, "an integer >= 1")
    from rancf.scenario.shell_build import refuse_shells  # nothing without a shell

    refuse_shells(sc, "buckling")
    find_form(sc)
    system = sc.build_system()
    y = lam = None
    solved: list[str] = []
    if about == "reference":
        refuse_unloaded_reference(sc, "buckling")
    if about == "static":
        y, lam, solved = static_state(sc, system)
    return BucklingRun(system, linear_buckling(system, count, about, y, lam), y, solved)
