"""``rancf modes`` on scenarios of several bodies (``[[bodies]]``, ``[[joints]]``,
``[[springs]]``): the modes of the system (about its equilibrium: :func:`rancf.solvers.static.
solve_static`) on the null space of its constraints (:mod:`rancf.solvers.system_modal`)."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from rancf.errors import InputError

__all__ = ["modes_system", "print_modes"]


def _static(sc: Any, system: Any, on_step: Any = None) -> Any:
    from rancf.solvers.static import solve_static

    return solve_static(system, sc.solver["load_steps"], method=sc.solver["static_method"],
                        on_step=on_step)  # fmt: skip


def modes_system(args: argparse.Namespace, sc: Any) -> dict[str, Any]:
    """The modes of a system about its reference or its equilibrium (``--about static``)."""
    import numpy as np

    from rancf.solvers.modal import natural_modes

    if args.plot:
        raise InputError("--plot", args.plot, "a one-body scenario (mode plots of systems: "
                         "export the modes' shapes from Python, rancf.natural_modes)")  # fmt: skip
    system = sc.build_system()
    about = args.about or sc.data["modes"]["about"]
    count = args.count if args.count is not None else sc.data["modes"]["count"]
    n_free = int(np.sum(~system.fixed))
    if count >= n_free:
        key = "--count" if args.count is not None else f"{sc.path}: modes.count"
        raise InputError(key, count, f"at most {n_free - 1} (the free coordinates - 1)")
    y = lam = None
    if about == "static":
        res = _static(sc, system)
        y, lam = res.y, res.lam
    out = natural_modes(system, y, count, lam)
    return {
        "frequencies_hz": out.frequencies_hz.tolist(),
        "growth_rates_per_s": out.growth_rates.tolist(),
        "eigenproblem": "symmetric" if out.symmetric else "general",
        "rigid_body_modes_removed": out.n_rigid,
        "about": about,
        "n_dofs_free": n_free,
        "constraints": system.m,
        "warnings": [],
    }


def print_modes(doc: dict[str, Any]) -> None:
    """The text summary of ``modes`` on a system."""
    print(f"natural frequencies about the {doc['about']} configuration "
          f"({doc['rigid_body_modes_removed']} zero-frequency mode(s) removed: rigid-body "
          f"motions and mechanisms; {doc['constraints']} constraint equations):")  # fmt: skip
    for i, (f, g) in enumerate(zip(doc["frequencies_hz"], doc["growth_rates_per_s"],
                                   strict=True), 1):  # fmt: skip
        extra = "" if g == 0 else f"  growth rate {g:.6g} 1/s"
        print(f"  mode {i:2d}  {f:12.6f} Hz{extra}")
    sys.stdout.flush()
