"""Where a scenario's dynamic run starts: its reference, or its static equilibrium.

Kept apart from :mod:`rancf.solvers.static`, which it imports only for a static start: a run
from the reference (the default) loads none of the static solvers.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from rancf.errors import ScenarioError

if TYPE_CHECKING:
    from rancf.bodies.flexible import Model
    from rancf.system import System

__all__ = ["start_state"]


def start_state(
    sc: Any, model: Model | System
) -> tuple[NDArray[np.float64] | None, dict[str, Any]]:
    """Where a scenario's dynamic run starts: ``(None, info)`` from the reference, or the static
    equilibrium's model coordinates (``solver.initial_state = "static"``: loads as they act at
    ``t = 0``, supports installed) and the ``summary.json`` entries describing it.

    Raises
    ------
    ScenarioError
        A support installed away from its reference, or a line given a length other than its
        chord (``geometry.length``), with ``initial_state = "reference"``.
    """
    key = sc.installed_support()
    if sc.solver["initial_state"] == "reference":
        if key is not None:
            raise ScenarioError(
                sc.path,
                key,
                "installs a support away from its reference, which needs solver.initial_state "
                '= "static" (the static solution moves it there before the run)',
            )
        lengths = sc.length_keys()
        if lengths:
            raise ScenarioError(
                sc.path,
                lengths[0],
                "gives the line a length its reference is not at rest in, which needs "
                'solver.initial_state = "static" (the run starts from its equilibrium)',
            )
        return None, {"initial_state": "reference"}
    from rancf.scenario.system_build import scenario_keys
    from rancf.solvers.linear_static import refuse_linear_start
    from rancf.solvers.static import solve_static  # the static solvers, only for this start

    refuse_linear_start(sc.static_options(), 'solver.initial_state = "static"')
    with scenario_keys(sc):
        res = solve_static(model, at_time=0.0, **sc.static_options())
    from rancf.solvers.form import form_summary

    info = {
        **form_summary(sc),
        "initial_state": "static",
        "static": {
            "method": res.method,
            "load_steps": int(len(res.load_factors) - 1),
            "relaxation_steps": res.relaxation_steps,
            "newton_iterations": res.n_newton,
            "wall_time_s": res.wall_time,
            **({"warnings": list(res.warnings)} if res.warnings else {}),
        },
    }
    return res.y, info
