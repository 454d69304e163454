"""How large a run's files will be, checked before it starts: the system of a scenario and
its outputs (:func:`plan_run`), refused where the files would pass a limit
(:func:`check_output_size`)."""

from __future__ import annotations

from typing import Any

from rancf.errors import RunTooLargeError
from rancf.system.outputs import SystemOutputs

__all__ = ["estimate_output_bytes", "check_output_size", "plan_run"]


def estimate_output_bytes(
    n_outputs: int, n_q: int, n_sensor_columns: int, n_directors: int = 0, n_derived: int = 0
) -> int:
    """Disk space a run needs at its end (raw history + results.npz + the CSV files).

    Raw and ``.npz`` copies of ``t, q, v, a``, energies, ``n_directors`` director components (a
    rod's 3 per node) and ``n_derived`` reactions and section values at 8 bytes a number each,
    about 20 bytes a number in the CSV files.
    """
    binary = 3 * n_q + 4 + n_sensor_columns + n_directors + n_derived
    per_row = 2 * 8 * binary + 20 * (n_sensor_columns + 6 + n_derived)
    return int(n_outputs) * per_row


def check_output_size(
    where: str,
    n_outputs: int,
    n_q: int,
    n_sensor_columns: int,
    n_directors: int,
    limit_gb: float,
    limit_name: str = "--max-output-gb",
    n_derived: int = 0,
) -> None:
    """Refuse, before it starts, a run whose files would take more than ``limit_gb`` GB
    (:func:`estimate_output_bytes`).

    Raises
    ------
    RunTooLargeError
        Naming ``where`` (the scenario), the size, the number of stored states and the limit.
    """
    need = estimate_output_bytes(n_outputs, n_q, n_sensor_columns, n_directors, n_derived)
    if need > limit_gb * 1e9:
        raise RunTooLargeError(
            f"{where}: this run would write about {need / 1e9:.3g} GB ({n_outputs} stored "
            f"states of {n_q} coordinates), more than {limit_name} = {limit_gb:g}; "
            "raise solver.output_step, shorten solver.t_end or raise the limit"
        )


def plan_run(
    sc: Any, limit_gb: float, limit_name: str = "--max-output-gb"
) -> tuple[Any, SystemOutputs]:
    """The system of scenario ``sc`` and its outputs, after checking the run's files fit in
    ``limit_gb`` (:func:`check_output_size`; every flexible body's ``q``, ``v``, ``a`` are also
    kept in ``bodies/NAME/``)."""
    from rancf.scenario.system_build import build_system, support_labels

    system = build_system(sc)
    outputs = SystemOutputs(system, sc.sensors, support_labels(sc))
    # the body folders repeat every flexible body's q, v, a
    n_derived = len(outputs.reaction_names) + outputs.n_along + system.m
    n_derived += 3 * sum(b.n for b in system.flex)
    check_output_size(
        sc.path,
        sc.dynamic_options().n_outputs,
        system.n,
        len(outputs.sensor_names),
        outputs.n_directors,
        limit_gb,
        limit_name,
        n_derived,
    )
    return system, outputs
