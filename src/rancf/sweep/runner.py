"""One run of a sweep, as executed by a Dask worker: its own folder and one result row.

The folder holds ``scenario.toml`` (the variant, with a CAD ``file`` made absolute), the
analysis output (``simulate``: the files of :func:`rancf.post.results.write_run`; ``static``:
``static.json`` and the load path as a run directory, :func:`rancf.post.results.write_static_run`;
``modes``: ``modes.json``) and, written last and atomically, ``row.json`` — its
presence marks the run as finished, so an interrupted sweep resumes with the runs that lack it.
"""

from __future__ import annotations

import copy
import json
import time
import traceback
from pathlib import Path
from typing import Any

from rancf.post.results import atomic_write
from rancf.sweep.toml_out import dumps

__all__ = ["run_variant", "run_variants_in_order", "ROW_FILE", "FREQUENCY_COLUMNS"]

ROW_FILE = "row.json"
#: Number of natural frequencies reported per ``modes`` run.
FREQUENCY_COLUMNS = 6


def _analyse(sc: Any, analysis: str, folder: Path) -> tuple[str, str, float, dict[str, float]]:
    """Run the analysis; returns status, message, solve time and the row's result values."""
    from rancf.post.results import sensor_table, write_run

    model = sc.build_model()
    if analysis == "simulate":
        from rancf.solvers.dynamic import integrate
        from rancf.solvers.static import start_state

        y0, start = start_state(sc, model)
        res = integrate(model, sc.dynamic_options(), initial=y0)
        extra = {"scenario": str(folder / "scenario.toml"), **start}
        summary = write_run(folder, model, sc.sensors, res, extra, sc.support_labels)
        energy = [[res.kinetic[-1], res.strain[-1], res.gravity[-1]]]
        names, vals = sensor_table(model, sc.sensors, res.q[-1:], res.v[-1:], energy)
        values = {"t_reached": float(res.t_reached), "steps": float(res.n_steps)}
        values.update(zip(names, map(float, vals[0]), strict=True))
        return summary["status"], res.message, float(res.wall_time), values
    if analysis == "static":
        from rancf.post.results import LoadPath, write_static_run
        from rancf.solvers.static import solve_static

        path = LoadPath(model, sc.support_labels)  # the load path, as `static --out` keeps it
        t0 = time.perf_counter()
        res = solve_static(
            model, sc.solver["load_steps"], on_step=path.record, method=sc.solver["static_method"]
        )
        wall = time.perf_counter() - t0
        names, vals = sensor_table(model, sc.sensors, res.q)
        values = dict(zip(names, map(float, vals[0]), strict=True))
        out = {"positions": model.node_positions(res.q).tolist(), "sensors": values}
        atomic_write(folder / "static.json", json.dumps(out, indent=2) + "\n")
        info = {"status": "completed", "message": "", "scenario": str(folder / "scenario.toml")}
        write_static_run(folder, path, sc.sensors, info)
        return "completed", "", wall, values
    from rancf.solvers.modal import natural_modes

    t0 = time.perf_counter()
    res = natural_modes(model, None, max(FREQUENCY_COLUMNS, sc.data["modes"]["count"]))
    wall = time.perf_counter() - t0
    f = res.frequencies_hz
    out = {"frequencies_hz": f.tolist(), "rigid_body_modes_removed": res.n_rigid}
    atomic_write(folder / "modes.json", json.dumps(out, indent=2) + "\n")
    values = {f"f{i + 1}_hz": float(x) for i, x in enumerate(f[:FREQUENCY_COLUMNS])}
    return "completed", "", wall, values


def run_variant(
    name: str, raw: dict[str, Any], base: str, analysis: str, folder: str
) -> dict[str, Any]:
    """Run one variant into ``folder``; never raises for a failing model (the row says so)."""
    from rancf.scenario import parse_scenario

    t0 = time.perf_counter()
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    raw = copy.deepcopy(raw)
    geo = raw.get("geometry", {})
    if geo.get("kind") == "cad" and isinstance(geo.get("file"), str):
        geo["file"] = str((Path(base).parent / geo["file"]).resolve())
    atomic_write(out / "scenario.toml", dumps(raw))
    try:
        sc = parse_scenario(raw, base)
        status, message, solve, values = _analyse(sc, analysis, out)
    except Exception as exc:  # noqa: BLE001 - every failure becomes a row, never a crash
        status, message, solve, values = "failed", _one_line(exc), None, {}
        atomic_write(out / "error.txt", traceback.format_exc())
    row = {
        "run": name,
        "status": status,
        "message": message,
        "wall_time_s": time.perf_counter() - t0,
        "solve_time_s": solve,
        "values": values,
    }
    atomic_write(out / ROW_FILE, json.dumps(row, indent=2) + "\n")
    return row


def run_variants_in_order(calls: list[tuple[Any, ...]]) -> list[dict[str, Any]]:
    """:func:`run_variant` for each argument tuple, one after another (one Dask task for
    several short runs); the rows in call order."""
    return [run_variant(*args) for args in calls]


def _one_line(exc: BaseException) -> str:
    text = f"{type(exc).__name__}: {exc}" if not str(exc) else str(exc)
    return " ".join(text.split())
