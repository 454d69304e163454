"""The five surface kinds of a shell as exact RANCF meshes (docs/derivations/shell.md sec. 2, 3).

``cylinder``, ``cone`` and ``sphere`` are surfaces of revolution: an azimuthal circle times a
profile (eq. 2.4), each element the product of a circular cubic with mapping factor K (the
cable's :func:`rancf.mesh.conic_chain.cubic_forms`) and a profile cubic (a line, or the sphere's
meridian circle).  ``rectangle`` is a product of lines, ``nurbs_surface`` a NURBS patch with
product weights cut into Bézier elements by the curve code's knot insertion
(:func:`rancf.geometry.nurbs.extraction`) and blossoming.  Parameters ``(u, v) ∈ [0, 1]²``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError
from rancf.geometry.bezier import degree_elevation_matrix, restriction_matrix
from rancf.geometry.conic_params import check_mapping_factor
from rancf.geometry.nurbs import check_knots, extraction
from rancf.mesh.conic_chain import cubic_forms, kopt_many
from rancf.mesh.mesh import check_element_count
from rancf.mesh.surfaces import Direction, SurfaceMesh, mesh_from_patches, regular_or_raise

__all__ = ["SURFACE_KEYS", "mesh_surface", "circle_pieces", "line_pieces", "surface_of_revolution"]

#: The keys of each kind (besides ``kind``).
SURFACE_KEYS: dict[str, tuple[str, ...]] = {
    "cylinder": ("radius", "length", "angles_deg"),
    "sphere": ("radius", "azimuth_deg", "polar_deg"),
    "cone": ("radius", "length", "angles_deg"),
    "rectangle": ("corner", "size"),
    "nurbs_surface": ("degree", "knots_u", "knots_v", "control_points", "weights"),
}
#: Largest angle one circular element may turn through [deg] (its standard quadratic form
#: needs less than 180°: the end tangents must meet).
MAX_ELEMENT_ANGLE = 179.0

KFactor = float | str | None


def circle_pieces(a0: float, a1: float, n: int, k: KFactor) -> tuple[NDArray, NDArray, Direction]:
    """``n`` equal circular elements of the unit circle from angle ``a0`` to ``a1`` [rad]:
    control points ``(n, 4, 2)`` (``(cos, sin)``), weights ``(n, 4)`` and the direction's data
    (eq. 2.5).  ``k``: one mapping factor, or ``"opt"``/None for Kopt of each element (eq. 3.7).
    """
    ang = np.linspace(a0, a1, n + 1)
    alpha = 0.5 * (ang[1:] - ang[:-1])
    mid = 0.5 * (ang[1:] + ang[:-1])
    unit = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    p1 = np.stack([np.cos(mid), np.sin(mid)], axis=1) / np.cos(alpha)[:, None]
    quad = np.stack([unit[:-1], p1, unit[1:]], axis=1)
    omega = np.cos(alpha)
    if k is None or (isinstance(k, str) and k == "opt"):
        ks = kopt_many(quad, omega)
    else:
        ks = np.full(n, check_mapping_factor(k))
    pts, w = cubic_forms(quad, omega, ks)
    closed = bool(abs(abs(a1 - a0) - 2.0 * np.pi) <= 1e-12 * 2.0 * np.pi)
    d = Direction(w, np.ones(n), np.linspace(0.0, 1.0, n + 1), ks, alpha, closed)
    return pts, w, d


def line_pieces(n: int) -> tuple[NDArray, Direction]:
    """``n`` equal straight elements of ``[0, 1]``: cubic control parameters ``(n, 4)`` (the
    line degree-elevated, all weights 1) and the direction's data."""
    t = (np.arange(n)[:, None] + np.arange(4)[None, :] / 3.0) / n
    nan = np.full(n, np.nan)
    return t, Direction(np.ones((n, 4)), np.ones(n), np.linspace(0.0, 1.0, n + 1), nan, nan)


def _number(spec: Mapping[str, Any], key: str, positive: bool = True) -> float:
    try:
        x = float(spec[key])
    except (TypeError, ValueError):
        raise InputError(f"geometry.{key}", spec[key], "a number") from None
    if not np.isfinite(x) or (positive and x <= 0.0):
        raise InputError(f"geometry.{key}", spec[key], "a finite number > 0")
    return x


def _pair(spec: Mapping[str, Any], key: str, what: str) -> NDArray[np.float64]:
    try:
        a = np.asarray(spec[key], dtype=float).ravel()
    except (TypeError, ValueError):
        a = np.empty(0)
    if a.size != 2 or not np.all(np.isfinite(a)):
        raise InputError(f"geometry.{key}", spec[key], f"two numbers: {what}")
    return a


