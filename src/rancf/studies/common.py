"""Shared pieces of the paper studies: example scenarios, variants, series, FFT, result records."""

from __future__ import annotations

import csv
import io
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import atomic_write
from rancf.bodies.flexible import Model
from rancf.errors import ConvergenceError
from rancf.scenario import Scenario, parse_scenario
from rancf.solvers.dynamic import DynamicResult, DynamicStatus
from rancf.solvers.modal import ModalResult
from rancf.studies.catalog import EXAMPLES, SCENARIO_ANALYSES, example_path
from rancf.studies.grid import Executor, GridRun, grid_variant, run_grid, variant_raw

__all__ = [
    "EXAMPLES",
    "SCENARIO_ANALYSES",
    "example_path",
    "load_example",
    "variant",
    "run",
    "modes",
    "fft_peak",
    "Comparison",
    "StudyResult",
    "n_elements",
    "format_error",
]


def load_example(name: str) -> dict[str, Any]:
    """The parsed TOML of a shipped example (a plain dictionary to derive variants from)."""
    return tomllib.loads(example_path(name).read_text(encoding="utf-8"))


def variant(raw: dict[str, Any], name: str, **changes: Any) -> tuple[Scenario, Model]:
    """A validated scenario (:func:`variant_raw`) and its model."""
    d = variant_raw(raw, **changes)
    sc = parse_scenario(d, f"{name} (variant {changes})" if changes else name)
    return sc, sc.build_model()


def run(sc: Scenario) -> DynamicResult:
    """The dynamics of a scenario with its ``[solver]`` settings, as ``rancf simulate`` runs it
    (:func:`rancf.runs.simulate.run_simulate`, held in memory)."""
    from rancf.runs.simulate import run_simulate

    return run_simulate(sc).result


def modes(sc: Scenario, count: int | None = None) -> ModalResult:
    """The natural modes of a scenario as ``rancf modes`` computes them
    (:func:`rancf.runs.modes.run_modes`): ``count`` of them, or every one of the free
    coordinates."""
    from rancf.runs.modes import run_modes

    return run_modes(sc, count, every=count is None).result


def fft_peak(t: NDArray, x: NDArray, f_min: float = 0.0) -> dict[str, Any]:
    """Amplitude spectrum of the linearly detrended signal and its peak above ``f_min``.

    Returns the frequencies, the one-sided amplitude spectrum, the peak frequency on the FFT
    grid, the resolution ``1 / T`` and a refined peak from parabolic interpolation of the log
    amplitude around the maximum (Hann window).
    """
    from scipy.signal import detrend  # imported here: scipy.signal takes 0.6 s to import

    t = np.asarray(t, dtype=float)
    x = detrend(np.asarray(x, dtype=float))
    n = x.size
    dt = float(np.mean(np.diff(t)))
    window = np.hanning(n)
    spec = np.abs(np.fft.rfft(x * window)) * 2.0 / window.sum()
    freqs = np.fft.rfftfreq(n, dt)
    sel = freqs > f_min
    i = int(np.flatnonzero(sel)[np.argmax(spec[sel])])
    refined = freqs[i]
    if 0 < i < spec.size - 1 and spec[i - 1] > 0 and spec[i + 1] > 0:
        a, b, c = np.log(spec[i - 1]), np.log(spec[i]), np.log(spec[i + 1])
        denom = a - 2 * b + c
        if denom != 0:
            refined = freqs[i] + 0.5 * (a - c) / denom * (freqs[1] - freqs[0])
    return {
        "freqs": freqs,
        "amplitude": spec,
        "peak_hz": float(freqs[i]),
        "refined_hz": float(refined),
        "resolution_hz": float(1.0 / (n * dt)),
        "peak_amplitude": float(spec[i]),
    }


@dataclass
class Comparison:
    """One row of a "paper says / we get" table."""

    quantity: str
    paper: str
    ours: str
    difference: str
    note: str = ""


