"""What C² buys: error against unknowns for C¹ and C² meshes.

Runs :func:`rancf.studies.continuity.continuity_study` (the shipped cantilever's first five
bending frequencies and highest frequency; the 6.1 pendulum's tip error), writes
``benchmarks/results/continuity_study.json`` and prints the Markdown tables of
``docs/guide/closed-curves.md``.

    python benchmarks/continuity_study.py [--quick] [--out FILE]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from rancf.post.results import strict_json
from rancf.studies.continuity import continuity_study


def _e(x: float | None) -> str:
    """A magnitude to 2 digits; a dash for a mode the mesh does not have (null in the JSON)."""
    return "—" if x is None or math.isnan(x) else f"{abs(x):.1e}"


def tables(doc: dict) -> str:
    """The two Markdown tables."""
    out = [
        "| continuity | elements | unknowns | f1 | f2 | f3 | f4 | f5 | highest [Hz] |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for r in doc["cantilever"]:
        errs = " | ".join(_e(x) for x in r["errors"])
        out.append(
            f"| {r['continuity']} | {r['elements']} | {r['unknowns']} | {errs} | "
            f"{r['highest_hz']:.0f} |"
        )
    out += [
        "",
        "| continuity | elements | unknowns | tip error [m] |",
        "| --- | ---: | ---: | ---: |",
    ]
    for r in doc["pendulum"]:
        out.append(
            f"| {r['continuity']} | {r['elements']} | {r['unknowns']} | {_e(r['tip_error'])} |"
        )
    out.append(
        f"\nreference check (C¹, 16 against 24 elements): {doc['pendulum_reference_check']:.1e} m"
    )
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument(
        "--out", default=str(Path(__file__).parent / "results" / "continuity_study.json")
    )
    args = ap.parse_args()
    doc = continuity_study(quick=args.quick)
    Path(args.out).write_text(strict_json(doc))
    print(tables(doc))


if __name__ == "__main__":
    main()
