"""One run of a sweep, as executed by a Dask worker: its own folder and one result row.

The folder holds ``scenario.toml`` (the variant, with a CAD ``file`` made absolute), the
analysis output (``simulate``: the files of :func:`rancf.post.results.write_run`; ``static``:
``static.json`` and the load path as a run directory, :func:`rancf.post.results.write_static_run`;
``modes``: ``modes.json``) and, written last and atomically, ``row.json`` — its
presence marks the run as finished, so an interrupted sweep resumes with the runs that lack it.
"""

from __future__ import annotations

import hashlib
import json
import math
import time
import traceback
from pathlib import Path
from typing import Any

from rancf.atomic import atomic_write
from rancf.post.results import strict_json
from rancf.sweep.toml_out import dumps, with_absolute_paths

__all__ = ["run_variant", "run_variants_in_order", "scenario_hash", "ROW_FILE", "FREQUENCY_COLUMNS"]

ROW_FILE = "row.json"
#: Disk a sweep run's files may take, as ``rancf simulate --max-output-gb``' default: a run
#: beyond it is refused (before the sweep starts when the grid shows it, else as a failed row).
MAX_RUN_GB = 2.0
LIMIT = "the limit of a sweep run (GB)"
#: Number of natural frequencies reported per ``modes`` run.
FREQUENCY_COLUMNS = 6


#: What an analysis returns: status, message, solve time, the row's result values and the run's
#: warnings (one line each, as the command prints them).
Outcome = tuple[str, str, float, dict[str, float], list[str]]


def _analyse(sc: Any, analysis: str, folder: Path) -> Outcome:
    """Run the analysis (``simulate``, ``static`` or ``modes``)."""
    if analysis == "simulate":
        return _simulate(sc, folder)
    if analysis == "static":
        return _static(sc, folder)
    return _modes(sc, folder)


def _simulate(sc: Any, folder: Path) -> Outcome:
    import numpy as np

    from rancf.post.results import sensor_table
    from rancf.runs.simulate import run_simulate

    info = {"scenario": str(folder / "scenario.toml")}
    run = run_simulate(sc, folder, info, MAX_RUN_GB, LIMIT)
    res, summary = run.result, run.summary
    assert summary is not None  # a folder was given
    energy = np.array([[res.kinetic[-1], res.strain[-1], res.gravity[-1]]])
    names, vals = sensor_table(
        run.outputs, sc.sensors, res.q[-1:], res.v[-1:], energy, t=res.t[-1:]
    )
    values = {"t_reached": float(res.t_reached), "steps": float(res.n_steps)}
    values.update(zip(names, map(float, vals[0]), strict=True))
    return summary["status"], res.message, float(res.wall_time), values, list(run.warnings)


def _static(sc: Any, folder: Path) -> Outcome:
    from rancf.post.static_run import positions_json
    from rancf.runs.static import run_static

    run = run_static(sc, folder, {"scenario": str(folder / "scenario.toml")})
    out = {"positions": positions_json(run.system, run.result.q), "sensors": run.sensors}
    atomic_write(folder / "static.json", strict_json(out))
    assert run.summary is not None  # a folder was given
    warned = list(run.notes) + list(run.summary["warnings"])
    return "completed", "", float(run.result.wall_time), run.sensors, warned


def _modes(sc: Any, folder: Path) -> Outcome:
    from rancf.runs.modes import run_modes

    t0 = time.perf_counter()  # as rancf modes: [modes] about, its static state, spin rates
    run = run_modes(sc, at_least=FREQUENCY_COLUMNS)
    wall = time.perf_counter() - t0
    res = run.result
    f = res.frequencies_hz
    out = {
        "frequencies_hz": f.tolist(),
        "rigid_body_modes_removed": res.n_rigid,
        "about": run.about,
    }
    atomic_write(folder / "modes.json", strict_json(out))
    values = {f"f{i + 1}_hz": float(x) for i, x in enumerate(f[:FREQUENCY_COLUMNS])}
    return "completed", "", wall, values, list(run.warnings)


def run_variant(
    name: str, raw: dict[str, Any], base: str, analysis: str, folder: str
) -> dict[str, Any]:
    """Run one variant into ``folder``; never raises for a failing model (the row says so)."""
    from rancf.scenario import parse_scenario

    t0 = time.perf_counter()
    out = Path(folder)
    out.mkdir(exist_ok=True)  # not its parents: a sweep folder removed meanwhile stays removed
    raw = with_absolute_paths(raw, base)
    digest = scenario_hash(raw, analysis, base)  # the files it reads as they are before the run
    atomic_write(out / "scenario.toml", dumps(raw))
    try:
        sc = parse_scenario(raw, base)
        status, message, solve, values, warned = _analyse(sc, analysis, out)
    except Exception as exc:  # noqa: BLE001 - every failure becomes a row, never a crash
        status, message, solve, values, warned = "failed", _one_line(exc), None, {}, []
        atomic_write(out / "error.txt", traceback.format_exc())
    bad = [k for k, x in values.items() if not math.isfinite(x)]
    if bad and status == "completed":
        status = "failed"
        message = f"non-finite result: {', '.join(f'{k} = {values[k]!r}' for k in bad[:3])}"
    row = {
        "run": name,
        "status": status,
        "message": message,
        "warnings": warned,
        "wall_time_s": time.perf_counter() - t0,
        "solve_time_s": solve,
        "values": values,
        "scenario_sha256": digest,
    }
    atomic_write(out / ROW_FILE, strict_json(row))  # non-finite values as null
    return row


def scenario_hash(raw: dict[str, Any], analysis: str, base: str | Path) -> str:
    """SHA-256 of a variant's scenario dictionary, analysis (key order ignored) and the
    contents of the files it reads (CSV tables, CAD files; relative names relative to the
    folder of the base scenario ``base``): a finished run is reused on resume only if this is
    unchanged."""
    from rancf.scenario.read_files import file_digests

    files = file_digests(raw, base)
    text = json.dumps(
        {"analysis": analysis, "scenario": raw, "files": files}, sort_keys=True, default=repr
    )
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def run_variants_in_order(calls: list[tuple[Any, ...]]) -> list[dict[str, Any]]:
    """:func:`run_variant` for each argument tuple, one after another (one Dask task for
    several short runs); the rows in call order."""
    return [run_variant(*args) for args in calls]


def _one_line(exc: BaseException) -> str:
    text = f"{type(exc).__name__}: {exc}" if not str(exc) else str(exc)
    return " ".join(text.split())