def _angles(spec: Mapping[str, Any], key: str, lo: float, hi: float, n: int) -> NDArray:
    a = _pair(spec, key, "[start, end] in degrees")
    if not (a[1] > a[0] and a[1] - a[0] <= 360.0 and lo <= a[0] and a[1] <= hi):
        raise InputError(
            f"geometry.{key}", spec[key], f"[start, end] degrees, start < end, within [{lo}, {hi}]"
        )
    if (a[1] - a[0]) / n > MAX_ELEMENT_ANGLE:
        raise InputError(
            "mesh.elements", n, f"enough elements that each turns < {MAX_ELEMENT_ANGLE}° ({key})"
        )
    return np.radians(a)


def _split_k(k: KFactor | tuple | list, curved: tuple[bool, bool]) -> tuple[KFactor, KFactor]:
    """One factor per direction: a scalar applies to the curved directions (eq. 3.7)."""
    ks = list(k) if isinstance(k, tuple | list) else [k if c else None for c in curved]
    if len(ks) != 2:
        raise InputError("mesh.k", k, 'a mapping factor, "opt", or one per direction [ku, kv]')
    for kk, c in zip(ks, curved, strict=True):
        if not c and kk is not None and not (isinstance(kk, str) and kk == "opt"):
            raise InputError("mesh.k", k, '"opt" (or none) for a straight direction')
    return ks[0], ks[1]


def surface_of_revolution(
    circle: tuple[NDArray, NDArray, Direction],
    profile: NDArray,
    pv: Direction,
    place: str,
    kind: str,
) -> SurfaceMesh:
    """A surface of revolution: circle pieces times a profile (docs/derivations/shell.md eq. 2.4).

    Parameters
    ----------
    circle : (points, weights, Direction)
        The azimuthal pieces of :func:`circle_pieces` (``points`` ``(nu, 4, 2)``: ``(cos, sin)``).
    profile : ndarray, shape (nv, 4, 2)
        Cubic control points ``(radius, axial)`` of the profile, one row per element along
        ``v`` (a line from :func:`line_pieces`, or the sphere's meridian).
    pv : Direction
        The profile direction's data (its weights carry a rational profile).
    place : str
        ``"xz"`` (the circle in the x–z plane, axis +y: cylinder, cone) or ``"xy"`` (axis +z:
        sphere, a flat annulus).
    kind : str
        The mesh's kind label.

    Returns
    -------
    SurfaceMesh
        Checked regular (:func:`rancf.mesh.surfaces.regular_or_raise`).
    """
    c, _, pu = circle
    rad, ax = profile[:, None, None, :, 0], profile[:, None, None, :, 1]  # [j, ., ., b]
    cx, cs = c[None, :, :, None, 0], c[None, :, :, None, 1]  # [., i, a, .]
    shape = (pv.n, pu.n, 4, 4)
    x, s = rad * cx, rad * cs
    y = np.broadcast_to(ax, shape)
    pts = np.stack([x, y, s] if place == "xz" else [x, s, y], axis=-1)
    mesh = mesh_from_patches(pts, pu, pv, kind)
    regular_or_raise(mesh, "geometry")
    return mesh


def _cylinder_or_cone(spec: Mapping[str, Any], n: tuple[int, int], k: Any) -> SurfaceMesh:
    kind = str(spec["kind"])
    if kind == "cylinder":
        r = np.full(2, _number(spec, "radius"))
    else:
        r = _pair(spec, "radius", "[r0, r1] at y = 0 and y = length")
        if np.any(r <= 0.0):
            raise InputError("geometry.radius", spec["radius"], "two radii > 0 (no apex)")
    length = _number(spec, "length")
    a = _angles(spec, "angles_deg", -360.0, 360.0, n[0])
    ku, _ = _split_k(k, (True, False))
    t, pv = line_pieces(n[1])
    profile = np.stack([r[0] + t * (r[1] - r[0]), length * t], axis=-1)
    return surface_of_revolution(circle_pieces(a[0], a[1], n[0], ku), profile, pv, "xz", kind)


