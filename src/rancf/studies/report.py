"""A self-contained HTML report of the paper studies (figures embedded as base64 PNG)."""

from __future__ import annotations

import base64
import csv
import datetime
import html
import platform
import re
from collections.abc import Sequence
from pathlib import Path

from rancf.atomic import atomic_write
from rancf.post.results import strict_json
from rancf.studies.common import NOT_REACHED, NOT_RUN, StudyResult

__all__ = ["write_report", "study_tables", "REFERENCES"]

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
.footnote { font-size: 0.85em; color: #555; margin-top: -1em; }
"""


#: Tables longer than this are collapsed (``<details>``).
_LONG_TABLE = 20

#: The works the studies reproduce and build on (HTML), cited in the report's "References".
#: The conic-section paper is described by what the copy rancf was written from gives: its
#: abstract, keywords, the initials of its author-contributions statement and its funding (that
#: copy has no title page, so no title, journal or year is cited; none is invented).
REFERENCES = (
    "[1] P. L., Y. L., M. S., M. L.: the conic-section RANCF paper, which in its abstract "
    "“propose[s] a direct definition method for RANCF elements that explicitly exploits the "
    "analytic properties of conic sections” and introduces the mapping factor <i>K</i> and the "
    "optimal <i>K</i><sub>opt</sub> (conic from chord, end-tangent angles and one interior "
    "point; degree elevation; gradient-ratio criterion, eq. 29; numerical examples in sections "
    "6.1–6.3, which rancf's paper studies reproduce). Keywords: rational absolute nodal "
    "coordinate formulation; conic section element; weights; mapping relationship; "
    "parameterization. Funded by the Henan Provincial R&amp;D Plan Joint Fund "
    "(No. 225101610072).",
    "[2] G. G. Sanborn, A. A. Shabana, <i>On the integration of computer aided design and "
    "analysis using the finite element absolute nodal coordinate formulation</i>, Multibody "
    "System Dynamics 22 (2009) 181–197, DOI "
    "<a href='https://doi.org/10.1007/s11044-009-9157-3'>10.1007/s11044-009-9157-3</a> "
    "(the ANCF cable element as a cubic Bézier curve; B-spline and NURBS conversions, which "
    "rancf's CAD import follows).",
)

_INTRO = (
    "The studies reproduce the numerical examples (sections 6.1–6.3) of the conic-section "
    "paper [1] that rancf implements; see the references at the end."
)

#: Words a study writes into a table cell instead of a number, and what they mean.
_CELL_NOTES = {
    NOT_REACHED: "the time integration stopped before t_end (Newton did not converge even at "
    "the smallest step, or the run was interrupted), so the run has no error over the whole "
    "interval and never counts as meeting a tolerance",
    NOT_RUN: "the run was not made (outside the range this column covers; see the notes)",
}

#: Bare non-finite numbers, shown as a dash with a footnote if a table still holds one.
_NON_FINITE = {"inf", "-inf", "nan", "infinity", "-infinity"}


def _text(s: str) -> str:
    """Escaped HTML with reStructuredText ``literals`` shown as code, not as backticks."""
    out = html.escape(s)
    return re.sub(r"``(.+?)``|`(.+?)`", lambda m: f"<code>{m.group(1) or m.group(2)}</code>", out)


def _table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """An HTML table; cells that hold no number are explained in a footnote below it.

    A bare ``inf``/``nan`` (a study that formatted a missing value as a number) is shown as
    "—" with the footnote that it has no value.
    """
    bare = False
    used: list[str] = []

    def cell(c: object) -> str:
        nonlocal bare
        text = str(c)
        if text.strip().lower() in _NON_FINITE:
            bare = True
            return "<td>—*</td>"
        used.extend(w for w in _CELL_NOTES if w in text and w not in used)
        return f"<td>{html.escape(text)}</td>"

    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(cell(c) for c in row) + "</tr>" for row in rows)
    notes = [f"“{html.escape(w)}”: {html.escape(_CELL_NOTES[w])}." for w in used]
    if bare:
        notes.append("—*: no value (the run stopped before t_end or was not made).")
    foot = f"<p class='footnote'>{'<br>'.join(notes)}</p>" if notes else ""
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>{foot}"


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
    unfinished: Sequence[str] = (),
    heading: tuple[str, str] | None = None,
) -> Path:
    """Write ``report.html`` (and ``report.json``) for studies whose files are in their folders.

    ``wall_time_s`` is the wall time of the whole report (the studies may have run in
    parallel); without it the sum of the studies' wall times is shown.  Figures (PNG) and
    animations (GIF) are embedded.  ``unfinished`` names studies that did not finish (failed or
    interrupted): the report then says at the top that it is incomplete, and ``report.json``
    has ``"complete": false``.  ``heading`` replaces the title and introduction of the paper's
    studies (``(title, introduction HTML)``, for other shipped scenarios).
    """
    title, intro = heading or ("RANCF conic-section cable elements: the paper's studies", _INTRO)
    out = Path(out)
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'>",
        f"<title>{html.escape(title)}</title><style>{_CSS}</style></head><body>",
        f"<h1>{html.escape(title)}</h1>",
        f"<p>Generated {datetime.datetime.now().isoformat(timespec='seconds')} on "
        f"{html.escape(platform.platform())}, Python {platform.python_version()}"
        f"{' — <b>reduced (quick) runs</b>' if quick else ''}. {_timing(studies, wall_time_s)}"
        "</p>",
        f"<p>{intro}</p>",
    ]
    if unfinished:
        parts.append(
            "<div class='note'><b>Incomplete report.</b> Not finished (failed or interrupted): "
            f"{html.escape(', '.join(unfinished))}; their folders may hold partial files.</div>"
        )
    parts += [
        "<h2>Contents</h2><ul>",
    ]
    parts += [f"<li><a href='#{s.name}'>{html.escape(s.title)}</a></li>" for s, _ in studies]
    parts.append("<li><a href='#references'>References</a></li></ul>")
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
    parts.append("<h2 id='references'>References</h2>")
    parts += [f"<p>{ref}</p>" for ref in REFERENCES]
    parts.append("</body></html>")
    path = out / "report.html"
    atomic_write(path, "\n".join(parts))
    doc = {
        "complete": not unfinished,
        "unfinished": list(unfinished),
        "quick": quick,
        "wall_time_s": wall_time_s,
        "studies": summary,
    }
    atomic_write(out / "report.json", strict_json(doc, default=str))
    return path


def study_tables(folder: str | Path) -> dict[str, list[list[str]]]:
    """Every study table (CSV) under a report or study folder, without wall-time columns.

    For comparing two runs of the same studies (``--workers 1`` against more): run folders and
    the sweeps' own ``results.csv`` (under ``sweep*/``, whose statuses of cancelled runs depend
    on timing) are left out, and so is every column whose header mentions a time.

    Returns
    -------
    dict
        Path relative to ``folder`` -> rows (header first).
    """
    folder = Path(folder)
    out = {}
    for f in sorted(folder.rglob("*.csv")):
        rel = f.relative_to(folder)
        if any(part.startswith("sweep") for part in rel.parts):
            continue
        with f.open(encoding="utf-8", newline="") as fh:
            rows = list(csv.reader(fh))
        keep = [i for i, h in enumerate(rows[0] if rows else []) if "time" not in h.lower()]
        out[str(rel)] = [[r[i] for i in keep if i < len(r)] for r in rows]
    return out
