"""Sub-commands that run a scenario: ``simulate``, ``static`` and ``modes``."""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import signal
import sys
import time
from pathlib import Path
from typing import Any

from rancf.cli_io import OutputDir, check_plot_path
from rancf.errors import InputError, RunFailedError

__all__ = ["add_parsers", "DEFAULT_MAX_OUTPUT_GB"]

#: Default ``--max-output-gb``: the disk a run's stored states may take.
DEFAULT_MAX_OUTPUT_GB = 2.0


def _process_age() -> float:
    """Seconds since this process started (Linux ``/proc``; else since the CLI was imported)."""
    try:
        with open("/proc/self/stat", encoding="ascii") as fh:
            start_ticks = int(fh.read().rsplit(")", 1)[1].split()[19])
        with open("/proc/uptime", encoding="ascii") as fh:
            uptime = float(fh.read().split()[0])
        return max(0.0, uptime - start_ticks / os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):  # pragma: no cover - not Linux
        return time.monotonic() - _IMPORTED


_IMPORTED = time.monotonic()


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


def _cmd_simulate(args: argparse.Namespace) -> int:
    every = _positive("--checkpoint-every", args.checkpoint_every, "a finite number of seconds > 0")
    limit = _positive("--max-output-gb", args.max_output_gb, "a finite size in GB > 0")
    od = OutputDir(args.out, kind="run", overwrite=args.overwrite)  # checks the path up front
    from rancf.atomic import atomic_write
    from rancf.post.checks import run_warnings, section_warnings
    from rancf.post.history import HistoryStore, plan_run
    from rancf.post.results import run_summary
    from rancf.scenario import load_scenario
    from rancf.solvers.static import start_state

    sc = load_scenario(args.scenario)
    opts = sc.dynamic_options()
    system, outputs = plan_run(sc, limit)
    y_start, start_info = start_state(sc, system)
    copy = _scenario_text(args.scenario)
    out = od.path
    stop = _StopFlag()
    notes = _warn(section_warnings(system))  # likely unit mistakes: the run goes on
    with stop, od:
        info = {"scenario": str(Path(args.scenario).resolve()), "setup_wall_time_s": None}
        info.update(start_info)
        store = HistoryStore(out, outputs, {**info, "warnings": notes})
        try:
            atomic_write(out / "scenario.toml", copy)
            store.write_summary(_running(system, 0.0))
            res = _run(args, system, opts, store, stop, every, od.keep, y_start)
            summary = run_summary(system, res)
            store.flush()  # every row's derived outputs, the strain among them
            store.info["warnings"] = run_warnings(system, largest=outputs.largest_strain)
            store.finish(summary)
        except BaseException as exc:
            err = _end_broken(store, system, exc, od.kept, out)
            if err is exc:
                raise
            raise err from None
    _warn(store.info["warnings"][len(notes) :])
    return _report(args, res, {**summary, **store.info}, out)


def _warn(notes: list[str]) -> list[str]:
    """Print each warning as one line on standard error; returns them."""
    for note in notes:
        print(f"rancf: warning: {note}", file=sys.stderr)
    return notes


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


def _running(model: Any, t: float) -> dict[str, Any]:
    from rancf.post.results import run_sizes

    return {
        "status": "running",
        "message": f"running, t = {t:g} s",
        "t_reached": t,
        **run_sizes(model),
    }


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


#: A progress bar appears once a run has been stepping this long [s] (short runs stay silent).
PROGRESS_AFTER_S = 0.5


def _progress_bar(t_end: float, t: float) -> Any:
    from tqdm import tqdm  # imported only for runs long enough to show a bar

    return tqdm(
        total=t_end,
        initial=t,
        unit="s",
        file=sys.stderr,
        leave=False,
        bar_format="{l_bar}{bar}| t = {n:.4g}/{total:.4g} s [{elapsed}<{remaining}]",
    )


