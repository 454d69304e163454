"""What the analysis drivers share: the static state an analysis is linearized about."""

from __future__ import annotations

from typing import Any

from numpy.typing import NDArray

__all__ = ["static_state", "refuse_unloaded_reference"]


def refuse_unloaded_reference(sc: Any, analysis: str) -> None:
    """Refuse an ``analysis`` (``"modes"``, ``"buckling"``) about the reference of a scenario
    whose line has a length other than its chord (``geometry.length``, ``[form]``): that
    reference carries a force and is no equilibrium.

    Raises
    ------
    InputError
        Naming ``--about`` and that ``static`` is the way.
    """
    from rancf.errors import InputError

    if sc.length_keys():
        raise InputError(
            "--about",
            "reference",
            f'"static" ({analysis} about the static equilibrium: a line given a length by '
            "geometry.length or [form] is not at rest in its reference; "
            '[modes] about = "static" for modes)',
        )


def static_state(sc: Any, system: Any) -> tuple[NDArray, NDArray, list[str]]:
    """The equilibrium of ``system`` under the full loads of scenario ``sc`` (coordinates and
    multipliers), solved with the ``[solver]`` table's static options, and the solve's warning
    lines (:attr:`~rancf.solvers.static.StaticResult.warnings`)."""
    from rancf.scenario.system_build import scenario_keys
    from rancf.solvers.linear_static import refuse_linear_start
    from rancf.solvers.static import solve_static

    refuse_linear_start(sc.static_options(), "an analysis about the static equilibrium")
    with scenario_keys(sc):
        res = solve_static(system, **sc.static_options())
    assert res.lam is not None  # a system's solution has its multipliers (empty: no joints)
    return res.y, res.lam, list(res.warnings)
