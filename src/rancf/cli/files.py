"""Sub-commands around the shipped files: ``example``, ``report`` and ``schema``.

``rancf example list | run NAME --out DIR | copy NAME DIR`` lists, runs (a paper study, or
another shipped scenario with the analyses it is meant for) or copies (to edit) the scenario
files in ``rancf/examples``; ``rancf report``
runs every study into one HTML report; ``rancf schema`` prints the scenario JSON Schema.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

from rancf.cli.io import OutputDir, check_out_dir
from rancf.errors import InputError

__all__ = ["add_parsers", "shipped_scenarios"]


def shipped_scenarios() -> dict[str, str]:
    """Shipped scenario names -> one-line description (paper studies first)."""
    from importlib import resources

    from rancf.studies.catalog import EXAMPLES

    out = dict(EXAMPLES)
    for f in sorted(resources.files("rancf.examples").iterdir(), key=lambda p: p.name):
        name = f.name.removesuffix(".toml")
        if f.name.endswith(".toml") and name not in out:
            first = f.read_text(encoding="utf-8").splitlines()[0]
            out[name] = first.lstrip("# ").rstrip(".") if first.startswith("#") else "scenario"
    return out


def _scenario_name(name: str) -> str:
    names = shipped_scenarios()
    if name not in names:
        raise InputError("NAME", name, f"one of {', '.join(names)} (see `rancf example list`)")
    return name


def _cmd_list(args: argparse.Namespace) -> int:
    from rancf.studies import SCENARIO_ANALYSES

    for name, what in shipped_scenarios().items():
        runs = SCENARIO_ANALYSES.get(name)
        how = f"; run: {', '.join(runs)}" if runs else ""
        print(f"{name:18s} {what}  ({name}.toml{how})")
    return 0


def _cmd_copy(args: argparse.Namespace) -> int:
    from rancf.atomic import atomic_write
    from rancf.studies.catalog import example_path

    name = _scenario_name(args.name)
    target = Path(args.dir) / f"{name}.toml"
    if target.exists() and not args.force:
        raise InputError("DIR", args.dir, f"a directory without {target.name} (or use --force)")
    with OutputDir(Path(args.dir), "DIR") as od:
        atomic_write(target, example_path(name).read_bytes())
        od.keep()
    print(f"wrote {target}")
    return 0


def _cmd_run(args: argparse.Namespace) -> int:
    from rancf.studies import EXAMPLES, SCENARIO_ANALYSES

    name = _scenario_name(args.name)
    if name not in EXAMPLES and name not in SCENARIO_ANALYSES:  # pragma: no cover - tested
        raise InputError("NAME", name, "a shipped scenario that `rancf example run` knows")
    out = check_out_dir(args.out)
    return _run_studies([name], out, args.quick, args.workers, nested=False)


def _cmd_report(args: argparse.Namespace) -> int:
    from rancf.studies import EXAMPLES

    out = check_out_dir(args.out)
    return _run_studies(list(EXAMPLES), out, args.quick, args.workers, nested=True)


def _workers(workers: int | None) -> int:
    n = workers if workers is not None else (os.cpu_count() or 1)
    if n < 1:
        raise InputError("--workers", workers, "an integer >= 1")
    return n


def _run_studies(
    names: list[str], out: Path, quick: bool, workers: int | None, nested: bool
) -> int:
    """Run studies into ``out`` (one sub-folder each when ``nested``) and write the report.

    With one worker every run happens in this process, one after another; with more, the
    studies' mesh grids go to a local Dask cluster (:mod:`rancf.studies.parallel`).
    """
    from rancf.studies import runs_a_grid
    from rancf.studies.parallel import run_studies_here, run_studies_parallel
    from rancf.studies.report import write_report

    n = _workers(workers)
    if not any(runs_a_grid(name) for name in names):
        n = 1  # no grid to share out: everything runs here
    where = "this process" if n == 1 else f"a local Dask cluster of {n} worker(s)"
    print(
        f"running {', '.join(names)}{' (quick)' if quick else ''} on {where} ...", file=sys.stderr
    )
    t0 = time.perf_counter()
    # one sub-folder per study, or one study with its files directly in ``out``
    folders = {name: out / name for name in names} if nested else {names[0]: out}
    results: dict[str, Any] = {}  # filled as studies finish
    with OutputDir(out) as od:
        od.keep()  # what the studies compute stays, even if a later one fails or is interrupted
        try:
            if n == 1:
                run_studies_here(folders, quick, results)
            else:
                run_studies_parallel(folders, quick, n, results)
        finally:
            done = []
            for name in (name for name in names if name in results):
                res, folder = results[name], folders[name]
                if res.comparison:  # the paper studies; other scenarios have no paper to check
                    res.write_comparison_csv(folder)
                done.append((res, folder))
                print(
                    f"  {name}: {len(res.figures)} figures, {res.wall_time_s:.1f} s",
                    file=sys.stderr,
                )
                for c in res.comparison:
                    print(f"    {c.quantity:60s} paper {c.paper:>10s}   ours {c.ours}")
            wall = time.perf_counter() - t0
            unfinished = [name for name in names if name not in results]
            if done or not unfinished:
                path = write_report(out, done, quick, wall, unfinished, _heading(names))
            if unfinished and done:
                print(
                    f"partial report ({len(done)} of {len(names)} studies; not finished: "
                    f"{', '.join(unfinished)}) written to {path}",
                    file=sys.stderr,
                )
    print(f"report written to {path}")
    print(f"wall time {wall:.1f} s on {where}", file=sys.stderr)
    return 0


def _heading(names: list[str]) -> tuple[str, str] | None:
    """Title and introduction of the report of a shipped scenario that is not a paper study."""
    from rancf.studies import EXAMPLES

    if all(name in EXAMPLES for name in names):
        return None  # the paper studies' own heading
    return (
        f"rancf: the shipped scenario {', '.join(names)}",
        f"The shipped scenario run by <code>rancf example run {' '.join(names)}</code>; "
        "every file its analyses wrote is in this folder.",
    )


def _cmd_schema(args: argparse.Namespace) -> int:
    from rancf.scenario.schema import scenario_schema

    print(json.dumps(scenario_schema(), indent=2))
    return 0


WORKERS_HELP = (
    "workers of a local Dask cluster, threads of this process (default: the number of cores); "
    "1 runs everything in this process, one run after another"
)


def add_parsers(sub: Any) -> None:
    """Register ``example`` (``list``, ``run``, ``copy``), ``report`` and ``schema``."""
    e = sub.add_parser("example", help="list, run or copy the shipped scenarios")
    actions = e.add_subparsers(dest="action", required=True)
    lst = actions.add_parser("list", help="list the shipped scenarios")
    lst.set_defaults(func=_cmd_list)
    run = actions.add_parser(
        "run", help="run a paper study or a shipped scenario, with a report (report.html)"
    )
    run.add_argument("name", metavar="NAME", help="a shipped scenario (see `rancf example list`)")
    run.add_argument("--out", required=True, help="output directory (created if needed)")
    run.add_argument("--quick", action="store_true", help="reduced runs (fewer elements)")
    run.add_argument("--workers", type=int, default=None, help=WORKERS_HELP)
    run.set_defaults(func=_cmd_run)
    cp = actions.add_parser("copy", help="write a shipped scenario file into DIR, to edit")
    cp.add_argument("name", metavar="NAME", help="a scenario (see `rancf example list`)")
    cp.add_argument("dir", metavar="DIR", help="directory (created if needed)")
    cp.add_argument("--force", action="store_true", help="overwrite DIR/NAME.toml")
    cp.set_defaults(func=_cmd_copy)

    r = sub.add_parser("report", help="run every paper study and write one HTML report")
    r.add_argument("--out", required=True, help="output directory")
    r.add_argument("--quick", action="store_true", help="reduced runs (fewer elements)")
    r.add_argument("--workers", type=int, default=None, help=WORKERS_HELP)
    r.set_defaults(func=_cmd_report)

    s = sub.add_parser("schema", help="print the scenario file format as a JSON Schema")
    s.set_defaults(func=_cmd_schema)