def _run(
    args: argparse.Namespace,
    model: Any,
    opts: Any,
    store: Any,
    stop: Any,
    every: float,
    started: Any,
    y_start: Any = None,
) -> Any:
    """Integrate into ``store`` from ``y_start`` (default the reference); ``started()`` once
    the first checkpoint is on disk."""
    from rancf.post.results import run_summary
    from rancf.solvers.dynamic import integrate

    bar: list[Any] = []
    pace = {"next": time.monotonic() + every, "every": every, "bar": math.inf}

    def on_start() -> None:
        store.info["setup_wall_time_s"] = _process_age()
        store.checkpoint(_running(model, 0.0))  # every file exists before the first step
        started()
        if not args.quiet:
            pace["bar"] = time.monotonic() + PROGRESS_AFTER_S

    def on_output(t: float, snapshot: Any) -> None:
        if bar:
            bar[0].update(t - bar[0].n)
        elif time.monotonic() >= pace["bar"]:
            bar.append(_progress_bar(opts.t_end, t))
        now = time.monotonic()
        if now >= pace["next"]:
            summary = {**run_summary(model, snapshot()), **_running(model, t)}
            store.checkpoint(summary)
            took = time.monotonic() - now
            pace["next"] = time.monotonic() + max(pace["every"], 4.0 * took)

    try:
        return integrate(
            model, opts, on_output, stop, sink=store, on_start=on_start, initial=y_start
        )
    finally:
        if bar:
            bar[0].close()


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


def _cmd_static(args: argparse.Namespace) -> int:
    import numpy as np

    from rancf.cli_equilibrium import reactions_json
    from rancf.post.checks import run_warnings
    from rancf.post.results import LoadPath, sensor_table, strict_json, write_static_run
    from rancf.scenario import load_scenario
    from rancf.solvers.static import solve_static

    sc = load_scenario(args.scenario)
    if sc.is_system:
        from rancf.cli_system import print_static, static_system

        copy = None if args.out is None else _scenario_text(args.scenario)
        doc = static_system(args, sc, copy)
        if args.json:
            print(strict_json(doc).rstrip())
        else:
            print_static(doc, args.out)
        return 0
    od = None if args.out is None else OutputDir(args.out, kind="run", overwrite=args.overwrite)
    model = sc.build_model()
    path = LoadPath(model, sc.support_labels)  # the load path, for --out
    method = sc.solver["static_method"]
    if od is None:
        res = solve_static(model, sc.solver["load_steps"], method=method)
    else:
        from rancf.atomic import atomic_write

        copy = _scenario_text(args.scenario)
        out_dir = od.path
        with od:
            info = {"scenario": str(Path(args.scenario).resolve())}
            try:
                res = solve_static(
                    model, sc.solver["load_steps"], on_step=path.record, method=method
                )
                info.update(status="completed", message="reached the end of the load path")
            except BaseException as exc:
                kind = "interrupted" if isinstance(exc, KeyboardInterrupt) else "failed"
                lam = path.steps[-1][0] if path.steps else 0.0
                text = " ".join(str(exc).split()) or f"{kind} at load factor {lam:g}"
                info.update(status=kind, message=text)
                raise
            finally:
                if path.steps:  # what converged is kept, also when a later increment fails
                    doc = write_static_run(out_dir, path, sc.sensors, info)
                    atomic_write(out_dir / "scenario.toml", copy)
                    od.keep()
    if path.steps:  # the load path's outputs tracked the largest strain
        notes = _warn(doc["warnings"])
    else:
        notes = _warn(run_warnings(model, res.load_factors[-1:], res.q[None], static=True))
    pos = model.node_positions(res.q)
    lf = res.load_factors[-1:]
    names, vals = sensor_table(model, sc.sensors, res.q, static=True, t=lf)
    out = {
        "positions": pos.tolist(),
        "sensors": dict(zip(names, vals[0].tolist(), strict=True)),
        "load_factors": res.load_factors.tolist(),
        "newton_iterations": res.n_newton,
        "method": res.method,
        "wall_time_s": res.wall_time,
        "reactions": reactions_json(sc, model, res.y),
        "warnings": notes,
    }
    if args.json:
        print(strict_json(out).rstrip())
    else:
        print(
            f"static equilibrium: {len(res.load_factors) - 1} load steps, "
            f"{res.n_newton} Newton iterations" + (f" -> {od.path}" if od is not None else "")
        )
        for k, v in out["sensors"].items():
            print(f"  {k:12s} {v: .9g}")
        # forces below the round-off of the internal forces (100 ε EA) print as 0
        floor = 100 * np.finfo(float).eps * model.props.ea
        for r in out["reactions"]:
            moment = f"  moment {_vec(r['moment'], floor)}" if "moment" in r else ""
            print(f"  reaction at {r['at']!s:6s} force {_vec(r['force'], floor)}{moment}")
    return 0


def _vec(v: list[float], floor: float) -> str:
    return "[" + ", ".join(f"{x:.9g}" if abs(x) > floor else "0" for x in v) + "]"