@dataclass
class StudyResult:
    """What a study produced: figures, tables, the comparison with the paper, notes."""

    name: str
    title: str
    figures: list[tuple[str, str]] = field(default_factory=list)
    animations: list[tuple[str, str]] = field(default_factory=list)
    tables: list[tuple[str, list[str], list[list[Any]], str]] = field(default_factory=list)
    comparison: list[Comparison] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    data: dict[str, Any] = field(default_factory=dict)
    wall_time_s: float = 0.0
    started: float = field(default_factory=time.perf_counter)

    def finish(self) -> StudyResult:
        """Record the wall time since the study started; returns ``self``."""
        self.wall_time_s = time.perf_counter() - self.started
        return self

    def add_table(
        self, out: Path, title: str, header: list[str], rows: list[list[Any]], filename: str
    ) -> None:
        """Record a table and write it as CSV into ``out``."""
        buf = io.StringIO()
        w = csv.writer(buf)
        w.writerow(header)
        w.writerows(rows)
        atomic_write(out / filename, buf.getvalue())
        self.tables.append((title, header, rows, filename))

    def write_comparison_csv(self, out: Path) -> None:
        """Write the comparison table as ``comparison.csv``."""
        self.add_table(
            out,
            "Paper says / we get",
            ["quantity", "paper", "ours", "difference", "note"],
            [[c.quantity, c.paper, c.ours, c.difference, c.note] for c in self.comparison],
            "comparison.csv",
        )
        self.tables.insert(0, self.tables.pop())


def begin_study(
    out: str | Path, name: str, title: str, doc: str | None
) -> tuple[Path, StudyResult, dict[str, Any]]:
    """Create the output folder, the result record (the module docstring's body as its first
    note) and load the example scenario ``name``."""
    path = Path(out)
    path.mkdir(parents=True, exist_ok=True)
    res = StudyResult(name, title)
    if doc:
        res.notes.append(doc.split("\n\n", 1)[1].strip())
    return path, res, load_example(name)


def slug(s: str) -> str:
    """A file-name-safe version of ``s``."""
    return "".join(c if c.isalnum() else "_" for c in s.lower()).strip("_")


def save_figure(fig: Any, path: Path, res: StudyResult, caption: str) -> None:
    """Write a figure as PNG and record it in the study result."""
    from rancf.post.plots import save_figure

    save_figure(fig, path, 100)
    res.figures.append((caption, path.name))


