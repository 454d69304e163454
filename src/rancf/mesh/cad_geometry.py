"""Scenario geometry ``kind = "cad"``: curves read from a CAD file, joined into one exact mesh.

``file`` (relative to the scenario file) names a STEP, IGES, DXF or geomdl JSON file;
``curve`` picks a curve by index or name, or a list of them forming a chain.  Curves of a chain
are oriented so that each starts where the previous one ends (a curve is reversed when needed);
the chain must be tangent-continuous: a gap or a kink — between two curves or inside one (an
interior knot of full multiplicity) — is reported with its location.  A curve or chain whose
ends meet with the same tangent is closed: a ring (:attr:`CableMesh.closed`); ends that meet
at a kink make an open curve (with a remark, :attr:`CableMesh.notes`).  The curves are planar
(2 coordinates) when every control point has ``z = 0``, spatial otherwise.

Every knot span becomes ``mesh.elements`` RANCF elements (exact subdivision, as
:func:`rancf.mesh.nurbs_mesh.mesh_nurbs`), with consistent shared nodes (docs/derivations/cable.md
sec. 6).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.geometry.bezier import RationalBezier
from rancf.geometry.conic_params import pad3
from rancf.geometry.nurbs import NurbsCurve
from rancf.geometry.tangents import GAP_RTOL, KINK_TOL, vector_angle
from rancf.mesh.mesh import CableMesh, check_element_count
from rancf.mesh.nurbs_mesh import mesh_segments

__all__ = ["select_cad_curves", "chain_segments", "mesh_curve_chain", "reversed_curve"]


def reversed_curve(c: NurbsCurve) -> NurbsCurve:
    """The same curve traversed backwards, on the same parameter domain."""
    a, b = c.domain
    return NurbsCurve(c.degree, (a + b) - c.knots[::-1], c.points[::-1], c.weights[::-1])


def select_cad_curves(
    file: Path, selection: Any
) -> tuple[list[NurbsCurve], list[str], tuple[str, ...]]:
    """Read ``file`` and pick the curves named by ``selection`` (index, name or list of them).

    Returns the curves (planar ones reduced to 2 coordinates), their labels and the reader's
    notes on them (units converted, control points built from fit points; each once).
    """
    from rancf.cad import read_curves

    curves = read_curves(file)
    items = selection if isinstance(selection, list) else [selection]
    if not items:
        raise InputError("geometry.curve", selection, "an index, a name or a non-empty list")
    picked: list[NurbsCurve] = []
    labels: list[str] = []
    notes: list[str] = []
    names = [c.name for c in curves]
    for it in items:
        if isinstance(it, int) and not isinstance(it, bool):
            if not -len(curves) <= it < len(curves):
                raise InputError(
                    "geometry.curve",
                    it,
                    f"an index in 0..{len(curves) - 1} ({file.name} holds "
                    f"{len(curves)} curve(s); see `rancf cad list`)",
                )
            c = curves[it]
        elif isinstance(it, str) and it in names:
            if names.count(it) > 1:
                raise InputError("geometry.curve", it, "a name used once in the file (use indices)")
            c = curves[names.index(it)]
        else:
            known = ", ".join(repr(n) for n in names if n) or "none"
            raise InputError(
                "geometry.curve", it, f"an index or a curve name of {file.name} (names: {known})"
            )
        if c.curve.degree not in (2, 3):
            raise InputError(
                "geometry.curve", it, f"a curve of degree 2 or 3 (it has degree {c.curve.degree})"
            )
        picked.append(c.curve)
        notes += [n for n in c.notes if n not in notes]
        labels.append(f"curve {c.index}" + (f" ({c.name})" if c.name else ""))
    planar = all(c.dim == 2 or np.all(c.points[:, 2] == 0.0) for c in picked)
    out = []
    for nc in picked:
        pts = nc.points[:, :2] if planar else pad3(nc.points)
        out.append(NurbsCurve(nc.degree, nc.knots, pts, nc.weights))
    return out, labels, tuple(notes)


def _where(x: NDArray) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in x) + ")"


def _end_tangents(seg: RationalBezier) -> tuple[NDArray, NDArray]:
    q = seg.points
    return q[1] - q[0], q[-1] - q[-2]


def chain_segments(
    curves: list[NurbsCurve], labels: list[str]
) -> tuple[list[RationalBezier], NDArray[np.float64]]:
    """Rational Bézier segments of a tangent-continuous chain of curves, and their parameters.

    The chain parameter runs through each curve's own domain, shifted to continue the previous
    one.  Curves are reversed where that makes the chain meet.

    Raises
    ------
    InputError
        For a gap or a kink, naming the location, the curves and the angle.
    """
    size = max(float(np.abs(c.points).max()) for c in curves)
    oriented = [curves[0]]
    for k, c in enumerate(curves[1:], 1):
        prev = oriented[-1]
        a, b = prev.domain
        end = prev(np.array([b]))[0]
        ca, cb = c.domain
        s, e = c(np.array([ca, cb]))
        if k == 1 and min(np.linalg.norm(s - end), np.linalg.norm(e - end)) > GAP_RTOL * size:
            start0 = prev(np.array([a]))[0]
            if min(np.linalg.norm(s - start0), np.linalg.norm(e - start0)) <= GAP_RTOL * size:
                oriented[0] = prev = reversed_curve(prev)
                end = start0
        if np.linalg.norm(e - end) < np.linalg.norm(s - end):
            c = reversed_curve(c)
            s = e
        gap = float(np.linalg.norm(s - end))
        if gap > GAP_RTOL * size:
            raise InputError(
                "geometry.curve",
                f"{labels[k - 1]} -> {labels[k]}",
                f"curves that meet end to end (gap {gap:.3g} m at {_where(end)})",
            )
        oriented.append(c)
    segments: list[RationalBezier] = []
    params: list[float] = []
    offset = 0.0
    owner: list[str] = []
    for c, label in zip(oriented, labels, strict=True):
        breaks, segs = c.bezier_segments()
        shift = offset - breaks[0]
        if not params:
            params.append(breaks[0] + shift)
        params.extend((breaks[1:] + shift).tolist())
        offset = breaks[-1] + shift
        segments.extend(segs)
        owner.extend([label] * len(segs))
    for j in range(len(segments) - 1):
        t0 = _end_tangents(segments[j])[1]
        t1 = _end_tangents(segments[j + 1])[0]
        ang = vector_angle(t0, t1)
        if ang > KINK_TOL:
            where = segments[j].points[-1]
            between = owner[j] if owner[j] == owner[j + 1] else f"{owner[j]} and {owner[j + 1]}"
            raise InputError(
                "geometry.curve",
                f"kink of {np.degrees(ang):.4g} deg at {_where(where)} ({between})",
                "a tangent-continuous curve or chain; split the model at the kink",
            )
    return segments, np.array(params)


def mesh_curve_chain(
    curves: list[NurbsCurve], labels: list[str], n_per_span: int = 1, notes: tuple[str, ...] = ()
) -> CableMesh:
    """An exact RANCF mesh of a chain of NURBS curves, ``n_per_span`` elements per knot span;
    ``notes`` (the reader's, :func:`select_cad_curves`) join the mesh's remarks."""
    n_per_span = check_element_count(n_per_span, "mesh.elements")
    segments, breaks = chain_segments(curves, labels)
    mesh = mesh_segments(segments, breaks, n_per_span)
    return replace(mesh, notes=tuple(notes) + mesh.notes) if notes else mesh
