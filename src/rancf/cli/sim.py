"""The sub-command that runs a scenario's dynamics: ``simulate``."""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import signal
import sys
import tomllib
from pathlib import Path
from typing import Any, Literal

from rancf.cli.io import OutputDir
from rancf.cli.stream import DiskStream, NothingToDo
from rancf.cli.stream import warn as _warn
from rancf.errors import InputError, RunFailedError

__all__ = ["add_parsers", "DEFAULT_MAX_OUTPUT_GB"]

#: Default ``--max-output-gb``: the disk a run's stored states may take.
DEFAULT_MAX_OUTPUT_GB = 2.0


def _positive(option: str, value: float, what: str) -> float:
    if not (math.isfinite(value) and value > 0):
        raise InputError(option, value, what)
    return value


def _scenario_text(path: str) -> str:
    """What the run folder keeps as ``scenario.toml`` (readers use it, not the original file,
    which may be edited or moved later)."""
    import tomllib

    from rancf.sweep.toml_out import scenario_copy

    text = Path(path).read_text(encoding="utf-8")  # load_scenario has read it already
    return scenario_copy(text, tomllib.loads(text), path)


def one_blas_thread() -> None:
    """Ask OpenBLAS for one thread (``OPENBLAS_NUM_THREADS=1``) unless set, before NumPy is
    loaded (``simulate``; ``sweep``, whose worker processes inherit it): a run makes no call
    that its threads would share, and idle, they spin after each small NumPy product (0.1 s of
    CPU of an 8-element pendulum's 0.45 s, 0.13 s of a 512-element run stored every step;
    ``docs/guide/performance.md``).  Nothing is changed once NumPy is loaded (a caller in
    Python keeps its own setting)."""
    if "numpy" not in sys.modules:
        os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def idle_cores() -> int:
    """The cores this process may use (its CPU affinity) that the last minute's load average
    leaves idle, at least 0."""
    from rancf.sweep.threads import default_threads

    cores = default_threads()
    try:
        busy = os.getloadavg()[0]
    except OSError:  # pragma: no cover - not available
        busy = 0.0
    return max(0, min(cores, int(cores - busy + 0.5)))


def element_threads(system: Any, asked: int | None, rows_beside: bool = False) -> int:
    """The threads a run's element loops use (``--threads``, else chosen): ``asked``, or, for a
    system with a flexible body of at least ``min_parallel_elements()`` elements (fewer: a loop
    shared between threads costs more than it saves), the idle cores (:func:`idle_cores`), less
    one for the output worker where it derives every step's row beside the loop
    (``rows_beside``), at least 1 (a thread that waits for a core holds up every loop it
    shares); else 1.  The sums are the same bit for bit whatever the number
    (``src/cpp/bodies/threads.hpp``); a sweep's runs keep one each."""
    from rancf.kernels import _core

    if asked is not None:
        return asked
    largest = max((getattr(b, "n_el", 0) for b in system.flex), default=0)
    if largest < _core.min_parallel_elements():
        return 1
    return max(1, idle_cores() - int(rows_beside))


def _rows_beside(plan: Any) -> bool:
    """Whether a worker thread derives every step's output row beside the time loop (the
    default output; :func:`rancf.post.block_worker.works_beside`): where it has a core of its
    own, two idle cores (:func:`idle_cores`) for the loop and it.  Without one the rows are
    derived between the steps, in larger blocks: a worker that shares the loop's core adds the
    threads' hand-overs to the same work."""
    from rancf.post.block_worker import works_beside

    opts = plan.options
    every_step = opts.output_step is None or opts.output_step <= opts.step
    return every_step and works_beside(plan.outputs) and idle_cores() >= 2


def _cmd_simulate(args: argparse.Namespace) -> int:
    one_blas_thread()
    if args.threads is not None and args.threads < 1:
        raise InputError("--threads", args.threads, "an integer >= 1")
    every = _positive("--checkpoint-every", args.checkpoint_every, "a finite number of seconds > 0")
    limit = _positive("--max-output-gb", args.max_output_gb, "a finite size in GB > 0")
    if args.t_end is not None:
        _positive("--t-end", args.t_end, "a finite time in s > 0")
    kind: Literal["resume", "run"] = "resume" if args.resume else "run"
    od = OutputDir(args.out, kind=kind, overwrite=args.overwrite)  # checks the path up front
    from rancf.cli.resume import scenario_for_run
    from rancf.runs.simulate import plan_simulate, simulate_planned
    from rancf.scenario.read_files import file_digests

    sc, copy = scenario_for_run(args.scenario, args.t_end)
    files = file_digests(tomllib.loads(copy), args.scenario)  # the run's CSV and CAD files
    plan = plan_simulate(sc, limit)  # refused before the folder is touched
    _warn(list(plan.notes))  # a mesh refined for the static start: said before the run
    from rancf.kernels import _core

    beside = _rows_beside(plan)
    _core.set_assembly_threads(element_threads(plan.system, args.threads, beside))
    if not args.quiet:
        from rancf.solvers.form import form_lines

        for line in form_lines(sc):
            print(f"rancf: {line}", file=sys.stderr)
    out = od.path
    stop = _StopFlag()
    with stop, od:
        disk = DiskStream(args, sc, copy, files, od, stop, every, beside)
        try:
            run = simulate_planned(sc, plan, stream=disk)
        except NothingToDo as done:
            return _nothing_to_do(args, out, done.t, plan.options.t_end)
        except BaseException as exc:
            disk.close_bar()
            if disk.store is None:  # before the run's files: nothing of it to keep
                raise
            err = _end_broken(disk.store, plan.system, exc, od.kept, out)
            if err is exc:
                raise
            raise err from None
    _warn(run.warnings[len(plan.notes) + len(disk.notes) :])
    assert run.summary is not None  # the stream ended the folder
    return _report(args, run.result, run.summary, out)