def add_animation(
    res: StudyResult,
    run_dir: Path,
    path: Path,
    caption: str,
    frames: int = 50,
    magnify: float = 1.0,
) -> None:
    """Animate the run in ``run_dir`` (about ``frames`` frames) into the GIF ``path`` and record
    it for the report."""
    from rancf.post.system_run import animate_system_run, load_run

    data = load_run(run_dir)
    every = max(1, -(-data.t.size // frames))
    animate_system_run(data, path, fps=10, every=every, dpi=60, magnify=magnify)
    res.animations.append((caption, path.name))


def convergence_runs(
    raw: dict[str, Any],
    name: str,
    kinds: dict[str, dict[str, Any]],
    ns: list[int],
    reference: tuple[int, str],
    tol: float,
    extra_after: int = 4,
    *,
    sweep_dir: Path,
    executor: Executor | None = None,
    extra: dict[str, dict[str, Any]] | None = None,
    **solver: Any,
) -> tuple[dict[str, dict[int, GridRun]], GridRun, dict[str, int | None]]:
    """Run every element kind for increasing numbers of elements against a fine reference.

    The error of a run is ``max_t |r_B(t) - r_B,ref(t)|`` over the output times; each kind stops
    ``extra_after`` sizes after the first one that meets ``tol`` (a run that stopped early never
    meets it).  The runs are one sweep (:func:`rancf.studies.grid.run_grid`) in ``sweep_dir``:
    the reference first, then the sizes in increasing order; once a kind's stopping size is
    known its larger sizes are cancelled (with a parallel executor some may have run already:
    they are left out, so the results are those of the sequential loop).  ``extra`` adds named
    runs (``{label: variant changes}``, returned in ``runs[label][0]``); ``solver`` holds
    variant changes common to every run (``solver__t_end=0.3``).

    Returns
    -------
    runs : kind -> n -> :class:`~rancf.studies.grid.GridRun` with ``err``
    ref : the reference run
    found : kind -> smallest n with error <= tol (None if none tried did)
    """
    n_ref, ref_kind = reference
    plan = {"reference": ("reference", n_ref, {**kinds[ref_kind], "mesh__elements": n_ref})}
    for label, changes in (extra or {}).items():
        plan[f"extra {label}"] = (label, 0, {**changes})
    for n in ns:
        for kind, opts in kinds.items():
            plan[f"{kind} n={n}"] = (kind, n, {**opts, "mesh__elements": n})
    variants = [
        grid_variant(raw, i, key, **changes, **solver)
        for i, (key, (_, _, changes)) in enumerate(plan.items())
    ]
    what = {v.name: plan[key][:2] for v, key in zip(variants, plan, strict=True)}
    by_kind_n = {plan[key][:2]: v.name for v, key in zip(variants, plan, strict=True)}
    done: dict[str, GridRun] = {}

    def on_run(vname: str, run: GridRun) -> list[str]:
        done[vname] = run
        ref = done.get(variants[0].name)
        if ref is None:
            return []
        cancel = []
        for kind in kinds:
            errs = {n: _error(r, ref) for (k, n), r in _runs_of(done, what, kind).items()}
            hit = [n for n in ns if n in errs and errs[n] <= tol]
            if hit:  # the stop can only come earlier as more sizes finish
                stop = next((n for n in ns if n >= hit[0] + extra_after), ns[-1])
                cancel += [by_kind_n[(kind, n)] for n in ns if n > stop]
        return cancel

    run_grid(executor, variants, example_path(name), sweep_dir, on_run)
    ref = done[variants[0].name]
    if ref["status"] != DynamicStatus.COMPLETED.value:
        raise ConvergenceError(
            f"the reference run ({n_ref} elements) failed: {ref['message']}",
            float(ref["t"][-1]) if ref["t"].size else 0.0,
        )
    runs: dict[str, dict[int, GridRun]] = {k: {} for k in kinds}
    found: dict[str, int | None] = {}
    for kind in kinds:
        found[kind] = None
        by_n = _runs_of(done, what, kind)
        for n in ns:
            run = by_n[(kind, n)]
            run["err"] = _error(run, ref)
            runs[kind][n] = run
            first = found[kind]
            if first is None and run["err"] <= tol:
                found[kind] = first = n
            if first is not None and n >= first + extra_after:
                break
    for label in extra or {}:
        runs[label] = {0: done[by_kind_n[(label, 0)]]}
    return runs, ref, found


def _runs_of(
    done: dict[str, GridRun], what: dict[str, tuple[str, int]], kind: str
) -> dict[tuple[str, int], GridRun]:
    return {what[v]: r for v, r in done.items() if what[v][0] == kind}


def _error(run: GridRun, ref: GridRun) -> float:
    """``max_t |tip - tip_ref|`` over the run's output times; inf for a run that stopped."""
    if run["status"] != DynamicStatus.COMPLETED.value:
        return float("inf")
    k = run["tip"].shape[0]
    return float(np.max(np.linalg.norm(run["tip"] - ref["tip"][:k], axis=1)))


def n_elements(n: int) -> str:
    """``"1 element"``, ``"4 elements"``: a count of elements for legends and captions."""
    return f"{n} element" if n == 1 else f"{n} elements"


#: What a non-finite error in a table means (see :func:`format_error`).
NOT_REACHED = "did not reach t_end"
NOT_RUN = "not run"


def format_error(err: float, fmt: str = ".4e") -> str:
    """A tip error for a table: the number, or words for a run without one.

    ``inf`` (a run that stopped before ``t_end``, :func:`_error`) becomes ``"did not reach
    t_end"`` and ``nan`` (a run that was not made) ``"not run"``, never a bare ``inf``/``nan``.
    """
    if np.isnan(err):
        return NOT_RUN
    if not np.isfinite(err):
        return NOT_REACHED
    return format(err, fmt)
