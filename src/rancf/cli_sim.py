"""Sub-commands that run a scenario: ``simulate``, ``static`` and ``modes``."""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from rancf.errors import InputError

__all__ = ["add_parsers", "dynamic_options"]


def dynamic_options(solver: dict[str, Any]) -> Any:
    """:class:`DynamicOptions` from a scenario's ``[solver]`` table."""
    from rancf.solvers.dynamic import DynamicOptions

    return DynamicOptions(
        t_end=solver["t_end"],
        step=solver["step"],
        rho_inf=solver["rho_inf"],
        adaptive=solver["adaptive"],
        rtol=solver["rtol"],
        min_step=solver["min_step"],
        output_step=solver["output_step"],
        newton_tol=solver["newton_tol"],
        max_newton=solver["max_newton"],
        newton=solver["newton"],
    )


def _cmd_simulate(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from rancf.model.scenario import load_scenario
    from rancf.post.results import write_run
    from rancf.solvers.dynamic import DynamicStatus, integrate

    sc = load_scenario(args.scenario)
    model = sc.build_model()
    opts = dynamic_options(sc.solver)
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise InputError("--out", str(out), "a directory (it exists and is a file)")
    out.mkdir(parents=True, exist_ok=True)
    extra = {"scenario": str(Path(args.scenario).resolve())}

    stop = {"flag": False}

    def on_sigint(signum: int, frame: Any) -> None:
        stop["flag"] = True

    old = signal.signal(signal.SIGINT, on_sigint)
    bar = tqdm(
        total=opts.t_end,
        unit="s",
        disable=args.quiet,
        file=sys.stderr,
        leave=False,
        bar_format="{l_bar}{bar}| t = {n:.4g}/{total:.4g} s [{elapsed}<{remaining}]",
    )
    last = {"ckpt": time.monotonic()}

    def on_output(t: float, snapshot: Any) -> None:
        bar.update(t - bar.n)
        now = time.monotonic()
        if now - last["ckpt"] >= args.checkpoint_every:
            write_run(out, model, sc.sensors, snapshot(), extra)
            last["ckpt"] = now

    try:
        res = integrate(model, opts, on_output, lambda: stop["flag"])
    finally:
        bar.close()
        signal.signal(signal.SIGINT, old)
    summary = write_run(out, model, sc.sensors, res, extra)
    if res.status is DynamicStatus.FAILED:
        print(f"rancf: simulation failed: {res.message} (written to {out})", file=sys.stderr)
        return 3
    if res.status is DynamicStatus.INTERRUPTED:
        print(f"rancf: {res.message}; results so far written to {out}", file=sys.stderr)
        return 130
    if not args.quiet:
        print(
            f"{summary['status']}: t = {summary['t_reached']:g} s, {summary['steps']} steps, "
            f"{summary['newton_iterations']} Newton iterations, "
            f"{summary['solve_wall_time_s']:.3f} s ({1e3 * summary['time_per_step_s']:.3f} ms/step)"
            f" -> {out}"
        )
    return 0


def _cmd_static(args: argparse.Namespace) -> int:
    from rancf.model.scenario import load_scenario
    from rancf.post.results import sensor_table
    from rancf.solvers.static import solve_static

    sc = load_scenario(args.scenario)
    model = sc.build_model()
    res = solve_static(model, sc.solver["load_steps"])
    pos = model.node_positions(res.q)
    names, vals = sensor_table(model, sc.sensors, res.q)
    out = {
        "positions": pos.tolist(),
        "sensors": dict(zip(names, vals[0].tolist(), strict=True)),
        "load_factors": res.load_factors.tolist(),
        "newton_iterations": res.n_newton,
    }
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print(
            f"static equilibrium: {len(res.load_factors) - 1} load steps, "
            f"{res.n_newton} Newton iterations"
        )
        for k, v in out["sensors"].items():
            print(f"  {k:12s} {v: .9g}")
    return 0


def _cmd_modes(args: argparse.Namespace) -> int:
    from rancf.model.scenario import load_scenario
    from rancf.solvers.modal import natural_modes
    from rancf.solvers.static import solve_static

    sc = load_scenario(args.scenario)
    model = sc.build_model()
    about = args.about or sc.data["modes"]["about"]
    count = args.count if args.count is not None else sc.data["modes"]["count"]
    if count < 1:
        raise InputError("--count", count, "an integer >= 1")
    y = None
    if about == "static":
        y = solve_static(model, sc.solver["load_steps"]).y
    res = natural_modes(model, y, count)
    if args.plot:
        from rancf.post.plots import plot_modes

        plot_modes(model, res, args.plot, y)
    out = {
        "frequencies_hz": res.frequencies_hz.tolist(),
        "rigid_body_modes_removed": res.n_rigid,
        "about": about,
        "n_dofs_free": int(np.sum(~model.fixed)),
    }
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print(
            f"natural frequencies about the {about} configuration "
            f"({res.n_rigid} rigid-body mode(s) removed):"
        )
        for i, f in enumerate(res.frequencies_hz, 1):
            print(f"  mode {i:2d}  {f:12.6f} Hz")
        if np.any(res.frequencies_hz < 1e-6):
            print(
                "  note: zero-frequency modes that are not rigid-body motions are kept; for a "
                "curved spatial cable they are the out-of-plane bending the magnitude "
                "curvature does not resist (see README)."
            )
    return 0


def add_parsers(sub: Any) -> None:
    """Register ``simulate``, ``static`` and ``modes`` on the ``rancf`` sub-parser set."""
    s = sub.add_parser("simulate", help="run the dynamics of a scenario file")
    s.add_argument("scenario", help="scenario TOML file")
    s.add_argument("--out", required=True, help="output directory (created if needed)")
    s.add_argument("--quiet", action="store_true", help="no progress bar or summary line")
    s.add_argument(
        "--checkpoint-every",
        type=float,
        default=10.0,
        metavar="SECONDS",
        help="write the result files every SECONDS of wall time while running (default 10)",
    )
    s.set_defaults(func=_cmd_simulate)

    st = sub.add_parser("static", help="static equilibrium of a scenario (Newton, load steps)")
    st.add_argument("scenario")
    st.add_argument("--json", action="store_true", help="print one JSON object")
    st.set_defaults(func=_cmd_static)

    m = sub.add_parser("modes", help="natural frequencies and mode shapes of a scenario")
    m.add_argument("scenario")
    m.add_argument(
        "--count", type=int, default=None, help="number of modes (default [modes].count)"
    )
    m.add_argument(
        "--about",
        choices=["reference", "static"],
        default=None,
        help="linearize about the reference (default) or the static equilibrium",
    )
    m.add_argument("--json", action="store_true", help="print one JSON object")
    m.add_argument("--plot", metavar="FILE.png", default=None, help="write mode-shape plots")
    m.set_defaults(func=_cmd_modes)


def _cmd_example(args: argparse.Namespace) -> int:
    from rancf.studies import EXAMPLES
    from rancf.studies.common import example_path

    if args.action == "list":
        for name, what in EXAMPLES.items():
            print(f"{name:18s} {what}  ({example_path(name).name})")
        return 0
    if args.name is None:
        raise InputError("NAME", None, f"an example name: {', '.join(EXAMPLES)}")
    if args.name not in EXAMPLES:
        raise InputError("example", args.name, f"one of {', '.join(EXAMPLES)}")
    if args.out is None:
        raise InputError("--out", None, "an output directory")
    return _run_studies([args.name], Path(args.out), args.quick, args.workers)


def _cmd_report(args: argparse.Namespace) -> int:
    from rancf.studies import EXAMPLES

    return _run_studies(list(EXAMPLES), Path(args.out), args.quick, args.workers)


def _run_studies(names: list[str], out: Path, quick: bool, workers: int | None) -> int:
    """Run studies into ``out/<name>/`` and write the report: with one worker one after another
    in this process, else all at once (:func:`rancf.studies.parallel.run_studies_parallel`)."""
    from rancf.post.report import write_report
    from rancf.studies.parallel import run_studies_here, run_studies_parallel

    n = workers if workers is not None else (os.cpu_count() or 1)
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise InputError("--workers", workers, "an integer >= 1")
    out.mkdir(parents=True, exist_ok=True)
    where = "this process" if n == 1 else f"a local Dask cluster of {n} worker(s)"
    print(
        f"running {', '.join(names)}{' (quick)' if quick else ''} on {where} ...", file=sys.stderr
    )
    t0 = time.perf_counter()
    if n == 1:
        results = run_studies_here(names, out, quick)
    else:
        results = run_studies_parallel(names, out, quick, n)
    done = []
    for name in names:
        res, folder = results[name], out / name
        res.write_comparison_csv(folder)
        done.append((res, folder))
        print(f"  {name}: {len(res.figures)} figures, {res.wall_time_s:.1f} s", file=sys.stderr)
        for c in res.comparison:
            print(f"    {c.quantity:60s} paper {c.paper:>10s}   ours {c.ours}")
    wall = time.perf_counter() - t0
    path = write_report(out, done, quick, wall)
    print(f"report written to {path}")
    print(f"wall time {wall:.1f} s on {where}", file=sys.stderr)
    return 0


WORKERS_HELP = (
    "local Dask worker processes (default: the number of cores); 1 runs everything in this "
    "process, one run after another"
)


def add_study_parsers(sub: Any) -> None:
    """Register ``example`` and ``report``."""
    e = sub.add_parser("example", help="list or run the paper's examples")
    e.add_argument("action", choices=["list", "run"])
    e.add_argument("name", nargs="?", default=None, help="example name (see `rancf example list`)")
    e.add_argument("--out", default=None, help="output directory")
    e.add_argument(
        "--quick", action="store_true", help="reduced runs (fewer elements, shorter time)"
    )
    e.add_argument("--workers", type=int, default=None, help=WORKERS_HELP)
    e.set_defaults(func=_cmd_example)
    r = sub.add_parser("report", help="run every example and write one HTML report")
    r.add_argument("--out", required=True, help="output directory")
    r.add_argument(
        "--quick", action="store_true", help="reduced runs (fewer elements, shorter time)"
    )
    r.add_argument("--workers", type=int, default=None, help=WORKERS_HELP)
    r.set_defaults(func=_cmd_report)
