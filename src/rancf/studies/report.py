"""A self-contained HTML report of the paper studies (figures embedded as base64 PNG)."""

from __future__ import annotations

import base64
import datetime
import html
import json
import platform
import re
from collections.abc import Sequence
from pathlib import Path

from rancf.post.results import atomic_write
from rancf.studies.common import StudyResult

__all__ = ["write_report"]

_CSS = """
body { font-family: system-ui, sans-serif; max-width: 1200px; margin: 2em auto; color: #222; }
h1, h2, h3 { color: #1a3d6d; }
table { border-collapse: collapse; margin: 0.8em 0 1.5em 0; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.3em 0.6em; text-align: left; vertical-align: top; }
th { background: #e8eef7; }
figure { margin: 1em 0 2em 0; }
figcaption { font-style: italic; color: #555; }
img { max-width: 100%; border: 1px solid #ddd; }
.note { background: #f7f7f0; border-left: 4px solid #c9b458; padding: 0.5em 1em; margin: 1em 0; }
"""


#: Tables longer than this are collapsed (``<details>``).
_LONG_TABLE = 20

_CITATION = (
    "The studies reproduce the numerical examples (sections 6.1–6.3) of the paper on rational "
    "ANCF conic-section cable elements that rancf implements; the CAD conversions follow "
    "Sanborn &amp; Shabana (2009), <i>A rational finite element method based on the absolute "
    "nodal coordinate formulation</i>, Nonlinear Dynamics."
)


def _text(s: str) -> str:
    """Escaped HTML with reStructuredText ``literals`` shown as code, not as backticks."""
    out = html.escape(s)
    return re.sub(r"``(.+?)``|`(.+?)`", lambda m: f"<code>{m.group(1) or m.group(2)}</code>", out)


def _table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>" for row in rows
    )
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _timing(studies: Sequence[tuple[StudyResult, Path]], wall_time_s: float | None) -> str:
    total = sum(s.wall_time_s for s, _ in studies)
    if wall_time_s is None:
        return f"Total wall time {total:.1f} s."
    return f"Wall time {wall_time_s:.1f} s (the studies' own wall times add up to {total:.1f} s)."


def write_report(
    out: str | Path,
    studies: Sequence[tuple[StudyResult, Path]],
    quick: bool,
    wall_time_s: float | None = None,
) -> Path:
    """Write ``report.html`` (and ``report.json``) for studies whose files are in their folders.

    ``wall_time_s`` is the wall time of the whole report (the studies may have run in
    parallel); without it the sum of the studies' wall times is shown.  Figures (PNG) and
    animations (GIF) are embedded.
    """
    out = Path(out)
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'>",
        f"<title>rancf: paper studies</title><style>{_CSS}</style></head><body>",
        "<h1>RANCF conic-section cable elements: the paper's studies</h1>",
        f"<p>Generated {datetime.datetime.now().isoformat(timespec='seconds')} on "
        f"{html.escape(platform.platform())}, Python {platform.python_version()}"
        f"{' — <b>reduced (quick) runs</b>' if quick else ''}. {_timing(studies, wall_time_s)}"
        "</p>",
        "<h2>Contents</h2><ul>",
    ]
    parts += [f"<li><a href='#{s.name}'>{html.escape(s.title)}</a></li>" for s, _ in studies]
    parts.append("</ul>")
    summary = {}
    for s, folder in studies:
        parts.append(f"<h2 id='{s.name}'>{html.escape(s.title)}</h2>")
        parts.append(
            f"<p>Wall time {s.wall_time_s:.1f} s; files in <code>{folder.name}/</code>.</p>"
        )
        for note in s.notes:
            parts.append(f"<div class='note'>{_text(note)}</div>")
        for caption, filename in s.figures:  # figures first, then the tables
            data = base64.b64encode((folder / filename).read_bytes()).decode("ascii")
            parts.append(
                f"<figure><img alt='{html.escape(caption)}' src='data:image/png;base64,{data}'>"
                f"<figcaption>{_text(caption)} ({html.escape(filename)})</figcaption>"
                "</figure>"
            )
        for caption, filename in s.animations:
            data = base64.b64encode((folder / filename).read_bytes()).decode("ascii")
            parts.append(
                f"<figure><img alt='{html.escape(caption)}' src='data:image/gif;base64,{data}'>"
                f"<figcaption>{_text(caption)} ({html.escape(filename)})</figcaption>"
                "</figure>"
            )
        for title, header, rows, filename in s.tables:
            head = f"{_text(title)} <small>({html.escape(filename)}, {len(rows)} rows)</small>"
            if len(rows) > _LONG_TABLE:
                parts.append(f"<details><summary>{head}</summary>{_table(header, rows)}</details>")
            else:
                parts.append(f"<h3>{head}</h3>{_table(header, rows)}")
        summary[s.name] = {
            "wall_time_s": s.wall_time_s,
            "comparison": [c.__dict__ for c in s.comparison],
            "figures": [f for _, f in s.figures],
            "animations": [f for _, f in s.animations],
        }
    parts.append(f"<h2>Reference</h2><p>{_CITATION}</p></body></html>")
    path = out / "report.html"
    atomic_write(path, "\n".join(parts))
    atomic_write(out / "report.json", json.dumps(summary, indent=2, default=str) + "\n")
    return path