def _sphere(spec: Mapping[str, Any], n: tuple[int, int], k: Any) -> SurfaceMesh:
    radius = _number(spec, "radius")
    az = _angles(spec, "azimuth_deg", -360.0, 360.0, n[0])
    pol = _angles(spec, "polar_deg", 0.0, 180.0, n[1])
    if pol[0] <= 0.0 or pol[1] >= np.pi:
        raise InputError(
            "geometry.polar_deg", spec["polar_deg"], "polar angles inside (0, 180): no pole"
        )
    ku, kv = _split_k(k, (True, True))
    m, _, pv = circle_pieces(pol[0], pol[1], n[1], kv)
    profile = radius * m[..., ::-1]  # (sin θ, cos θ): radius and height
    return surface_of_revolution(circle_pieces(az[0], az[1], n[0], ku), profile, pv, "xy", "sphere")


def _rectangle(spec: Mapping[str, Any], n: tuple[int, int], k: Any) -> SurfaceMesh:
    try:
        corner = np.asarray(spec["corner"], dtype=float).ravel()
    except (TypeError, ValueError):
        corner = np.empty(0)
    if corner.size not in (2, 3) or not np.all(np.isfinite(corner)):
        raise InputError("geometry.corner", spec["corner"], "a point [x, y] or [x, y, z]")
    size = _pair(spec, "size", "[a, b] > 0 along x and y")
    if np.any(size <= 0.0):
        raise InputError("geometry.size", spec["size"], "two side lengths [a, b] > 0")
    _split_k(k, (False, False))
    (tu, pu), (tv, pv) = line_pieces(n[0]), line_pieces(n[1])
    c3 = np.concatenate([corner, [0.0]])[:3]
    pts = np.zeros((n[1], n[0], 4, 4, 3)) + c3
    pts[..., 0] += size[0] * tu[None, :, :, None]
    pts[..., 1] += size[1] * tv[:, None, None, :]
    return mesh_from_patches(pts, pu, pv, "rectangle")


def _span_operators(knots: NDArray, degree: int, n_ctrl: int, n: int) -> tuple[NDArray, NDArray]:
    """Cubic Bézier operators ``(n_el, 4, n_ctrl)`` of ``n`` equal steps of every knot span and
    the element ends in ``[0, 1]`` (eq. 2.6): extraction, elevation to degree 3, restriction."""
    breaks, ops = extraction(knots, degree, n_ctrl)
    elev = np.eye(degree + 1)
    for p in range(degree, 3):
        elev = degree_elevation_matrix(p) @ elev
    t = np.linspace(0.0, 1.0, n + 1)
    rows = [restriction_matrix(3, t[i], t[i + 1]) @ elev @ c for c in ops for i in range(n)]
    ends = [breaks[0]] + [
        b0 + ti * (b1 - b0) for b0, b1 in zip(breaks[:-1], breaks[1:], strict=True) for ti in t[1:]
    ]
    ends_arr = np.asarray(ends)
    return np.array(rows), (ends_arr - ends_arr[0]) / (ends_arr[-1] - ends_arr[0])


def _floats(spec: Mapping[str, Any], key: str, what: str) -> NDArray[np.float64]:
    """``spec[key]`` as a float array, or an InputError naming the key."""
    try:
        x = np.asarray(spec[key], dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"geometry.{key}", spec[key], what) from None
    if not np.all(np.isfinite(x)):
        raise InputError(f"geometry.{key}", spec[key], what)
    return x


def _nurbs_data(spec: Mapping[str, Any]) -> tuple[int, int, NDArray, NDArray, NDArray, NDArray]:
    """Degrees, checked knot vectors, control points ``(nv, nu, 3)`` and weights ``(nv, nu)``."""
    deg = _floats(spec, "degree", "[p, q], each 1, 2 or 3").ravel()
    if deg.size != 2 or not all(int(d) == d and 1 <= d <= 3 for d in deg):
        raise InputError("geometry.degree", spec["degree"], "[p, q], each 1, 2 or 3")
    p, q = int(deg[0]), int(deg[1])
    ku = _floats(spec, "knots_u", "a knot vector (numbers)").ravel()
    kv = _floats(spec, "knots_v", "a knot vector (numbers)").ravel()
    nu_c, nv_c = ku.size - p - 1, kv.size - q - 1
    want = f"{max(nu_c, 0)} × {max(nv_c, 0)} points [x, y, z], u fastest"
    pts = _floats(spec, "control_points", want)
    if nu_c < p + 1 or nv_c < q + 1 or pts.shape != (nu_c * nv_c, 3):
        raise InputError("geometry.control_points", pts.shape, want)
    w = _floats(spec, "weights", f"{nu_c * nv_c} weights > 0, u fastest").ravel()
    if w.size != nu_c * nv_c:
        raise InputError("geometry.weights", w.size, f"{nu_c * nv_c} weights, u fastest")
    knots = []
    for key, kn, deg_, n_c in (("knots_u", ku, p, nu_c), ("knots_v", kv, q, nv_c)):
        try:
            knots.append(check_knots(kn, deg_, n_c))
        except InputError as err:
            raise InputError(f"geometry.{key}", kn.tolist(), err.allowed) from None
    return p, q, knots[0], knots[1], pts.reshape(nv_c, nu_c, 3), w.reshape(nv_c, nu_c)


