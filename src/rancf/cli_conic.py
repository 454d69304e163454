"""``rancf conic``: a conic arc from chord, end angles and one interior point."""

from __future__ import annotations

import argparse
from typing import Any

from rancf.cli_io import check_plot_path
from rancf.errors import InputError

__all__ = ["add_parsers", "MAX_ELEMENTS"]

#: Largest ``--elements`` (the command prints one table row per element).
MAX_ELEMENTS = 1000


#: Argument names of the geometry functions -> options of ``rancf conic``.
_OPTIONS = {
    "chord": "--chord",
    "angles (theta0)": "--angles T0",
    "angles (theta1)": "--angles T1",
    "point": "--point",
    "k": "--k",
}


def _cmd_conic(args: argparse.Namespace) -> int:
    try:
        return _conic(args)
    except InputError as exc:
        if exc.parameter not in _OPTIONS:
            raise
        raise InputError(_OPTIONS[exc.parameter], exc.value, exc.allowed) from None


def _conic(args: argparse.Namespace) -> int:
    import numpy as np

    from rancf.elements.mapping import K_RANGE, conic_element, kopt
    from rancf.geometry.conic import conic_arc
    from rancf.model.mesh import check_element_count, mesh_conic

    n = check_element_count(args.elements, "--elements")
    if n > MAX_ELEMENTS:
        raise InputError("--elements", n, f"at most {MAX_ELEMENTS} (one table row per element)")
    plot = check_plot_path(args.plot) if args.plot else None
    if args.k is not None and not K_RANGE[0] <= args.k <= K_RANGE[1]:  # NaN included
        lo, hi = K_RANGE
        raise InputError("--k", args.k, f"a mapping factor in [{lo:g}, {hi:g}] (as mesh.k)")
    conic = conic_arc(args.chord, args.angles, args.point)
    k_opt = kopt(conic)
    single = conic_element(conic, args.k)
    mesh = mesh_conic(conic, n, "opt" if args.k is None else args.k, args.spacing)
    ratios = mesh.gradient_ratios()
    elements = []
    for j in range(n):
        elements.append(
            {
                "k": float(mesh.k[j]),
                "weights": mesh.weights[j].tolist(),
                "scale": float(mesh.scales[j]),
                "nodal_coordinates": mesh.element_nodal()[j].ravel().tolist(),
                "gradient_ratio": float(ratios[j]),
            }
        )
    out = {
        "type": conic.kind,
        "circular": conic.is_circular(),
        "omega": conic.omega,
        "chord": conic.chord,
        "angles_deg": [float(a) for a in args.angles],
        "point": [float(p) for p in args.point],
        "control_points": [conic.p0.tolist(), conic.p1.tolist(), conic.p2.tolist()],
        "arc_length": conic.arc_length(),
        "kopt": k_opt,
        "k": single.k,
        "gradient_ratio": single.gradient_ratio,
        "gradient_ratio_kopt": float(conic_element(conic, k_opt).gradient_ratio),
        "spacing": args.spacing,
        "elements": elements,
    }
    if plot is not None:
        from rancf.post.conic_plots import plot_conic

        plot_conic(conic, k_opt, single.k, plot, n)
    if args.json:
        from rancf.post.results import strict_json

        print(strict_json(out).rstrip())
    else:
        circ = " (circular arc)" if out["circular"] else ""
        print(f"conic type      {conic.kind}{circ}")
        print(f"omega           {conic.omega:.6f}")
        print(f"arc length      {out['arc_length']:.6f} m")
        print(f"Kopt            {k_opt:.4f}   (gradient ratio {out['gradient_ratio_kopt']:.4f})")
        print(f"K used          {single.k:.4f}   (gradient ratio {single.gradient_ratio:.4f})")
        print(f"weights         {np.array2string(single.weights, precision=6)}")
        print(f"{n} element(s), {args.spacing} spacing:")
        print("   #        K   gradient ratio    weights")
        for j, e in enumerate(elements):
            w = ", ".join(f"{x:.5f}" for x in e["weights"])
            print(f"  {j:2d}  {e['k']:.4f}   {e['gradient_ratio']:14.5f}    [{w}]")
        if args.plot:
            print(f"plot written to {args.plot}")
    return 0


def add_parsers(sub: Any) -> None:
    """Register ``conic``."""
    c = sub.add_parser(
        "conic",
        help="define a conic arc from chord, end angles and one interior point",
        description="Conic arc in the local frame P0=(0,0), P2=(L,0); reports ω, type, arc "
        "length, Kopt and the element definition(s).",
    )
    c.add_argument("--chord", type=float, required=True, help="chord length L [m], > 0")
    c.add_argument(
        "--angles",
        type=float,
        nargs=2,
        required=True,
        metavar=("T0", "T1"),
        help="end tangent-to-chord angles [deg], each in (0, 90)",
    )
    c.add_argument(
        "--point",
        type=float,
        nargs=2,
        required=True,
        metavar=("X", "Y"),
        help="an interior point of the arc [m], strictly inside the tangent triangle",
    )
    c.add_argument("--k", type=float, default=None, help="mapping factor K in (0, 1); default Kopt")
    c.add_argument(
        "--elements", type=int, default=1, help=f"number of elements, 1..{MAX_ELEMENTS} (default 1)"
    )
    c.add_argument(
        "--spacing",
        choices=["arc", "parameter"],
        default="arc",
        help="element ends at equal arc length (default) or equal conic parameter",
    )
    c.add_argument("--json", action="store_true", help="print one JSON object")
    c.add_argument("--plot", metavar="FILE.png", default=None, help="write the K-study figure")
    c.set_defaults(func=_cmd_conic)
