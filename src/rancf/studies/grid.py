"""Mesh grids of the studies, run through the sweep engine (:mod:`rancf.sweep`).

A study lists its runs as scenario variants (:func:`grid_variant`); :func:`run_grid` runs them
with an executor — :class:`~rancf.sweep.engine.LocalExecutor` (this process, one after another:
the sequential baseline) or :class:`~rancf.sweep.engine.DaskExecutor` (every core) — into
``OUT/sweep/runs/<run>/`` with ``OUT/sweep/results.csv``, exactly as ``rancf sweep`` does, and
reads every run back as a :class:`GridRun`.  Both executors call the same function on the same
scenario, so the numbers do not depend on the executor (a test checks it).

Shapes: ``t`` ``(n_t,)``, ``tip`` ``(n_t, dim)``, ``ab`` ``(n_t,)``, ``gradients`` ``(n_nodes,)``.
"""

from __future__ import annotations

import copy
import json
import shutil
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import numpy as np

from rancf.post.results import load_results
from rancf.sweep.engine import LocalExecutor, SweepExecutor, run_variants
from rancf.sweep.spec import Variant

__all__ = ["GridRun", "grid_variant", "variant_raw", "run_grid", "Executor"]

Executor = SweepExecutor


class GridRun(dict[str, Any]):
    """One finished run of a study grid, read back from its folder.

    Keys: ``n_el``, ``t``, ``tip`` (last node), ``ab`` (distance first–last node),
    ``gradients`` (reference nodal gradient magnitudes; cables only, else empty), ``status``,
    ``message``, ``wall`` (solve time [s]), ``folder``.  ``model`` (rebuilt from the run's
    ``scenario.toml``) and ``result`` (a :class:`~rancf.solvers.dynamic.DynamicResult` read
    from ``results.npz``) are made on first use only: rebuilding a mesh costs more than most runs.
    """

    def __missing__(self, key: str) -> Any:
        if key == "model":
            from rancf.scenario import load_scenario

            value: Any = load_scenario(self["folder"] / "scenario.toml").build_model()
        elif key == "result":
            value = _dynamic_result(self["folder"])
        else:
            raise KeyError(key)
        self[key] = value
        return value


def _dynamic_result(folder: Path) -> Any:
    from rancf.solvers.dynamic import DynamicResult, DynamicStatus

    d = load_results(folder / "results.npz")
    s = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    return DynamicResult(
        t=d["t"],
        q=d["q"],
        v=d["v"],
        kinetic=d["kinetic"],
        strain=d["strain"],
        gravity=d["gravity"],
        status=DynamicStatus(s["status"]),
        message=s["message"],
        n_steps=s["steps"],
        n_newton=s["newton_iterations"],
        n_factorizations=s["factorizations"],
        n_rejected=s["rejected_steps"],
        wall_time=s["solve_wall_time_s"],
    )


def read_run(folder: Path, row: dict[str, Any]) -> GridRun:
    """A :class:`GridRun` from a run folder and its result row."""
    if not (folder / "results.npz").is_file():  # failed before the time loop
        return GridRun(
            n_el=0,
            t=np.zeros(0),
            tip=np.zeros((0, 2)),
            ab=np.zeros(0),
            gradients=np.zeros(0),
            status=row["status"],
            message=row.get("message", ""),
            wall=0.0,
            folder=folder,
        )
    from rancf.post.system_run import load_run

    b = load_run(folder).body()
    dim, dpn = b.dim, b.q.shape[1] // b.n_nodes
    pos = b.q.reshape(b.t.size, -1, dpn)[..., :dim]
    ref = b.reference.reshape(-1, dpn)
    grads = np.linalg.norm(ref[:, dim:], axis=1) if dpn == 2 * dim else np.zeros(0)
    return GridRun(
        n_el=b.n_nodes - 1,
        t=b.t,
        tip=pos[:, -1],
        ab=np.linalg.norm(pos[:, -1] - pos[:, 0], axis=1),
        gradients=grads,
        status=row["status"],
        message=row.get("message", ""),
        wall=float(row.get("solve_time_s") or 0.0),
        folder=folder,
    )


def variant_raw(raw: dict[str, Any], **changes: Any) -> dict[str, Any]:
    """A copy of the scenario dictionary ``raw`` with some keys changed.

    ``changes`` use ``table__key`` names, e.g. ``mesh__elements=8``, ``solver__t_end=0.5``; a
    plain table name replaces the whole table (``initial_velocity=[]``).
    """
    d = copy.deepcopy(raw)
    for key, value in changes.items():
        if "__" in key:
            table, sub = key.split("__")
            d.setdefault(table, {})[sub] = value
        else:
            d[key] = value
    return d


def grid_variant(raw: dict[str, Any], index: int, label: str, **changes: Any) -> Variant:
    """A sweep variant of the scenario dictionary ``raw``.

    ``changes`` use ``table__key`` names (``mesh__elements=8``); a plain name replaces a whole
    table.  ``label`` names the run folder (``<index>_<label>``).
    """
    d = variant_raw(raw, **changes)
    values = {key.replace("__", "."): value for key, value in changes.items() if "__" in key}
    safe = "".join(c if c.isalnum() or c in ".-+=" else "-" for c in label)
    return Variant(index, f"{index:04d}_{safe}"[:120], values, d)


def run_grid(
    executor: Executor | None,
    variants: list[Variant],
    base: Path,
    out: Path,
    on_run: Callable[[str, GridRun], Iterable[str]] | None = None,
) -> dict[str, GridRun]:
    """Run ``variants`` (``simulate``) into ``out`` (emptied first) and read them back.

    Parameters
    ----------
    executor : LocalExecutor or DaskExecutor, optional
        Default: :class:`~rancf.sweep.engine.LocalExecutor`.
    variants : list of Variant
        In priority order.
    base : Path
        The scenario file the variants derive from.
    out : Path
        The grid's sweep directory.
    on_run : callable, optional
        ``on_run(name, run)`` as runs finish; returns names of variants no longer needed.

    Returns
    -------
    dict
        Variant name -> :class:`GridRun`, for every run that ran.
    """
    if out.exists():
        shutil.rmtree(out)  # a study always computes afresh
    runs: dict[str, GridRun] = {}

    def done(name: str, row: dict[str, Any]) -> Iterable[str]:
        runs[name] = read_run(out / "runs" / name, row)
        return on_run(name, runs[name]) if on_run is not None else ()

    run_variants(executor or LocalExecutor(), variants, base, "simulate", out, False, done)
    return runs