def _nurbs(spec: Mapping[str, Any], n: tuple[int, int], k: Any) -> SurfaceMesh:
    if k is not None and not (isinstance(k, str) and k == "opt"):
        raise InputError("mesh.k", k, "none for a NURBS surface (its elements keep its weights)")
    p, q, ku, kv, pts, w = _nurbs_data(spec)
    a, b = _product_weights(w)
    ou, bu = _span_operators(ku, p, pts.shape[1], n[0])
    ov, bv = _span_operators(kv, q, pts.shape[0], n[1])
    h = np.concatenate([pts * w[..., None], w[..., None]], axis=-1)
    patch = np.einsum("iak,jbl,lkx->jiabx", ou, ov, h)
    wu, wv = ou @ a, ov @ b
    nan_u, nan_v = np.full(wu.shape[0], np.nan), np.full(wv.shape[0], np.nan)
    pu = Direction(wu / wu[:, :1], np.ones(wu.shape[0]), bu, nan_u, nan_u)
    pv = Direction(wv / wv[:, :1], np.ones(wv.shape[0]), bv, nan_v, nan_v)
    mesh = mesh_from_patches(patch[..., :3] / patch[..., 3:], pu, pv, "nurbs_surface")
    regular_or_raise(mesh, "geometry")
    return mesh


def _product_weights(w: NDArray) -> tuple[NDArray, NDArray]:
    """``w_ij = a_i b_j`` (u fastest: ``w[j, i]``), or an InputError (eq. 2.3)."""
    if not np.all(np.isfinite(w)) or np.any(w <= 0.0):
        raise InputError("geometry.weights", w.ravel().tolist(), "finite weights > 0")
    a, b = w[0] / w[0, 0], w[:, 0]
    if np.abs(np.outer(b, a) - w).max() > 1e-12 * w.max():
        raise InputError(
            "geometry.weights",
            w.ravel().tolist(),
            "product weights w[j][i] = a_i b_j (B-spline surfaces, surfaces of revolution, "
            "extrusions); general rational patches are not supported",
        )
    return a, b


_BUILDERS = {
    "cylinder": _cylinder_or_cone,
    "cone": _cylinder_or_cone,
    "sphere": _sphere,
    "rectangle": _rectangle,
    "nurbs_surface": _nurbs,
}


def mesh_surface(
    geometry: Mapping[str, Any], elements: ArrayLike, k: KFactor | tuple | list = "opt"
) -> SurfaceMesh:
    """An exact RANCF shell mesh of a surface (docs/derivations/shell.md sec. 2, 3).

    Parameters
    ----------
    geometry : mapping
        ``kind`` and that kind's keys (:data:`SURFACE_KEYS`), as in the module docstring.
    elements : [nu, nv]
        Elements along ``u`` and ``v`` (for ``nurbs_surface``: per knot span).
    k : float, "opt", None or [ku, kv]
        Mapping factors of the circular directions (eq. 3.7); ``"opt"``: Kopt per element.
    """
    kind = geometry.get("kind")
    if kind not in SURFACE_KEYS:
        raise InputError("geometry.kind", kind, ", ".join(f'"{s}"' for s in SURFACE_KEYS))
    extra = set(geometry) - set(SURFACE_KEYS[str(kind)]) - {"kind"}
    missing = [key for key in SURFACE_KEYS[str(kind)] if key not in geometry]
    if extra or missing:
        bad = sorted(extra)[0] if extra else missing[0]
        raise InputError(
            f"geometry.{bad}",
            geometry.get(bad, "missing"),
            f"the keys of {kind}: {', '.join(SURFACE_KEYS[str(kind)])}",
        )
    el = np.asarray(elements, dtype=object).ravel()
    if el.size != 2:
        raise InputError("mesh.elements", elements, "[nu, nv]: elements along u and along v")
    n = (check_element_count(el[0], "mesh.elements"), check_element_count(el[1], "mesh.elements"))
    return _BUILDERS[str(kind)](geometry, n, k)
