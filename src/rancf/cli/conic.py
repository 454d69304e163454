"""``rancf conic``: a conic arc from chord, end angles and one interior point."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Iterable, Iterator
from typing import Any

from rancf.cli.io import check_plot_path
from rancf.errors import InputError

__all__ = ["add_parsers", "MAX_TABLE_ELEMENTS", "json_text"]

#: Largest ``--elements`` of the table (one row per element); ``--json`` takes the scenario
#: limit, :data:`rancf.scenario.geometry.MAX_ELEMENTS`.
MAX_TABLE_ELEMENTS = 1000


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
    from rancf.mesh.factories import mesh_conic
    from rancf.mesh.mesh import check_element_count
    from rancf.scenario.geometry import MAX_ELEMENTS

    n = check_element_count(args.elements, "--elements")
    if n > MAX_ELEMENTS:
        raise InputError("--elements", n, f"at most {MAX_ELEMENTS} (the scenario limit)")
    if n > MAX_TABLE_ELEMENTS and not args.json:
        raise InputError(
            "--elements",
            n,
            f"at most {MAX_TABLE_ELEMENTS} for the table (one row per element); "
            f"up to {MAX_ELEMENTS} with --json",
        )
    plot = check_plot_path(args.plot) if args.plot else None
    if args.k is not None and not K_RANGE[0] <= args.k <= K_RANGE[1]:  # NaN included
        lo, hi = K_RANGE
        raise InputError("--k", args.k, f"a mapping factor in [{lo:g}, {hi:g}] (as mesh.k)")
    conic = conic_arc(args.chord, args.angles, args.point)
    k_opt = kopt(conic)
    single = conic_element(conic, args.k)
    mesh = mesh_conic(conic, n, "opt" if args.k is None else args.k, args.spacing)
    ratios = mesh.gradient_ratios(exact=n <= MAX_TABLE_ELEMENTS)  # else sampled, ~1e-10
    nodal = mesh.element_nodal().reshape(n, -1)

    def elements() -> Iterator[dict[str, Any]]:
        for j in range(n):
            yield {
                "k": float(mesh.k[j]),
                "weights": mesh.weights[j].tolist(),
                "scale": float(mesh.scales[j]),
                "nodal_coordinates": nodal[j].tolist(),
                "gradient_ratio": float(ratios[j]),
            }

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
    }
    if plot is not None:
        from rancf.post.conic_plots import plot_conic

        plot_conic(conic, k_opt, single.k, plot, n)
    if args.json:
        for chunk in json_text(out, "elements", elements()):
            sys.stdout.write(chunk)
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
        for j, e in enumerate(elements()):
            w = ", ".join(f"{x:.5f}" for x in e["weights"])
            print(f"  {j:2d}  {e['k']:.4f}   {e['gradient_ratio']:14.5f}    [{w}]")
    if plot is not None:  # with --json on standard error: stdout stays one JSON object
        print(f"plot written to {plot}", file=sys.stderr if args.json else sys.stdout)
    return 0


def json_text(head: dict[str, Any], key: str, items: Iterable[Any]) -> Iterator[str]:
    """JSON of ``{**head, key: [items]}`` in pieces: ``head`` indented, then one compact item a
    line, so a million elements are printed without holding their list or text in memory."""
    from rancf.post.results import json_safe  # strict JSON: a non-finite number is null

    text = json.dumps(json_safe({**head, key: []}), indent=2, allow_nan=False)
    tail = "[]\n}"
    if not text.endswith(tail):  # pragma: no cover - json.dumps puts the last key last
        raise ValueError(f"{key!r} must be the last key")
    yield text[: -len(tail)] + "["
    first, sep = "\n    ", ",\n    "
    lead = first
    for item in items:
        yield lead + json.dumps(json_safe(item), allow_nan=False)
        lead = sep
    yield "]\n}\n" if lead is first else "\n  ]\n}\n"


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
        "--elements",
        type=int,
        default=1,
        help=f"number of elements (default 1): at most {MAX_TABLE_ELEMENTS} for the table, "
        "the scenario limit (1 000 000) with --json",
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
