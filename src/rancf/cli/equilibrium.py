"""Equilibrium and linearized analyses on the command line: ``rancf static``, ``rancf modes``
and ``rancf buckling``."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from rancf.cli.io import OutputDir, check_plot_path
from rancf.cli.sim import OVERWRITE_HELP, _scenario_text, _warn
from rancf.errors import InputError

__all__ = ["add_parsers"]


def _cmd_buckling(args: argparse.Namespace) -> int:
    from rancf.runs.buckling import run_buckling
    from rancf.scenario import load_scenario
    from rancf.solvers.form import form_lines, form_summary

    plot = check_plot_path(args.plot) if args.plot else None
    if args.count < 1:
        raise InputError("--count", args.count, "an integer >= 1")
    sc = load_scenario(args.scenario)
    run = run_buckling(sc, args.count, args.about)
    _warn(run.warnings)
    res = run.result
    if plot is not None:
        from rancf.post.plots import plot_buckling

        plot_buckling(run.system, res, plot, run.y)
    out = {
        "load_factors": res.load_factors.tolist(),
        "about": res.about,
        "eigenproblem": "symmetric" if res.symmetric else "general",
        **form_summary(sc),
    }
    if args.json:
        from rancf.post.results import strict_json

        print(strict_json(out).rstrip())
    else:
        print(f"buckling about the {res.about} configuration (critical load factors):")
        for line in form_lines(sc):
            print(f"  {line}")
        for i, lam_i in enumerate(res.load_factors, 1):
            print(f"  mode {i:2d}  {lam_i:14.8g}")
        if plot is not None:
            print(f"mode shapes -> {plot}", file=sys.stderr)
    return 0


def _cmd_static(args: argparse.Namespace) -> int:
    import numpy as np

    from rancf.post.checks import element_notes, run_warnings
    from rancf.post.results import strict_json
    from rancf.post.static_run import positions_json, reactions_json
    from rancf.runs.static import run_static
    from rancf.scenario import load_scenario

    sc = load_scenario(args.scenario)
    od = None if args.out is None else OutputDir(args.out, kind="run", overwrite=args.overwrite)
    if od is None:
        run = run_static(sc)
    else:
        from rancf.atomic import atomic_write

        copy = _scenario_text(args.scenario)

        def keep(_summary: dict[str, Any]) -> None:  # kept also when a later increment fails
            atomic_write(od.path / "scenario.toml", copy)
            od.keep()

        with od:
            info = {"scenario": str(Path(args.scenario).resolve())}
            run = run_static(sc, od.path, info, keep)
    system, res = run.system, run.result
    # the load path's outputs tracked the largest strain (--out), else the last state's
    largest = run.outputs.largest_strain
    if run.summary is not None:
        notes = _warn(run.notes + run.summary["warnings"])
    else:
        notes = _warn(
            run.notes
            + run_warnings(
                system, static=True, largest=largest, by_body=run.outputs.largest_by_body
            )
        )
    for note in element_notes(system):  # a curved spatial cable's missing stiffness
        print(f"rancf: {note}", file=sys.stderr)
    out = {
        "positions": positions_json(system, res.q),
        "sensors": run.sensors,
        "load_factors": res.load_factors.tolist(),
        "newton_iterations": res.n_newton,
        "relaxation_steps": res.relaxation_steps,
        "method": res.method,
        "wall_time_s": res.wall_time,
        "reactions": reactions_json(run.outputs, res.y, res.lam),
        "warnings": notes,
        **run.form,
    }
    if args.json:
        print(strict_json(out).rstrip())
        return 0
    relaxed = f", {res.relaxation_steps} relaxation steps" if res.relaxation_steps else ""
    where = f" -> {od.path}" if od is not None else ""
    steps = f"{len(res.load_factors) - 1} load steps, {res.n_newton} Newton iterations"
    if res.method == "linear":
        steps = "small displacements, one solve with the reference's stiffness"
    print(f"static equilibrium ({res.method}): {steps}{relaxed}{where}")
    for line in run.form_lines:
        print(f"  {line}")
    wide = max((len(k) for k in out["sensors"]), default=0)  # the columns aligned
    for k, v in out["sensors"].items():
        print(f"  {k:{max(12, wide)}s} {v: .9g}")
    # forces below the round-off of the internal forces (100 ε EA) print as 0
    floor = 100 * np.finfo(float).eps * max((b.props.ea for b in system.flex), default=0.0)
    wide = max((len(str(r["at"])) for r in out["reactions"]), default=0)
    for r in out["reactions"]:
        moment = f"  moment {_vec(r['moment'], floor)}" if "moment" in r else ""
        at = f"{r['at']!s:{max(6, wide)}s}"
        print(f"  reaction at {at} force {_vec(r['force'], floor)}{moment}")
    return 0


def _vec(v: list[float], floor: float) -> str:
    return "[" + ", ".join(f"{x:.9g}" if abs(x) > floor else "0" for x in v) + "]"


def _cmd_modes(args: argparse.Namespace) -> int:
    import numpy as np

    from rancf.post.results import strict_json
    from rancf.runs.modes import run_modes
    from rancf.scenario import load_scenario
    from rancf.solvers.form import form_lines, form_summary

    plot = check_plot_path(args.plot) if args.plot else None
    if args.count is not None and args.count < 1:
        raise InputError("--count", args.count, "an integer >= 1")
    sc = load_scenario(args.scenario)
    key = "--count" if args.count is not None else None
    run = run_modes(sc, args.count, args.about, count_key=key)
    system, res, cam = run.system, run.result, run.campbell
    notes = _warn(run.warnings)
    shapes_plot = None
    if plot is not None:
        from rancf.post.plots import plot_modes

        shapes_plot = plot if cam is None else _shapes_path(plot)
        plot_modes(system, res, shapes_plot, run.y)
    out = {
        "frequencies_hz": res.frequencies_hz.tolist(),
        "growth_rates_per_s": res.growth_rates.tolist(),
        "eigenproblem": "symmetric" if res.symmetric else "general",
        "rigid_body_modes_removed": res.n_rigid,
        "about": run.about,
        "n_dofs_free": run.n_free,
        "constraints": system.m,
        "warnings": notes,
        **form_summary(sc),
    }
    if cam is not None:
        out["campbell"] = {
            "spin_rates": cam.spin_rates.tolist(),
            "labels": list(cam.labels),
            "frequencies_hz": cam.frequencies_hz.tolist(),
            "growth_rates_per_s": cam.growth_rates.tolist(),
        }
        if plot is not None:
            from rancf.post.plots import plot_campbell

            plot_campbell(cam, plot)
    if args.json:
        print(strict_json(out).rstrip())
    else:
        print(
            f"natural frequencies about the {run.about} configuration "
            f"({res.n_rigid} rigid-body mode(s) removed):"
        )
        for line in form_lines(sc):
            print(f"  {line}")
        for i, (f, g) in enumerate(zip(res.frequencies_hz, res.growth_rates, strict=True), 1):
            extra = "" if res.symmetric and g == 0 else f"  growth rate {g:.6g} 1/s"
            print(f"  mode {i:2d}  {f:12.6f} Hz{extra}")
        if not res.symmetric:
            print(
                "  note: general eigenproblem (the tangent is not symmetric: point moments, "
                "friction);\n  a growth rate > 0 is an unstable mode: flutter (frequency > 0) "
                "or divergence (frequency 0)."
            )
        if np.any(res.frequencies_hz < 1e-6) and not np.any(res.growth_rates > 0):
            print(
                "  note: zero-frequency modes that are not rigid-body motions are kept; for a "
                "curved spatial cable they are the out-of-plane bending the magnitude "
                'curvature does not resist: use mesh.element = "rod" (torsion and out-of-plane '
                "bending stiffness) for curved spatial structures (docs/guide/rods.md)."
            )
        if "campbell" in out:
            _print_campbell(out["campbell"])
    if plot is not None:  # after the JSON object, on standard error: stdout stays one object
        stream = sys.stderr if args.json else sys.stdout
        if "campbell" in out:
            print(f"Campbell diagram written to {plot}", file=stream)
        print(f"mode shapes written to {shapes_plot}", file=stream)
    return 0


def _shapes_path(plot: Path) -> Path:
    """Where the mode shapes go when ``--plot`` draws the Campbell diagram: ``NAME-shapes``."""
    plot = Path(plot)
    return plot.with_name(f"{plot.stem}-shapes{plot.suffix}")


def _print_campbell(cam: dict[str, Any]) -> None:
    """The Campbell table: one row per spin rate."""
    print(
        "frequencies about the steady rotation (Hz) against the spin rate (rad/s), each "
        "column one mode followed by its shape:"
    )
    print("  " + " " * 10 + "  " + " ".join(f"{lab:>11s}" for lab in cam["labels"]))
    for rate, row in zip(cam["spin_rates"], cam["frequencies_hz"], strict=True):
        print(f"  {rate:10.4g}  " + " ".join(f"{f:11.6f}" for f in row))


def add_parsers(sub: Any) -> None:
    """Register ``static``, ``modes`` and ``buckling`` on the ``rancf`` sub-parser set."""
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

    b = sub.add_parser(
        "buckling",
        help="buckling load factors of a scenario's loads (linearized, located on the static path)",
    )
    b.add_argument("scenario")
    b.add_argument("--count", type=int, default=3, help="number of load factors (default 3)")
    b.add_argument(
        "--about",
        choices=["reference", "static"],
        default="reference",
        help="linearize about the reference (default) or the static equilibrium (pre-loaded)",
    )
    b.add_argument("--json", action="store_true", help="print one JSON object")
    b.add_argument("--plot", metavar="FILE.png", default=None, help="write mode-shape plots")
    b.set_defaults(func=_cmd_buckling)
