"""``rancf static`` and ``rancf modes`` on scenarios of several bodies (``[[bodies]]``,
``[[joints]]``, ``[[springs]]``): the system's equilibrium (:func:`rancf.solvers.static.
solve_static` on a :class:`~rancf.system.System`) and its modes on the null space of its
constraints (:mod:`rancf.solvers.system_modal`)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from rancf.cli.io import OutputDir
from rancf.errors import InputError

__all__ = ["static_system", "modes_system", "print_static", "print_modes"]


def _static(sc: Any, system: Any, on_step: Any = None) -> Any:
    from rancf.solvers.static import solve_static

    return solve_static(system, sc.solver["load_steps"], method=sc.solver["static_method"],
                        on_step=on_step)  # fmt: skip


def static_system(args: argparse.Namespace, sc: Any, copy: str | None) -> dict[str, Any]:
    """The equilibrium of a system (``--out``: its load path as a run folder); returns the
    JSON object ``static`` prints: positions of every body's nodes (or centre), sensors,
    load factors, Newton iterations, the reactions of supports and joints by column."""
    from rancf.post.results import LoadPath, sensor_table, write_static_run
    from rancf.scenario.system_build import support_labels
    from rancf.system.outputs import SystemOutputs

    system = sc.build_system()
    labels = support_labels(sc)
    path = LoadPath(system, labels)
    od = None if args.out is None else OutputDir(args.out, kind="run", overwrite=args.overwrite)
    if od is None:
        res = _static(sc, system)
    else:
        from rancf.atomic import atomic_write

        with od:
            info = {"scenario": str(Path(args.scenario).resolve())}
            try:
                res = _static(sc, system, path.record)
                info.update(status="completed", message="reached the end of the load path")
            except BaseException as exc:
                kind = "interrupted" if isinstance(exc, KeyboardInterrupt) else "failed"
                info.update(status=kind, message=" ".join(str(exc).split()) or kind)
                raise
            finally:
                if path.steps:
                    write_static_run(od.path, path, sc.sensors, info)
                    atomic_write(od.path / "scenario.toml", copy or "")
                    od.keep()
    outputs = SystemOutputs(system, sc.sensors, labels)
    lf = res.load_factors[-1:]
    rows = outputs.rows(lf, res.q[None], None, None, None, res.lam[None], static=True)
    positions: dict[str, Any] = {}
    for name in system.names:
        b, sl = system.bodies[name], system.body_slice(name)
        q = res.q[sl]
        positions[name] = (b.node_positions(q).tolist() if hasattr(b, "node_positions")
                           else q[: system.dim].tolist())  # fmt: skip
    names, vals = sensor_table(outputs, sc.sensors, res.q, static=True, t=lf, lam=res.lam[None])
    return {
        "positions": positions,
        "sensors": dict(zip(names, vals[0].tolist(), strict=True)),
        "load_factors": res.load_factors.tolist(),
        "newton_iterations": res.n_newton,
        "method": res.method,
        "wall_time_s": res.wall_time,
        "reactions": dict(zip(outputs.reaction_names, rows["r"][0].tolist(), strict=True)),
        "warnings": [],
    }


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


def print_static(doc: dict[str, Any], out: Any) -> None:
    """The text summary of ``static`` on a system."""
    where = f" -> {out}" if out else ""
    steps = len(doc["load_factors"]) - 1
    print(
        f"static equilibrium: {steps} load steps, {doc['newton_iterations']} Newton iterations"
        f"{where}"
    )
    for k, v in doc["sensors"].items():
        print(f"  {k:12s} {v: .9g}")
    for k, v in doc["reactions"].items():
        print(f"  reaction {k:16s} {v: .9g}")


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
