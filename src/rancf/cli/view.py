"""The sub-command that writes a run's interactive 3D view: ``view``."""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Any

from rancf.errors import InputError

__all__ = ["add_parsers", "refuse_shell_runs"]


def _cmd_view(args: argparse.Namespace) -> int:
    from rancf.post.system_run import load_run

    run = load_run(args.run_dir)
    refuse_shell_runs(run, args.run_dir)
    out = Path(args.out) if args.out is not None else Path(args.run_dir) / "view.html"
    n = _write(run, out, args)
    print(f"{n} of {run.t.size} stored times -> {out}")
    return 0


def refuse_shell_runs(run: Any, run_dir: str | Path) -> None:
    """Refuse in one line a run with a shell (``rancf view``, ``rancf animate`` draw lines and
    rigid bodies): its surfaces are drawn in ParaView from the run's own VTK files."""
    shells = [b for b in run.bodies if b["kind"] == "shell"]
    if shells:
        b = shells[0]
        raise InputError(
            "RUN_DIR",
            str(run_dir),
            f"a run of lines and rigid bodies: {b['name']!r} is a shell, whose surfaces are in "
            f"{Path(run_dir) / b['folder'] / (b['name'] + '.pvd')} (open it in ParaView)",
        )


def _write(run: Any, out: Path, args: argparse.Namespace) -> int:
    """Write the view of ``run`` to ``out``; returns the number of frames.  A path that cannot
    be written is refused on one line naming ``--out`` and the user's path (not the temporary
    file the page is written through)."""
    from rancf.post.view import write_view

    if out.is_dir():
        raise InputError("--out", str(out), "a file name (this path is a directory)")
    if not out.parent.is_dir():
        raise InputError("--out", str(out), "a file in an existing directory")
    if not os.access(out.parent, os.W_OK | os.X_OK):
        raise InputError(
            "--out", str(out), f"a file in a writable directory ({out.parent} is not writable)"
        )
    try:
        return write_view(run, out, args.frames, args.samples)
    except OSError as exc:
        raise InputError(
            "--out",
            str(out),
            f"a file that can be written here (writing it failed: {exc.strerror or exc})",
        ) from None


def add_parsers(sub: Any) -> None:
    """Register ``view``."""
    from rancf.post.view_options import DEFAULT_FRAMES

    v = sub.add_parser(
        "view",
        help="write a run as one interactive 3D HTML page (works offline)",
        description="One self-contained HTML file: the bodies, obstacles and contact forces in "
        "3D, with play, pause and a time slider (Plotly, its library inlined: no network "
        "needed to open it).",
    )
    v.add_argument("run_dir", metavar="RUN_DIR", help="a directory written by `rancf simulate`")
    v.add_argument(
        "--out",
        default=None,
        metavar="FILE.html",
        help="the page to write (default RUN_DIR/view.html)",
    )
    v.add_argument(
        "--frames",
        type=int,
        default=DEFAULT_FRAMES,
        help=f"at most this many stored times, evenly spaced (default {DEFAULT_FRAMES})",
    )
    v.add_argument(
        "--samples",
        type=int,
        default=8,
        help="points per element along a flexible body (default 8)",
    )
    v.set_defaults(func=_cmd_view)
