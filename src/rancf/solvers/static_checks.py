"""Checks that a converged static state is an equilibrium a user may be given.

Newton's method converges to any root of the residual, and a slender line has roots no real line
rests in: a cable folded back on itself inside an element, a loop of a cable carrying
compression, a line pushed through the seabed.  :func:`static_state_problems` names them; the
static solver refuses such a state (:func:`rancf.solvers.static.solve_static` raises
:class:`~rancf.errors.ConvergenceError`, ``rancf static`` exits 3 with the first problem in one
line).  Criteria (docs/guide/statics.md, "Checked equilibria"):

* **folded**: at a section sample point (:class:`~rancf.bodies.section_outputs.SectionSampler`,
  4 per element) the stretch ``λ = sqrt(1 + 2 ε)`` is below :data:`FOLD_STRETCH`, or two
  successive quarter-element chords point more than 90° apart where the reference's do not
  (the curve turns back on itself);
* **compressive loop**: the axial force ``N`` is below ``-N_allowed``,
  ``N_allowed = COMPRESSION_BUCKLING π² EI / ℓ² + COMPRESSION_ROUNDOFF EA`` with ``ℓ`` the
  element's reference length (a multiple of the element's own Euler load: a column below its
  buckling load passes; a cable, whose ``EI`` is negligible, may carry no compression beyond the
  round-off of its axial stiffness);
* **passing through itself**: two stretches of a body that are not neighbours along it (more
  than ``π r`` of arc apart, ``r`` the section radius: a tube bent no tighter than its own
  radius) come closer than ``r`` (:func:`self_crossing`; a loop of a planar line crosses
  itself, the distance is 0);
* **penetration**: an obstacle's largest penetration exceeds :data:`PENETRATION_LIMIT` of the
  diameter ``2 sqrt(A / π)`` of the thinnest body that touches it;
* **unresolved touchdown**: where a line meets or leaves a seabed (a fixed plane its wet weight
  ``w`` presses on), its bend radius ``T / w`` under the axial force ``T`` there is shorter than
  the element holding it.

The final state of a static solve is also checked for stability (:func:`instability`, only
where an element carries compression beyond round-off): a negative eigenvalue of the tangent
on the constraints' null space is an error, after an arc-length path a warning.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.section_outputs import SectionSampler
from rancf.bodies.shell_model import unstable_shells

__all__ = [
    "FOLD_STRETCH",
    "COMPRESSION_BUCKLING",
    "COMPRESSION_ROUNDOFF",
    "PENETRATION_LIMIT",
    "STABILITY_MODES",
    "StateCheck",
    "check_state",
    "instability",
    "most_compressed",
    "static_state_problems",
    "self_crossing",
    "touchdown_ratios",
]

#: Smallest stretch of a sample point that is not a fold.
FOLD_STRETCH = 0.5
#: Allowed compression as a multiple of the element's Euler load ``π² EI / ℓ²``.
COMPRESSION_BUCKLING = 4.0
#: Allowed compression as a fraction of ``EA`` (the round-off of a line's axial force).
COMPRESSION_ROUNDOFF = 1e-6
#: Largest penetration of an obstacle, as a fraction of the touching body's diameter: a tube sunk
#: wholly below the surface.  (MoorDyn's own soft seabeds sink lines by half a diameter: its
#: WD0050 regression input, kBot = 1e5 Pa/m, rests its 0.252 m chain 0.13 m deep.)
PENETRATION_LIMIT = 1.0
#: Eigenvalues of the tangent the stability check of a compressed state looks at (the lowest).
STABILITY_MODES = 6


@dataclass(frozen=True)
class StateCheck:
    """The checks of one static state: its problems (module docstring, one line each; empty: it
    may be reported as an equilibrium) and, per line touching a seabed, the largest ratio of an
    element's length to the bend radius at a touchdown in it and that element's length
    (:func:`touchdown_ratios`)."""

    problems: list[str]
    touchdowns: dict[str, tuple[float, float]]


def check_state(system: Any, q: NDArray[np.float64]) -> StateCheck:
    """The checks of the static state ``q`` (full coordinates) of ``system``: every flexible
    body sampled once (:class:`~rancf.bodies.section_outputs.SectionSampler`) for its folds,
    compressive loops, self-crossings and seabed bends."""
    problems: list[str] = []
    samplers = {}
    for name, model in zip(system.names, system.flex, strict=False):
        if not model.family.surface:  # the checks of lines (a shell's: instability)
            samplers[name] = sampler = SectionSampler(model)
            y = model.y_from_q(np.asarray(q)[system.body_slice(name)])
            problems += [f"body {name!r}: {p}" for p in _body_problems(model, y, sampler)]
    bends = _seabed_bends(system, q, samplers)
    problems += _penetration_problems(system, q) + _touchdown_problems(bends)
    return StateCheck(problems, _ratios(bends))


def static_state_problems(system: Any, q: NDArray[np.float64]) -> list[str]:
    """The problems of the static state ``q`` (full coordinates) of ``system`` (module
    docstring, :func:`check_state`), one line each; empty when it may be reported as an
    equilibrium."""
    return check_state(system, q).problems


def _body_problems(model: Model, y: NDArray[np.float64], sampler: SectionSampler) -> list[str]:
    """Folds and compressive loops of one flexible body at its model coordinates ``y``
    (``sampler``: the body's)."""
    vals = sampler.values(y)
    k = sampler.per_element
    stretch = np.sqrt(np.clip(1.0 + 2.0 * vals[:, 0], 0.0, None))
    el = np.minimum(np.arange(stretch.size) // k, model.n_el - 1)
    out = []
    x = sampler.positions(y)
    fold = _fold_element(x, sampler.positions(model.y0), k)
    if fold is not None or stretch.min() < FOLD_STRETCH:
        e = fold if fold is not None else int(el[np.argmin(stretch)])
        out.append(
            f"element {e} is folded (the curve turns back on itself or its stretch "
            f"falls to {stretch[el == e].min():.3g}, below {FOLD_STRETCH}): not an "
            "equilibrium a line rests in"
        )
    crossing = self_crossing(model, x, sampler.s)
    if crossing:
        out.append(crossing)
    starts, ell, mean = _element_forces(model, vals, sampler)
    allowed = (
        COMPRESSION_BUCKLING * np.pi**2 * model.props.ei / ell**2
        + COMPRESSION_ROUNDOFF * model.props.ea
    )
    e = int(np.argmin(mean + allowed))
    if mean[e] < -allowed[e]:
        out.append(
            f"a compressive loop: element {e} (s = {starts[e]:.4g} m) is compressed by "
            f"{-mean[e]:.4g} N on average, beyond the {allowed[e]:.3g} N it carries "
            f"({COMPRESSION_BUCKLING:g} π² EI / ℓ² + {COMPRESSION_ROUNDOFF:g} EA)"
        )
    return out


def _element_forces(
    model: Model, vals: NDArray[np.float64], sampler: SectionSampler
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Each element's start arc length, reference length and mean axial force over its sample
    points (``vals``: ``sampler``'s values).  The mean: a coarse element of a stiff line has
    its own strain oscillate about it by more than it (a 20-element chain: -1.0 MN to 2.4 MN
    within one element whose mean pulls 1.3 MN), while a loop compresses whole elements."""
    k = sampler.per_element
    el = np.minimum(np.arange(vals.shape[0]) // k, model.n_el - 1)
    starts = sampler.s[::k][: model.n_el]
    ell = np.diff(np.r_[starts, sampler.s[-1]])
    mean = np.array([vals[el == e, 1].mean() for e in range(model.n_el)])
    return starts, ell, mean


def most_compressed(system: Any, q: NDArray[np.float64]) -> tuple[str, int, float, float] | None:
    """The element carrying the largest mean compression beyond round-off
    (``N < -COMPRESSION_ROUNDOFF EA``) in the state ``q`` (full coordinates) of ``system``:
    its body, index, compression ``-N`` [N] and own Euler load ``π² EI / ℓ²`` [N]; None when
    no element does (a tensioned line)."""
    worst: tuple[str, int, float, float] | None = None
    for name, model in zip(system.names, system.flex, strict=False):
        if model.family.surface:
            continue
        sampler = SectionSampler(model)
        y = model.y_from_q(np.asarray(q)[system.body_slice(name)])
        _, ell, mean = _element_forces(model, sampler.values(y), sampler)
        e = int(np.argmin(mean))
        if mean[e] < -COMPRESSION_ROUNDOFF * model.props.ea and (
            worst is None or -mean[e] > worst[2]
        ):
            worst = (name, e, float(-mean[e]), float(np.pi**2 * model.props.ei / ell[e] ** 2))
    return worst


def instability(system: Any, y: NDArray[np.float64], lam: NDArray[np.float64] | None) -> str:
    """Why the converged static state ``y`` (model coordinates; multipliers ``lam``) of
    ``system`` is no stable equilibrium, or ``""``.  Checked only where an element carries
    compression beyond round-off (:func:`most_compressed`; a tensioned line pays nothing) or
    the system has a shell (whose membrane compression is not sampled: always checked): the
    lowest :data:`STABILITY_MODES` eigenvalues ``λ`` of the tangent stiffness on the null space
    of the constraints, ``K φ + Gᵀ μ = λ M φ``, ``G φ = 0``
    (:func:`rancf.solvers.modal.natural_modes`: dense for small models, shift-invert near 0
    beyond; a follower load's non-symmetric tangent by QZ / Arnoldi); one with a negative real
    part beyond round-off (a growth rate > 0) makes the state unstable: past a buckling load,
    it is no equilibrium a line rests in (docs/guide/statics.md, "Checked equilibria").  Not
    with drums: a drum's line has its length outside the drum as a coordinate, which the
    section samples do not follow (a hanging wire read as compressed by 778 N), and a drum
    held by a constant torque is a divergent equilibrium of its own (the line paid out weighs
    more: growth rate 0.49 1/s in ``drum-hoist.toml``) that its runs start from on purpose."""
    from rancf.solvers.modal import natural_modes  # modal builds on the solvers importing us

    if getattr(system, "drums", None):
        return ""
    q = system.q_from_y(np.asarray(y))
    worst = most_compressed(system, q)
    shells = [n for n, b in zip(system.names, system.flex, strict=False) if b.family.surface]
    n_free = int(np.sum(~system.fixed))
    if (worst is None and not shells) or n_free < 2:  # a shell's compression is not sampled
        return ""
    res = natural_modes(system, y, min(STABILITY_MODES, n_free - 1), lam)
    bad = (res.growth_rates > 0) & (np.asarray(res.eigenvalues).real < 0)
    if not np.any(bad):
        return ""
    low = complex(np.asarray(res.eigenvalues)[bad][0])
    if worst is None:
        return unstable_shells(shells, int(bad.sum()), low)
    name, e, n_c, euler = worst
    return (
        f"unstable equilibrium: the tangent stiffness has {int(bad.sum())} negative "
        f"eigenvalue(s) on the constraints' null space (lowest λ = ω² = {low.real:.4g} 1/s², "
        f"growth rate {float(res.growth_rates[bad].max()):.4g} 1/s), compression "
        f"{n_c:.4g} N in element {e} of body {name!r} (its own Euler load π² EI / ℓ² is "
        f"{euler:.3g} N): the state is past a buckling load; try more load steps, an "
        'imperfection (a slightly bent reference) or solver.static_method = "arc_length"'
    )


def self_crossing(model: Model, x: NDArray[np.float64], s: NDArray[np.float64]) -> str:
    """Where the polyline through the sample points ``x`` (arc lengths ``s``) of ``model``
    passes through itself: two of its chords more than ``π r`` of arc apart whose closest
    points are nearer than the section radius ``r`` (an open body's first and last chords left
    out: an end that meets the body, a cantilever rolled into a full circle, touches it), as a
    line naming both arc lengths (empty when there is none).  Candidate pairs come from a k-d
    tree of the chords' midpoints."""
    from scipy.spatial import cKDTree

    r = float(model.section.radius)
    a, b = x[:-1], x[1:]
    half = 0.5 * float(np.max(np.linalg.norm(b - a, axis=1)))
    pairs = cKDTree(0.5 * (a + b)).query_pairs(2.0 * half + r, output_type="ndarray")
    if not len(pairs):
        return ""
    i, j = np.sort(pairs, axis=1).T
    apart = s[j] - s[i + 1]  # the arc between the two chords
    if getattr(model.mesh, "closed", False):
        apart = np.minimum(apart, s[-1] - s[0] - (s[j + 1] - s[i]))
    keep = apart > np.pi * r
    if not getattr(model.mesh, "closed", False):  # an end that meets the body touches it
        keep &= (i > 0) & (j < len(a) - 1)
    i, j = i[keep], j[keep]
    d = _chord_distances(a[i], b[i], a[j], b[j])
    if not d.size or d.min() >= r:
        return ""
    k = int(np.argmin(d))
    return (
        f"the line passes through itself: at s = {s[i[k]]:.4g} m and s = {s[j[k]]:.4g} m "
        f"its centre line is {d[k]:.3g} m from itself, closer than its radius {r:.3g} m "
        "(a loop): not an equilibrium a line rests in"
    )


def _chord_distances(p0: NDArray, p1: NDArray, q0: NDArray, q1: NDArray) -> NDArray:
    """The distances of the segments ``p0 p1`` and ``q0 q1`` (rows), from their closest points
    (Ericson, *Real-Time Collision Detection*, sec. 5.1.9, parameters clamped to [0, 1])."""
    d1, d2, r0 = p1 - p0, q1 - q0, p0 - q0
    a = np.einsum("ij,ij->i", d1, d1)
    e = np.einsum("ij,ij->i", d2, d2)
    f = np.einsum("ij,ij->i", d2, r0)
    c = np.einsum("ij,ij->i", d1, r0)
    bb = np.einsum("ij,ij->i", d1, d2)
    den = a * e - bb * bb
    safe = np.where(den > 1e-300, den, 1.0)
    sp = np.where(den > 1e-14 * a * e, np.clip((bb * f - c * e) / safe, 0.0, 1.0), 0.0)
    tq = (bb * sp + f) / np.where(e > 0.0, e, 1.0)
    tq_c = np.clip(tq, 0.0, 1.0)
    sp = np.where(tq != tq_c, np.clip((bb * tq_c - c) / np.where(a > 0.0, a, 1.0), 0.0, 1.0), sp)
    gap = p0 + sp[:, None] * d1 - (q0 + tq_c[:, None] * d2)
    return np.linalg.norm(gap, axis=1)


def _fold_element(x: NDArray[np.float64], x0: NDArray[np.float64], k: int) -> int | None:
    """The first element where two successive sample chords (``k`` per element, positions
    ``x``; ``x0`` the reference's) point more than 90° apart though they did not in the
    reference (the curve turns back on itself), or None."""
    c, c0 = np.diff(x, axis=0), np.diff(x0, axis=0)
    back = (np.einsum("id,id->i", c[:-1], c[1:]) < 0.0) & (
        np.einsum("id,id->i", c0[:-1], c0[1:]) >= 0.0
    )
    bad = np.nonzero(back)[0]
    return int((bad[0] + 1) // k) if bad.size else None


def _touchdown_problems(bends: list[tuple[str, str, list]]) -> list[str]:
    """Lines whose bend where they leave a seabed is shorter than one of their elements: a
    line leaving a fixed plane its wet weight ``w`` presses on under the axial force ``T``
    bends there with the catenary's radius ``T / w``; an element longer than that cannot take
    the bend, and the stiff line settles into a state whose forces are far off (an inextensible
    U-shaped line of 40 elements: a fairlead force 4.5 times too small)."""
    out = []
    for name, ob_name, found in bends:
        for s, bend, ell in found:
            if bend < ell:
                out.append(
                    f"body {name!r}: its bend at s = {s:.4g} m has the radius T/w = "
                    f"{bend:.3g} m, shorter than its element ({ell:.3g} m): the touchdown is "
                    "not resolved and the line's forces, T among them, may be far off; refine "
                    "the mesh until its elements there are shorter than T/w, where it leaves "
                    f"{ob_name!r}"
                )
                break
    return out


def touchdown_ratios(system: Any, q: NDArray[np.float64]) -> dict[str, tuple[float, float]]:
    """Per line touching a seabed (module docstring) at the static state ``q``, the largest
    ratio ``ℓ / (T / w)`` of an element's length to the bend radius where the line meets or
    leaves the seabed in that element (``inf`` where ``T <= 0``) and that element's length
    ``ℓ``; lines with no touchdown are left out (:attr:`StateCheck.touchdowns` of
    :func:`check_state`, which has them with the problems)."""
    return check_state(system, q).touchdowns


def _ratios(bends: list[tuple[str, str, list]]) -> dict[str, tuple[float, float]]:
    """:func:`touchdown_ratios` from the bends of :func:`_seabed_bends`."""
    out: dict[str, tuple[float, float]] = {}
    for name, _, found in bends:
        for _, bend, ell in found:
            ratio = ell / bend if bend > 0.0 else np.inf
            if ratio > out.get(name, (0.0, 0.0))[0]:
                out[name] = (ratio, ell)
    return out


def _seabed_bends(
    system: Any, q: NDArray[np.float64], samplers: dict[str, SectionSampler]
) -> list[tuple[str, str, list]]:
    """``(body, plane, bends)`` of every cable body and fixed plane its wet weight presses on
    (:func:`_bends`; ``samplers``: the bodies')."""
    from rancf.system.seabed import pressing_weight

    out = []
    pairs = set(getattr(system, "contact_pairs", ()) or ())
    for ob, ob_name in zip(system.obstacles, getattr(system, "obstacle_names", ()), strict=False):
        if ob.kind != "plane" or ob.body is not None:
            continue
        n = np.asarray(ob.normal, dtype=float)
        n = n / np.linalg.norm(n)
        for name, model in zip(system.names, system.flex, strict=False):
            w = pressing_weight(system, name, np.r_[n, np.zeros(3 - n.size)])
            if not model.family.gradient or (name, ob_name) not in pairs or not w > 0.0:
                continue
            y = model.y_from_q(np.asarray(q)[system.body_slice(name)])
            point = np.asarray(ob.point, dtype=float)
            bends = _bends(model, samplers[name], y, point, n, w)
            out.append((name, ob_name, bends))
    return out


def _bends(
    model: Model, sampler: SectionSampler, y: NDArray, point: NDArray, n: NDArray, w: float
) -> list[tuple[float, float, float]]:
    """``(s, T / w, ℓ)`` where ``model`` at ``y`` leaves or meets the plane through ``point``
    (unit normal ``n``): the arc length ``s`` of the sample point, the bend radius under the
    axial force ``T`` there and the length ``ℓ`` of the element holding it.  ``T`` is read from
    the nodal forces at the element's inner nodes
    (:func:`~rancf.bodies.nodal_forces.nodal_axial_forces`: a stiff line's strain oscillates
    inside coarse elements by far more than its tension)."""
    from rancf.bodies.nodal_forces import nodal_axial_forces, recovers_axial_force

    if not recovers_axial_force(model) or model.n_el < 2:
        return []
    k, radius = sampler.per_element, model.section.radius
    gap = (sampler.positions(y) - point) @ n - radius
    touch = gap <= 5e-2 * radius  # the touchdown sensor's tolerance
    axial = nodal_axial_forces(model, y, np.zeros_like(y))  # inner nodes only are used
    starts = sampler.s[::k][: model.n_el]
    ell = np.diff(np.r_[starts, sampler.s[-1]])
    out = []
    for i in np.flatnonzero(touch[1:] != touch[:-1]):
        e = min(int(i) // k, model.n_el - 1)
        inner = [j for j in (e, e + 1) if 0 < j < model.n_nodes - 1]
        bend = max(max(float(axial[j]) for j in inner), 0.0) / w
        out.append((float(sampler.s[i]), bend, float(ell[e])))
    return out


def _penetration_problems(system: Any, q: NDArray[np.float64]) -> list[str]:
    """Obstacles penetrated deeper than :data:`PENETRATION_LIMIT` of the touching diameter."""
    if not getattr(system, "obstacle_names", None):
        return []
    from rancf.system.contact_states import contact_outputs

    states = contact_outputs(system, system.y_from_q(q))
    out = []
    for name, st in states.items():
        touching = [f for f, o in system.contact_pairs if o == name]
        if not touching:
            continue
        d = 2.0 * min(system.bodies[f].section.radius for f in touching)
        if st.penetration > PENETRATION_LIMIT * d:
            out.append(
                f"obstacle {name!r} is penetrated {st.penetration:.4g} m deep, more than "
                f"{PENETRATION_LIMIT:g} of the diameter {d:.4g} m: raise its stiffness "
                "(obstacles.stiffness) or leave it to the default"
            )
    return out