def _cmd_modes(args: argparse.Namespace) -> int:
    import numpy as np

    from rancf.post.checks import run_warnings
    from rancf.post.results import strict_json
    from rancf.scenario import load_scenario
    from rancf.solvers.modal import natural_modes
    from rancf.solvers.static import solve_static

    plot = check_plot_path(args.plot) if args.plot else None
    if args.count is not None and args.count < 1:
        raise InputError("--count", args.count, "an integer >= 1")
    sc = load_scenario(args.scenario)
    if sc.is_system:
        from rancf.cli_system import modes_system, print_modes

        doc = modes_system(args, sc)
        if args.json:
            print(strict_json(doc).rstrip())
        else:
            print_modes(doc)
        return 0
    model = sc.build_model()
    about = args.about or sc.data["modes"]["about"]
    count = args.count if args.count is not None else sc.data["modes"]["count"]
    key = "--count" if args.count is not None else f"{sc.path}: modes.count"
    n_free = int(np.sum(~model.fixed))
    if count > n_free:
        raise InputError(key, count, f"at most {n_free} (the free coordinates of this model)")
    y = None
    if about == "static":
        y = solve_static(model, sc.solver["load_steps"], method=sc.solver["static_method"]).y
    static = [] if y is None else [model.q_from_y(y)]  # the strain of the equilibrium
    notes = _warn(run_warnings(model, np.ones(len(static)), np.array(static), static=True))
    res = natural_modes(model, y, count)
    if res.frequencies_hz.size < count:
        raise InputError(
            key,
            count,
            f"at most {res.frequencies_hz.size}: this model has {n_free} free coordinates and "
            f"{res.n_rigid} rigid-body mode(s), which are removed",
        )
    if plot is not None:
        from rancf.post.plots import plot_modes

        plot_modes(model, res, plot, y)
    growth = res.growth_rates if res.growth_rates is not None else np.zeros_like(res.frequencies_hz)
    out = {
        "frequencies_hz": res.frequencies_hz.tolist(),
        "growth_rates_per_s": growth.tolist(),
        "eigenproblem": "symmetric" if res.symmetric else "general",
        "rigid_body_modes_removed": res.n_rigid,
        "about": about,
        "n_dofs_free": int(np.sum(~model.fixed)),
        "warnings": notes,
    }
    if args.json:
        print(strict_json(out).rstrip())
    else:
        print(
            f"natural frequencies about the {about} configuration "
            f"({res.n_rigid} rigid-body mode(s) removed):"
        )
        for i, (f, g) in enumerate(zip(res.frequencies_hz, growth, strict=True), 1):
            extra = "" if res.symmetric else f"  growth rate {g:.6g} 1/s"
            print(f"  mode {i:2d}  {f:12.6f} Hz{extra}")
        if not res.symmetric:
            print(
                "  note: general eigenproblem (the point moments' load stiffness is not "
                "symmetric);\n  a growth rate > 0 is an unstable mode: flutter (frequency > 0) "
                "or divergence (frequency 0)."
            )
        if np.any(res.frequencies_hz < 1e-6):
            print(
                "  note: zero-frequency modes that are not rigid-body motions are kept; for a "
                "curved spatial cable they are the out-of-plane bending the magnitude "
                'curvature does not resist: use mesh.element = "rod" (torsion and out-of-plane '
                "bending stiffness) for curved spatial structures (docs/guide/rods.md)."
            )
    if plot is not None:  # after the JSON object, on standard error: stdout stays one object
        print(f"mode shapes written to {plot}", file=sys.stderr if args.json else sys.stdout)
    return 0


OVERWRITE_HELP = (
    "replace the earlier run in --out (all of that folder's contents); without it --out must "
    "be a new or empty folder"
)


def add_parsers(sub: Any) -> None:
    """Register ``simulate``, ``static`` and ``modes`` on the ``rancf`` sub-parser set."""
    s = sub.add_parser("simulate", help="run the dynamics of a scenario file")
    s.add_argument("scenario", help="scenario TOML file")
    s.add_argument("--out", required=True, help="output directory (created if needed)")
    s.add_argument("--quiet", action="store_true", help="no progress bar or summary line")
    s.add_argument("--overwrite", action="store_true", help=OVERWRITE_HELP)
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
    s.set_defaults(func=_cmd_simulate)

    st = sub.add_parser("static", help="static equilibrium of a scenario (Newton, load steps)")
    st.add_argument("scenario")
    st.add_argument("--json", action="store_true", help="print one JSON object")
    st.add_argument(
        "--out",
        default=None,
        help="also write the load path as a run directory (λ in place of t) for export, plot "
        "and animate",
    )
    st.add_argument("--overwrite", action="store_true", help=OVERWRITE_HELP)
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
