"""Going on with the run of a run folder: its checkpoint and the rows its files hold.

A run folder's checkpoint (:class:`rancf.post.history.HistoryStore`) renames its files in
order: the history files, then ``checkpoint.npz`` (the
:class:`~rancf.solvers.state.DynamicState` after the last stored row), then ``summary.json``.
A run killed at any moment thus leaves a state and at least the rows up to it (rows beyond it
are dropped on resuming: the resumed run computes them again, the same).  :func:`stored_rows`
reads those rows back in the layout of the raw history (every stream
:meth:`HistoryStore.flush` writes), so that the resumed run appends to them and its files read
as one run.
"""

from __future__ import annotations

import contextlib
import json
import re
import shutil
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.solvers.state import NPZ_ERRORS, DynamicState
from rancf.system.outputs import SystemOutputs

__all__ = ["CHECKPOINT", "stored_rows", "read_checkpoint", "remove_leftovers"]

#: The run folder's file of the state after its last stored row.
CHECKPOINT = "checkpoint.npz"

#: Names of the temporary files of :mod:`rancf.atomic` (``.NAME.XXXXXXXX.EXT``).
_TEMPORARY = re.compile(r"^\..+\.[A-Za-z0-9_]{8}(\.[A-Za-z0-9]+)?$")


def read_checkpoint(out: Path) -> DynamicState | None:
    """The state of ``out``'s last checkpoint, or None if the run wrote none."""
    path = Path(out) / CHECKPOINT
    return DynamicState.load(path) if path.is_file() else None


def remove_leftovers(out: Path) -> list[str]:
    """Remove what a killed run leaves besides its last checkpoint: the raw history and the
    temporary files of writes it did not finish.  Returns their names."""
    gone = []
    raw = Path(out) / ".history"
    if raw.exists():
        shutil.rmtree(raw, ignore_errors=True)
        gone.append(".history")
    for folder in [Path(out), *sorted((Path(out) / "bodies").glob("*"))]:
        if not folder.is_dir():
            continue
        for p in folder.iterdir():
            if p.is_file() and _TEMPORARY.match(p.name):
                with contextlib.suppress(OSError):
                    p.unlink()
                    gone.append(str(p.relative_to(out)))
    return gone


def _load(path: Path, keys: tuple[str, ...], n: int) -> dict[str, NDArray]:
    try:
        with np.load(path, allow_pickle=False) as z:
            got = {k: np.asarray(z[k], dtype=float) for k in keys}
    except NPZ_ERRORS as exc:
        raise InputError("--out", str(path), f"a run folder's results file ({exc})") from None
    short = [k for k, a in got.items() if a.shape[0] < n]
    if short:
        raise InputError(
            "--out",
            str(path),
            f"a results file with the {n} stored states of the checkpoint "
            f"({short[0]} has {got[short[0]].shape[0]})",
        )
    return {k: a[:n] for k, a in got.items()}


def stored_rows(out: Path, outputs: SystemOutputs, n: int) -> dict[str, NDArray]:
    """The first ``n`` rows of run folder ``out`` as the raw history holds them: ``t``, ``q``,
    ``v``, ``e`` (energies), rods' ``m`` (directors) and the derived ``a``, ``lam``, ``r``
    (reactions), ``s`` (section values), ``c`` (sensors) and ``eb`` (energies body by body).

    Raises
    ------
    InputError
        If a file is missing, unreadable or shorter than ``n`` rows.
    """
    out = Path(out)
    top = _load(
        out / "results.npz",
        ("t", "q", "v", "a", "lam", "kinetic", "strain", "gravity", "sensors", "reactions"),
        n,
    )
    rows = {k: top[k] for k in ("t", "q", "v", "a", "lam")}
    rows["e"] = np.column_stack([top["kinetic"], top["strain"], top["gravity"]])
    rows["c"], rows["r"] = top["sensors"], top["reactions"]
    along, energies, directors = [], [], []
    for name, model in outputs.flex:
        keys: tuple[str, ...] = ("along", "kinetic", "strain", "gravity")
        keys += ("directors",) if model.family.has_triads else ()
        body = _load(out / "bodies" / name / "results.npz", keys, n)
        along.append(body["along"].reshape(n, -1))
        energies.append(np.column_stack([body["kinetic"], body["strain"], body["gravity"]]))
        if model.family.has_triads:
            directors.append(body["directors"].reshape(n, -1))
    rows["s"] = np.concatenate(along, axis=1) if along else np.empty((n, 0))
    rows["eb"] = np.concatenate(energies, axis=1) if energies else np.empty((n, 0))
    if directors:
        rows["m"] = np.concatenate(directors, axis=1)
    return rows


def summary_of(out: Path) -> dict:
    """``out``'s ``summary.json`` (empty if missing or unreadable)."""
    try:
        return json.loads((Path(out) / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