def _nothing_to_do(args: argparse.Namespace, out: Path, t: float, t_end: float) -> int:
    if not args.quiet:
        print(
            f"rancf: {out} already reached t = {t:g} s (t_end = {t_end:g} s): nothing to "
            "do; give --t-end to go further",
            file=sys.stderr,
        )
    return 0


def _end_broken(store: Any, model: Any, exc: BaseException, kept: bool, out: Path) -> BaseException:
    """Leave the run folder truthful after ``exc``; returns the exception to raise.

    Before the first checkpoint nothing of the run is kept (its files are removed; the folder
    too if this command created it).  After it, the folder keeps the last complete checkpoint,
    its summary says ``failed``, and an operating-system error (a full disk) becomes a
    :class:`~rancf.errors.RunFailedError` naming the file and the time the files reach.
    """
    if not kept:
        store.discard()
        with contextlib.suppress(OSError):
            (out / "scenario.toml").unlink()
        return exc
    store.fail(_broken(model, store, exc))
    if isinstance(exc, OSError):
        where = f"{exc.filename}: " if exc.filename is not None else ""
        return RunFailedError(
            f"{where}{exc.strerror or exc}; the run stopped; {out} keeps its results up to "
            f"t = {store.saved_t or 0.0:g} s (summary.json says failed)"
        )
    return exc


class _StopFlag:
    """While active, SIGINT and SIGTERM set a flag instead of raising (polled between steps)."""

    def __init__(self) -> None:
        self.flag = False
        self._old: dict[int, Any] = {}

    def __call__(self) -> bool:
        return self.flag

    def _set(self, signum: int, frame: Any) -> None:
        self.flag = True

    def __enter__(self) -> _StopFlag:
        for sig in (signal.SIGINT, signal.SIGTERM):
            self._old[sig] = signal.signal(sig, self._set)
        return self

    def __exit__(self, *exc: object) -> None:
        for sig, old in self._old.items():
            signal.signal(sig, old)


def _broken(model: Any, store: Any, exc: BaseException) -> dict[str, Any]:
    """Summary of a run ended by an exception (the error path prints the message)."""
    from rancf.post.results import run_sizes

    kind = "interrupted" if isinstance(exc, KeyboardInterrupt) else "failed"
    text = str(exc)
    if isinstance(exc, OSError) and exc.strerror:
        text = f"{exc.filename}: {exc.strerror}" if exc.filename is not None else exc.strerror
    return {
        "status": kind,
        "message": " ".join(text.split()) or type(exc).__name__,
        "t_reached": store.saved_t,
        "outputs": store.n_rows,
        **run_sizes(model),
    }


def _report(args: argparse.Namespace, res: Any, summary: dict[str, Any], out: Path) -> int:
    from rancf.solvers.dynamic import DynamicStatus

    if res.status is DynamicStatus.FAILED:
        print(f"rancf: simulation failed: {res.message} (written to {out})", file=sys.stderr)
        return 3
    if res.status is DynamicStatus.INTERRUPTED:
        print(f"rancf: {res.message}; results so far written to {out}", file=sys.stderr)
        return 130
    if not args.quiet:
        per_step = summary["time_per_step_s"] or 0.0
        print(
            f"{summary['status']}: t = {summary['t_reached']:g} s, {summary['steps']} steps, "
            f"{summary['newton_iterations']} Newton iterations, "
            f"{summary['solve_wall_time_s']:.3f} s ({1e3 * per_step:.3f} ms/step) -> {out}"
        )
    return 0


OVERWRITE_HELP = (
    "replace the earlier run in --out (all of that folder's contents); without it --out must "
    "be a new or empty folder"
)


def add_parsers(sub: Any) -> None:
    """Register ``simulate`` on the ``rancf`` sub-parser set."""
    s = sub.add_parser(
        "simulate",
        help="run the dynamics of a scenario file",
        description="Run the dynamics of a scenario file into a run folder. NumPy's OpenBLAS "
        "is asked for one thread (OPENBLAS_NUM_THREADS=1) unless the environment sets it: "
        "the run makes no call its threads would share.",
    )
    s.add_argument("scenario", help="scenario TOML file")
    s.add_argument("--out", required=True, help="output directory (created if needed)")
    s.add_argument("--quiet", action="store_true", help="no progress bar or summary line")
    s.add_argument("--overwrite", action="store_true", help=OVERWRITE_HELP)
    s.add_argument(
        "--resume",
        action="store_true",
        help="go on with the run in --out from its last checkpoint (a killed, failed or "
        "finished run; a new or empty folder starts a new run)",
    )
    s.add_argument(
        "--t-end",
        type=float,
        default=None,
        metavar="SECONDS",
        help="end time instead of the scenario's solver.t_end (with --resume: extends a "
        "finished run)",
    )
    s.add_argument(
        "--checkpoint-every",
        type=float,
        default=10.0,
        metavar="SECONDS",
        help="write the result files every SECONDS of wall time while running (default 10)",
    )
    s.add_argument(
        "--max-output-gb",
        type=float,
        default=DEFAULT_MAX_OUTPUT_GB,
        metavar="GB",
        help="refuse a run whose stored states would need more disk than this "
        f"(default {DEFAULT_MAX_OUTPUT_GB:g})",
    )
    s.add_argument(
        "--threads",
        type=int,
        default=None,
        metavar="N",
        help="threads of the element loops (default: the idle cores this process may use where "
        "a body has enough elements to share, else 1; the results are the same bit for bit)",
    )
    s.set_defaults(func=_cmd_simulate)
