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

__all__ = ["add_parsers", "reactions_json"]


def reactions_json(sc: Any, model: Any, y: Any) -> list[dict[str, Any]]:
    """``static --json``'s ``"reactions"``: one object per support, in file order:
    ``{"at", "force", "moment"}`` (moment for clamps and rods)."""
    from rancf.bodies.reactions import support_reactions
    from rancf.solvers.equilibrium import EquilibriumProblem

    labels = sc.support_labels
    res = EquilibriumProblem(model).full_residual(y, 1.0)  # the full loads
    out = []
    for r in support_reactions(model, y, res, labels):
        item: dict[str, Any] = {"at": r.at, "force": r.force.tolist()}
        if r.moment is not None:
            item["moment"] = r.moment.tolist()
        out.append(item)
    return out


def _cmd_buckling(args: argparse.Namespace) -> int:
    from rancf.scenario import load_scenario
    from rancf.solvers.buckling import linear_buckling
    from rancf.solvers.static import solve_static

    plot = check_plot_path(args.plot) if args.plot else None
    if args.count < 1:
        raise InputError("--count", args.count, "an integer >= 1")
    sc = load_scenario(args.scenario)
    model = sc.build_model()
    y = None
    if args.about == "static":
        y = solve_static(model, sc.solver["load_steps"], method=sc.solver["static_method"]).y
    res = linear_buckling(model, args.count, args.about, y)
    if plot is not None:
        from rancf.post.plots import plot_buckling

        plot_buckling(model, res, plot, y)
    out = {
        "load_factors": res.load_factors.tolist(),
        "about": res.about,
        "eigenproblem": "symmetric" if res.symmetric else "general",
    }
    if args.json:
        from rancf.post.results import strict_json

        print(strict_json(out).rstrip())
    else:
        print(f"linear buckling about the {res.about} configuration (critical load factors):")
        for i, lam in enumerate(res.load_factors, 1):
            print(f"  mode {i:2d}  {lam:14.8g}")
        if plot is not None:
            print(f"mode shapes -> {plot}", file=sys.stderr)
    return 0


def _cmd_static(args: argparse.Namespace) -> int:
    import numpy as np

    from rancf.post.checks import run_warnings
    from rancf.post.results import LoadPath, sensor_table, strict_json, write_static_run
    from rancf.scenario import load_scenario
    from rancf.solvers.static import solve_static

    sc = load_scenario(args.scenario)
    if sc.needs_system:
        from rancf.cli.system import print_static, static_system

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
    if sc.needs_system:
        from rancf.cli.system import modes_system, print_modes

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
        "buckling", help="linear buckling load factors of a scenario's loads (K0 + λ Kσ) φ = 0"
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
