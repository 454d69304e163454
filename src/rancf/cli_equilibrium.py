"""Equilibrium on the command line: ``rancf buckling`` and the reactions of ``rancf static``."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from rancf.cli_io import check_plot_path
from rancf.errors import InputError

__all__ = ["add_parsers", "reactions_json"]


def reactions_json(sc: Any, model: Any, y: Any) -> list[dict[str, Any]]:
    """``static --json``'s ``"reactions"``: one object per support, in file order:
    ``{"at", "force", "moment"}`` (moment for clamps and rods)."""
    from rancf.model.reactions import support_reactions
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


def add_parsers(sub: Any) -> None:
    """Register ``buckling`` on the ``rancf`` sub-parser set."""
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
