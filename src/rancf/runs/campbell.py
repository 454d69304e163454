"""The Campbell driver: :func:`run_campbell` (frequencies about a steady rotation against the
spin rate, ``[modes] spin_rates``)."""

from __future__ import annotations

from typing import Any

from rancf.solvers.campbell import CampbellResult, campbell

__all__ = ["run_campbell"]


def run_campbell(sc: Any, system: Any, count: int, about: str) -> CampbellResult:
    """The lowest ``count`` frequencies of ``system`` (built from scenario ``sc``) at each of
    ``[modes] spin_rates`` about ``spin_axis`` through ``spin_center``; with ``about = "static"``
    each rate's steady state carries the scenario's loads (``[solver]`` load steps and method)."""
    spin = sc.data["modes"]
    return campbell(
        system,
        spin["spin_axis"],
        spin["spin_center"],
        spin["spin_rates"],
        count,
        loads=about == "static",
        load_steps=sc.solver["load_steps"],
        method=sc.solver["static_method"],
    )
