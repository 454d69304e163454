"""Sliding joints: a flexible body runs through a place (a guide, fairlead, sheave point) without
friction (docs/derivations/sliding.md).

``Joint("sliding", ("rope", place))``: the first entry names a flexible body of cable or rod
elements (the body itself, no node), the second the place it runs through: a point of a rigid
body, a point mass, another body's node, or the ground (then ``position`` says where).  The
joint's unknowns are its reaction ``λ`` (``dim`` multipliers) and the material coordinate
``σ = e + ξ`` (element ``e``, its parameter ``ξ``) of the body's point at the place, kept in the
multiplier vector right after them (the core's slot, ``src/cpp/system/sliding.hpp``).  The place
must lie on the body in the reference configuration; ``σ`` starts at its closest point.  Outputs
report ``σ`` as the reference arc length ``s`` from the body's start (``NAME_s``).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.bodies.flexible import Model
from rancf.elements.cable import cable_shape_functions
from rancf.errors import InputError
from rancf.geometry.quadrature import gauss_legendre
from rancf.kernels.records import JointRecord, SlidingRecord, floats
from rancf.system.joint_data import JointFields
from rancf.system.places import Place

__all__ = [
    "sliding_body",
    "sliding_pair",
    "sliding_joint",
    "sliding_records",
    "sliding_starts",
    "start_multipliers",
    "arc_length",
    "material_coordinate",
    "sliding_values",
    "sliding_slots",
    "ON_BODY_RTOL",
]

#: The place lies on the body in the reference to this (relative to the system's size).
ON_BODY_RTOL = 1e-6

#: Samples per element of the search for the closest point (then Newton).
_SAMPLES = 16


def sliding_body(system: Any, j: JointFields) -> tuple[str, Model]:
    """The name and model of the flexible body of sliding joint ``j`` (its first place)."""
    spec = j.between[0]
    p = Place.parse(spec, system.single) if not isinstance(spec, Place) else spec
    key = f"{j.name or 'joints'}.between"
    body = system.bodies.get(p.body) if p.body is not None else None
    if not isinstance(body, Model) or not body.family.gradient or body.reduction is not None:
        raise InputError(
            key,
            str(spec),
            "first a flexible body of cable or rod elements with "
            'continuity "C1" (the body that slides, by name: "rope")',
        )
    if p.at is not None and system.single is None:
        raise InputError(
            key,
            str(spec),
            f"the body itself ({p.body!r}), not one of its "
            "places: it slides through the second place",
        )
    return str(p.body), body


def sliding_pair(system: Any, j: JointFields, rows: Any) -> tuple[int, int]:
    """The place records of sliding joint ``j``: the body's node 0 (a placeholder the core
    does not evaluate) and the place it runs through (the ground at ``position``)."""
    name, body = sliding_body(system, j)
    key = f"{j.name or 'joints'}"
    b = system.resolve(j.between[1])
    if b.body == name:
        raise InputError(f"{key}.between", str(j.between[1]), "a place off the sliding body")
    point = None
    if b.body is None:
        if j.position is None or np.asarray(j.position).size != system.dim:
            raise InputError(
                f"{key}.position",
                None if j.position is None else list(j.position),
                f"the guide's position on the ground "
                f"({system.dim} numbers): required for a sliding joint to the "
                "ground",
            )
        point = np.r_[np.asarray(j.position, dtype=float), np.zeros(3 - system.dim)]
    elif j.position is not None:
        raise InputError(
            f"{key}.position",
            list(j.position),
            "only for a sliding joint to the ground (a place on a body is where it is)",
        )
    a = system.place_index(Place(name, 0), rows)
    return a, system.place_index(b, rows, point)


def sliding_joint(system: Any, j: JointFields, rows: Any) -> JointRecord:
    """The core's record of sliding joint ``j``, its places registered in ``rows``
    (:func:`sliding_pair`)."""
    a, b = sliding_pair(system, j, rows)
    return JointRecord("sliding", a, b, body=system.flex.index(sliding_body(system, j)[1]))


def _nodal(body: Model, y: NDArray | None = None) -> NDArray:
    """The body's nodal positions and gradients ``(n_nodes, 2, dim)`` at its coordinates ``y``
    (default the reference)."""
    q = body.q0 if y is None else body.q_from_y(y)
    d = body.dim
    return q.reshape(body.n_nodes, body.dpn)[:, : 2 * d].reshape(body.n_nodes, 2, d)


def _evaluate(body: Model, nodal: NDArray, sigma: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """Centre line ``r``, ``r_σ``, ``r_σσ`` ``(k, dim)`` at material coordinates ``sigma`` (the
    core's ``slide_point``: the end elements continued beyond the ends)."""
    sigma = np.atleast_1d(np.asarray(sigma, dtype=float))
    m = body.mesh
    e = np.clip(np.floor(sigma).astype(int), 0, body.n_el - 1)
    xi = sigma - e
    out = []
    for order in range(3):
        n = np.stack(
            [
                cable_shape_functions(m.weights[k : k + 1], m.scales[k : k + 1], [x])[order][0, 0]
                for k, x in zip(e, xi, strict=True)
            ]
        )
        el = np.concatenate([nodal[e], nodal[e + 1]], axis=1)  # (k, 4, dim)
        out.append(np.einsum("kj,kjd->kd", n, el))
    return out[0], out[1], out[2]


def material_coordinate(
    body: Model,
    x: ArrayLike,
    y: NDArray | None = None,
    guess: float | None = None,
    beyond: bool = False,
) -> tuple[float, float]:
    """``σ`` of the body's point closest to ``x`` (its ``dim`` components), and the distance:
    the nearest of ``_SAMPLES`` points per element (or ``guess``), then Newton on
    ``(r(σ) - x) · r_σ = 0`` kept within the body (``beyond``: on the end elements continued
    past the ends, as the joint holds them)."""
    x = np.asarray(x, dtype=float)[: body.dim]
    nodal = _nodal(body, y)
    hi = float(body.n_el)
    if guess is None:
        xi = np.linspace(0.0, 1.0, _SAMPLES + 1)
        pts = body.mesh.evaluate(xi, nodal)  # (n_el, k, dim)
        dist = np.linalg.norm(pts - x, axis=-1)
        e, k = np.unravel_index(int(np.argmin(dist)), dist.shape)
        sigma = float(e) + float(xi[k])
    else:
        sigma = float(guess)
    for _ in range(30):
        r, rs, rss = (v[0] for v in _evaluate(body, nodal, np.array([sigma])))
        f, df = (r - x) @ rs, rs @ rs + (r - x) @ rss
        step = -f / df if df > 0 else -f / (rs @ rs)
        new = sigma + step if beyond else min(max(sigma + step, 0.0), hi)
        if abs(new - sigma) <= 1e-14 * max(hi, 1.0):
            sigma = new
            break
        sigma = new
    r = _evaluate(body, nodal, np.array([sigma]))[0][0]
    return sigma, float(np.linalg.norm(r - x))


def arc_length(body: Model, sigma: ArrayLike) -> NDArray[np.float64]:
    """The reference arc length from the body's start at material coordinates ``sigma``
    (12-point Gauss rule per element on ``|r0_ξ|``; the end elements continued beyond the
    ends)."""
    sigma = np.atleast_1d(np.asarray(sigma, dtype=float))
    nodal = _nodal(body)
    lengths = body.mesh.arc_lengths()
    before = np.r_[0.0, np.cumsum(lengths)]
    e = np.clip(np.floor(sigma).astype(int), 0, body.n_el - 1)
    xi = sigma - e
    xg, wg = gauss_legendre(12)
    out = np.empty(sigma.size)
    for i, (k, x) in enumerate(zip(e, xi, strict=True)):
        pts = np.array([float(k) + x * g for g in xg])
        speed = np.linalg.norm(_evaluate(body, nodal, pts)[1], axis=1)
        out[i] = before[k] + x * float(wg @ speed)
    return out


def sliding_records(system: Any, joints: Sequence[JointFields]) -> tuple[SlidingRecord, ...]:
    """The core's record of the element geometry of every body a sliding joint runs along."""
    out: dict[str, SlidingRecord] = {}
    for j in joints:
        if not j.entry.slides:
            continue
        name, body = sliding_body(system, j)
        if name not in out:
            m = body.mesh
            out[name] = SlidingRecord(
                body=system.flex.index(body),
                weights=floats(m.weights),
                scales=floats(m.scales),
                closed=bool(body.closed),
            )
    return tuple(out.values())


def sliding_starts(system: Any) -> None:
    """After the core is built: each sliding joint's start ``σ`` (``system.sliding_start``:
    joint index -> σ), its place on the body in the reference configuration."""
    system.sliding_start, system.sliding_passed = {}, set()
    for k, j in enumerate(system.joints):
        if not j.entry.slides:
            continue
        name, body = sliding_body(system, j)
        x, _ = system.core.place(system.model.joints[k].b, system.y0, 0.0)
        sigma, gap = material_coordinate(body, x)
        if not gap <= ON_BODY_RTOL * system.size:
            raise InputError(
                f"{j.name or f'joints[{k}]'}.between",
                [str(v) for v in j.between],
                f"a place on the body {name!r} in the reference configuration (it is "
                f"{gap:.4g} m from it; move the place or the body)",
            )
        system.sliding_start[k] = sigma


def start_multipliers(system: Any, y: NDArray | None = None) -> NDArray[np.float64]:
    """The multipliers to start from: zero, and the sliding joints' ``σ`` in their slots: at
    the reference, or (``y``: a state to start from) the body's point closest to the place
    (:func:`sliding_slots`)."""
    if y is not None:
        return sliding_slots(system, y)
    lam = np.zeros(system.m)
    for k, sigma in getattr(system, "sliding_start", {}).items():
        lam[system.joint_rows[k] + system.dim] = sigma
    return lam


def sliding_values(
    system: Any, k: int, y: NDArray, lam: NDArray, warn: Callable[[str], None] | None = None
) -> float:
    """The arc length ``s`` [m] of sliding joint ``k`` at the state ``(y, λ)`` (its ``σ`` in
    the slot), with one warning line (``warn``, default :func:`warnings.warn`) when the body's
    end has passed through the place (once a joint)."""
    j = system.joints[k]
    name, body = sliding_body(system, j)
    sigma = float(lam[system.joint_rows[k] + system.dim])
    passed: set[int] = getattr(system, "sliding_passed", set())
    if not body.closed and not (0.0 <= sigma <= body.n_el) and k not in passed:
        passed.add(k)
        msg = (
            f"rancf: sliding joint {j.name or k!r}: the {'start' if sigma < 0 else 'end'} "
            f"of body {name!r} has passed through its place (material coordinate "
            f"{sigma:.6g} of 0..{body.n_el} elements): the joint continues the end element "
            "beyond the body; make the body longer"
        )
        (warn or (lambda s: warnings.warn(s, stacklevel=3)))(msg)
    if body.closed:
        laps, rest = divmod(sigma, float(body.n_el))
        return float(laps * np.sum(body.mesh.arc_lengths()) + arc_length(body, rest)[0])
    return float(arc_length(body, sigma)[0])


def sliding_slots(system: Any, y: NDArray, lam: NDArray | None = None) -> NDArray[np.float64]:
    """Multipliers ``(m,)`` that are zero but in the sliding joints' slots: those of ``lam``
    (a run's stored multipliers), or else found from the state ``y``: the body's point closest
    to the place (:func:`material_coordinate`; what the joint holds at a converged state)."""
    out = np.zeros(system.m)
    for k, j in enumerate(system.joints):
        if not j.entry.slides:
            continue
        slot = system.joint_rows[k] + system.dim
        if lam is not None:
            out[slot] = lam[slot]
            continue
        name, body = sliding_body(system, j)
        x, _ = system.core.place(system.model.joints[k].b, np.ascontiguousarray(y), 0.0)
        yb = np.asarray(y)[system.body_slice(name)]
        out[slot] = material_coordinate(body, x, yb, beyond=not body.closed)[0]
    return out
