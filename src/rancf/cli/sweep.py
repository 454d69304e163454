"""The ``rancf sweep`` sub-command."""

from __future__ import annotations

import argparse
from typing import Any

from rancf.errors import InputError

__all__ = ["add_parsers"]


def _cmd_sweep(args: argparse.Namespace) -> int:
    from rancf.cli.sim import one_blas_thread

    one_blas_thread()  # its runs' processes and threads: one BLAS thread each
    from rancf.cli.io import OutputDir
    from rancf.sweep.cluster import check_scheduler
    from rancf.sweep.engine import run_sweep
    from rancf.sweep.spec import load_sweep

    if args.scheduler is not None:
        check_scheduler(args.scheduler)
    if args.workers is not None and args.workers < 1:
        raise InputError("--workers", args.workers, "an integer >= 1")
    if args.threads is not None and args.threads < 1:
        raise InputError("--threads", args.threads, "an integer >= 1")
    if args.threads is not None and (args.scheduler or args.workers):
        raise InputError("--threads", args.threads, "without --scheduler and --workers (Dask's)")
    od = OutputDir(args.out, kind="sweep")
    spec = load_sweep(args.sweep)
    with od:
        try:
            rep = run_sweep(
                spec, od.path, args.scheduler, args.workers, not args.quiet, args.threads
            )
        finally:
            if (od.path / "results.csv").is_file():
                od.keep()  # the runs done so far stay, also after an interrupt
    where = args.scheduler or f"a local cluster of {args.workers or 'all'} worker(s)"
    if args.threads is not None:
        where = f"{args.threads} thread(s) of this process"
    warned = f", {rep.warned} with warnings (its column)" if rep.warned else ""
    print(
        f"{rep.total} run(s): {rep.skipped} already finished, {rep.ran} run on {where}, "
        f"{rep.failed} failed{warned} -> {rep.csv_path}"
    )
    return 0


def add_parsers(sub: Any) -> None:
    """Register ``sweep``."""
    s = sub.add_parser(
        "sweep",
        help="run a grid of scenario variants in parallel on Dask",
        description="Runs the Cartesian product of SWEEP.toml's [grid] on a local Dask cluster "
        "(default) or an existing scheduler; one folder per run under OUT/runs, one row per run "
        "in OUT/results.csv; finished runs are skipped when the command is repeated. NumPy's "
        "OpenBLAS is asked for one thread in every run (OPENBLAS_NUM_THREADS=1) unless the "
        "environment sets it.",
    )
    s.add_argument("sweep", metavar="SWEEP.toml")
    s.add_argument("--out", required=True, help="output directory")
    s.add_argument(
        "--scheduler", default=None, metavar="ADDRESS", help="existing scheduler, tcp://host:port"
    )
    s.add_argument(
        "--workers", type=int, default=None, help="local worker processes (default: cores)"
    )
    s.add_argument(
        "--threads",
        type=int,
        default=None,
        help="run on N threads of this process instead of Dask (one model a run)",
    )
    s.add_argument("--quiet", action="store_true", help="no progress bar")
    s.set_defaults(func=_cmd_sweep)
