"""The natural-modes driver: :func:`run_modes` (``rancf modes``, modal sweeps, the shipped
examples)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.post.checks import largest_strain, largest_stretch, run_warnings
from rancf.runs.campbell import run_campbell
from rancf.runs.common import refuse_unloaded_reference, static_state
from rancf.solvers.campbell import CampbellResult
from rancf.solvers.form import find_form
from rancf.solvers.modal import ModalResult, natural_modes

__all__ = ["ModesRun", "run_modes"]


@dataclass
class ModesRun:
    """A modal analysis: the system, the modes, the state they are about (``y is None``: the
    reference), the free coordinates, the run's warnings and, with ``[modes] spin_rates``, the
    Campbell diagram."""

    system: Any
    result: ModalResult
    about: str
    y: NDArray | None
    n_free: int
    warnings: list[str]
    campbell: CampbellResult | None


def run_modes(
    sc: Any,
    count: int | None = None,
    about: str | None = None,
    *,
    at_least: int | None = None,
    count_key: str | None = None,
    every: bool = False,
) -> ModesRun:
    """The ``count`` lowest natural modes of scenario ``sc`` (default ``[modes] count``) about
    ``about`` (default ``[modes] about``: the reference or the static equilibrium under the full
    loads), and its Campbell diagram when ``[modes] spin_rates`` is given.

    ``at_least``: given, ask for at least this many modes but never more than the model has (a
    sweep's frequency columns, an example's table); ``count_key``: the name an error message gives
    ``count``; ``every``: every mode of the free coordinates (a convergence study's spectrum;
    ``count`` is not used).

    Raises
    ------
    InputError
        ``count < 1``, or ``count`` not below the free coordinates (without ``at_least``).
    """
    find_form(sc)
    system = sc.build_system()
    n_free = int(np.sum(~system.fixed))
    key = count_key or f"{sc.path}: modes.count"
    if count is None:
        count = sc.data["modes"]["count"]
    if count < 1:
        raise InputError(key, count, "an integer >= 1")
    if at_least is not None:
        count = min(max(count, at_least), n_free - 1)
    if count >= n_free:
        raise InputError(key, count, f"at most {n_free - 1} (the free coordinates - 1)")
    about = about or sc.data["modes"]["about"]
    if about == "reference":
        refuse_unloaded_reference(sc, "modes")
    y = lam = None
    largest, by_body = (0.0, 1.0), {}
    solved: list[str] = []
    if about == "static":
        y, lam, solved = static_state(sc, system)
        q = system.q_from_y(y)
        for name, b in zip(system.names, system.flex, strict=False):  # the equilibrium's strain
            if b.family.surface:  # a line's section strain (a shell has none sampled)
                continue
            qb = q[system.body_slice(name)]
            largest = max(largest, largest_strain(b, np.ones(1), qb[None]))
            by_body[name] = largest_stretch(b, qb)
    notes = solved + run_warnings(system, static=True, largest=largest, by_body=by_body)
    res = natural_modes(system, y, None if every else count, lam)
    if sc.data["modes"]["spin_rates"]:
        from rancf.scenario.shell_build import refuse_shells

        refuse_shells(sc, "modes with [modes] spin_rates (a Campbell diagram)")
    cam = run_campbell(sc, system, count, about) if sc.data["modes"]["spin_rates"] else None
    return ModesRun(system, res, about, y, n_free, notes, cam)
