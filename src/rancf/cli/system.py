"""``rancf static`` on scenarios of several bodies (``[[bodies]]``, ``[[joints]]``,
``[[springs]]``): the system's equilibrium (:func:`rancf.solvers.static.solve_static` on a
:class:`~rancf.system.System`)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from rancf.cli.io import OutputDir

__all__ = ["static_system", "print_static"]


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
