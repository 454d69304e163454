"""Sub-commands on finished runs: ``export`` (ParaView, CAD), ``plot`` and ``animate``; and
``cad list``."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from rancf.cli.io import OutputDir, check_out_dir
from rancf.errors import InputError

__all__ = ["add_parsers", "run_to_nurbs"]


#: End points of a chain closer than this (relative to the curve's extent) are one point: a
#: ring's seam, held by its closure rows to round-off.
SEAM_RTOL = 1e-12


def run_to_nurbs(run: Any, i: int) -> Any:
    """The configuration of stored state ``i`` as one exact NURBS curve (cable and rod elements:
    a rod's centreline).

    The nodal coordinates give an :class:`~rancf.elements.cad.ElementChain` (breakpoints: the
    cumulative reference gradient scales, i.e. reference arc length) and
    :func:`~rancf.elements.cad.chain_to_nurbs` turns it into a cubic NURBS with the lowest knot
    multiplicities that represent it.  Ends that meet to round-off (:data:`SEAM_RTOL`: a ring's
    seam) are written as one point, so a closed curve stays closed in the CAD file.
    """
    import numpy as np

    from rancf.elements.cad import ElementChain, chain_to_nurbs

    if not run.family.gradient:
        raise InputError(
            "RUN_DIR",
            str(run.path),
            "a run of cable or rod elements: beam elements have no exact curve to export",
        )
    from rancf.post.centerline import centerline_nodes

    nodes = centerline_nodes(run, run.q[i])
    if not np.all(np.isfinite(nodes)):
        raise InputError(
            "--time", float(run.t[i]), "a stored state with finite coordinates (this one is not)"
        )
    # a closed curve's seam: its two copies agree to round-off, and CAD wants one point
    gap = np.abs(nodes[-1, 0] - nodes[0, 0]).max()
    if gap <= SEAM_RTOL * max(np.abs(nodes[:, 0]).max(), 1e-300):
        nodes = nodes.copy()
        nodes[-1, 0] = nodes[0, 0]
    nodal = np.concatenate([nodes[:-1], nodes[1:]], axis=1)
    breaks = np.concatenate([[0.0], np.cumsum(run.scales)])
    return chain_to_nurbs(ElementChain(nodal, run.weights, run.scales, breaks))


def _cmd_export(args: argparse.Namespace) -> int:
    import numpy as np

    from rancf.post.run_data import frame_indices
    from rancf.post.system_run import export_system_vtk, load_run
    from rancf.post.vtk import check_export_size
    from rancf.post.vtk_contact import export_contact_vtk

    if args.vtk is None and args.nurbs is None:
        from rancf.cli import UsageError

        raise UsageError("export needs at least one of --vtk OUT_DIR, --nurbs FILE")
    out = OutputDir(args.vtk, "--vtk") if args.vtk is not None else None
    run = load_run(args.run_dir)
    if out is not None:
        n = frame_indices(run.t.size, args.every).size
        for r in run.flexible.values():
            check_export_size(r, args.every, args.samples)
        with out:
            paths = export_system_vtk(run, out.path, args.every, args.samples)
            contact = export_contact_vtk(run.path, out.path, args.every, run.rigid_frame)
            out.keep()
        print(f"{n} VTK frame(s) of {run.name} written")
        for p in paths:
            name = p.parent.name if p.parent != out.path else "rigid bodies"
            print(f"{name}: open {p} in ParaView")
        if contact is not None:
            print(f"contact forces: open {contact} in ParaView")
        for b in run.bodies:  # a shell's surfaces were written with its run
            if b["kind"] == "shell":
                shell = Path(run.path) / b["folder"] / f"{b['name']}.pvd"
                print(f"{b['name']}: the shell's surfaces (written by the run): open {shell}")
        for name, r in run.flexible.items():
            if r.directors is not None:
                nodes = out.path / name / f"{name}_nodes.pvd"
                print(f"{name}: rod nodes and material frames: {nodes}")
            elif r.family.has_triads:
                print(
                    f"rancf: note: {r.path} holds no rod directors (written by an older rancf): "
                    "no material frames exported; run `rancf simulate` again to get them",
                    file=sys.stderr,
                )
    if args.nurbs is not None:
        from rancf.cad import write_curve

        body = run.body(args.body)
        i = run.time_index(args.time)
        curve = run_to_nurbs(body, i)
        label = f"{'lambda' if run.static else 't'}={run.t[i]:g}"  # ASCII: STEP/IGES names
        path = write_curve(args.nurbs, curve, f"{run.name} {label}")
        interior = curve.knots[curve.degree + 1 : curve.n_ctrl]
        print(
            f"{run.time_text(run.t[i], 'g')}: cubic NURBS, {curve.n_ctrl} control points, "
            f"{np.unique(interior).size} interior knot value(s) -> {path}"
        )
    return 0


def _cmd_plot(args: argparse.Namespace) -> int:
    from rancf.post.system_run import load_run, plot_system_run

    if args.out is not None:
        check_out_dir(args.out)
    run = load_run(args.run_dir)
    if not 1 <= args.configurations <= MAX_CONFIGURATIONS:
        raise InputError(
            "--configurations", args.configurations, f"an integer in [1, {MAX_CONFIGURATIONS}]"
        )
    with OutputDir(Path(args.out) if args.out is not None else run.path / "plots") as out:
        written = plot_system_run(run, out.path, args.configurations)
        out.keep()
    for p in written:
        print(p)
    return 0


#: Most configurations ``rancf plot`` draws in one figure.
MAX_CONFIGURATIONS = 100


def _cmd_animate(args: argparse.Namespace) -> int:
    from rancf.cli.view import refuse_shell_runs
    from rancf.post.system_run import animate_system_run, load_run

    run = load_run(args.run_dir)
    refuse_shell_runs(run, args.run_dir)
    n = animate_system_run(run, args.out, args.fps, args.every)
    print(f"{n} frames at {args.fps} fps -> {args.out}")
    return 0


def _cmd_cad(args: argparse.Namespace) -> int:
    import numpy as np

    from rancf.cad import read_curves

    curves = read_curves(args.file)
    for note in dict.fromkeys(n for c in curves for n in c.notes):
        print(f"rancf: note: {note}", file=sys.stderr)
    print(" #  name              degree  control points  spans  rational  start -> end")
    for c in curves:
        cv = c.curve
        a, b = cv.domain
        ends = cv(np.array([a, b]))
        spans = np.unique(cv.knots[(cv.knots >= a) & (cv.knots <= b)]).size - 1
        rational = "yes" if np.ptp(cv.weights) > 0 else "no"
        fmt = ", ".join
        print(
            f"{c.index:2d}  {c.name or '-':16s}  {cv.degree:6d}  {cv.n_ctrl:14d}  {spans:5d}  "
            f"{rational:8s}  ({fmt(f'{x:.6g}' for x in ends[0])}) -> "
            f"({fmt(f'{x:.6g}' for x in ends[1])})"
        )
    return 0


def add_parsers(sub: Any) -> None:
    """Register ``export``, ``plot``, ``animate`` and ``cad``."""
    e = sub.add_parser(
        "export",
        help="write a run as ParaView files (--vtk) or a CAD curve (--nurbs)",
        description="ParaView: one .vtu per stored time (the exact element curves sampled "
        "densely) and a .pvd collection. CAD: the configuration at one time as one NURBS curve "
        "(.json geomdl, .step/.stp, .igs/.iges, .dxf).",
    )
    e.add_argument("run_dir", metavar="RUN_DIR", help="a directory written by `rancf simulate`")
    e.add_argument("--vtk", metavar="OUT_DIR", default=None, help="write .pvd + .vtu files here")
    e.add_argument("--every", type=int, default=1, help="every N-th stored time (default 1)")
    e.add_argument(
        "--samples", type=int, default=16, help="points per element along the curve (default 16)"
    )
    e.add_argument("--nurbs", metavar="FILE", default=None, help="write the shape as NURBS")
    e.add_argument(
        "--time", type=float, default=None, help="time of the --nurbs shape (default: the last)"
    )
    e.add_argument(
        "--body", default=None, help="flexible body of the --nurbs shape (default: the only one)"
    )
    e.set_defaults(func=_cmd_export)

    p = sub.add_parser("plot", help="PNG figures of a run: sensors, energies, configurations")
    p.add_argument("run_dir", metavar="RUN_DIR")
    p.add_argument("--out", default=None, help="output directory (default RUN_DIR/plots)")
    p.add_argument("--configurations", type=int, default=6, help="configurations drawn (default 6)")
    p.set_defaults(func=_cmd_plot)

    a = sub.add_parser("animate", help="render the motion of a run to a GIF or MP4 file")
    a.add_argument("run_dir", metavar="RUN_DIR")
    a.add_argument("--out", required=True, metavar="FILE.gif|FILE.mp4")
    a.add_argument("--fps", type=int, default=20, help="frames per second (default 20)")
    a.add_argument("--every", type=int, default=1, help="every N-th stored time (default 1)")
    a.set_defaults(func=_cmd_animate)

    c = sub.add_parser("cad", help="inspect CAD files (STEP, IGES, DXF, geomdl JSON)")
    c.add_argument("action", choices=["list"], help="list the curves a file holds")
    c.add_argument("file", metavar="FILE")
    c.set_defaults(func=_cmd_cad)
