"""A block of stored dynamic rows through the compiled core at once, for
:meth:`rancf.system.outputs.SystemOutputs.rows` (the same values as its row-by-row formulas):

* :func:`block_derived`: the consistent accelerations and multipliers, the balance residual
  with them and the joints' reactions of every row (``SystemIntegrator.derived_rows``, one
  call), then the supports' reactions from the held rows of the residuals
  (:func:`rancf.bodies.reactions.support_reactions` on the stack of rows); the assembly that
  gives a row's residual also gives its element forces and the bodies' own terms, which the
  nodal axial forces need (no second residual, no further force pass);
* :func:`block_sections`: the section strains and curvatures of every row, one call of the
  core a body where the body's length is the same at every row (no winch), and the nodal
  axial forces of the block at once (:func:`rancf.bodies.nodal_forces.nodal_axial_forces`).

Only for dynamic rows without rods' directors or sliding joints (their multipliers' slots and
extra columns are the row loop's).  Rows with contact take the forces of the step that ended at
them (``alpha``, as the row loop does), and their obstacles' columns come from
:func:`contact_row` row by row.  :func:`rod_triads` sets rods' triads from a row's stored
directors for the row loop.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.nodal_forces import nodal_axial_forces
from rancf.bodies.reactions import reaction_row, support_reactions
from rancf.system.seabed_friction import seabed_friction

__all__ = ["block_derived", "block_sections", "contact_row", "takes_block", "rod_triads"]


def takes_block(system: Any, static: bool, directors: NDArray | None, k: int) -> bool:
    """Whether ``k`` rows of ``system`` go through the core as one block."""
    sliding = any(j.entry.slides for j in system.joints)
    return not (static or sliding) and directors is None and k > 0


def block_derived(
    outputs: Any,
    t: NDArray,
    ys: NDArray,
    vs: NDArray,
    out: dict[str, NDArray],
    alpha: NDArray | None = None,
) -> tuple[NDArray, NDArray]:
    """Accelerations ``out["a"]``, multipliers ``out["lam"]`` and reactions ``out["r"]`` of the
    states ``ys``, ``vs`` ``(k, n)`` at times ``t``; returns the bodies' own terms of the
    balance and the element forces ``(k, n)`` each, from the assembly that gives the residual
    (for the nodal axial forces; empty without bodies that need them).  ``alpha`` ``(k, 2 n)``:
    systems with contact, each row's step's generalized-α point ``(y_f, v_f)``, whose contact
    forces the row takes (without it the row's own state's)."""
    s = outputs.system
    k, nj = ys.shape[0], len(s.joints)
    a, lam = np.empty((k, s.n)), np.empty((k, s.m))
    res, jr = np.empty((k, s.n + s.m)), np.empty((k, nj, 6))
    res0, fint = (np.empty((k, s.n)), np.empty((k, s.n))) if outputs.recovered else (None, None)
    step = np.ascontiguousarray(alpha, dtype=float) if s.has_contact and alpha is not None else None
    outputs.integrator.derived_rows(
        np.ascontiguousarray(t),
        np.ascontiguousarray(ys),
        np.ascontiguousarray(vs),
        a,
        lam,
        res,
        jr,
        nj,
        res0,
        fint,
        step,
    )
    out["a"], out["lam"] = s.q_from_y(a), lam
    parts = []
    for name, b in outputs.flex:
        sl = s.body_slice(name)
        if b.supports:
            parts.append(
                reaction_row(support_reactions(b, ys[:, sl], res[:, sl], outputs.labels[name]))
            )
    for j in range(nj):
        parts.append(jr[:, j, : s.dim])
        if len(outputs.joint_names[j]) > s.dim:  # the joint reports a moment
            parts.append(jr[:, j, 5:] if s.dim == 2 else jr[:, j, 3:])
    if s.has_contact:
        parts.append(_contact_block(s, ys, vs, step))
    out["r"] = np.concatenate(parts, axis=1) if parts else np.empty((k, 0))
    if res0 is None or fint is None:
        return np.empty((k, 0)), np.empty((k, 0))
    return res0, fint


def _contact_block(s: Any, ys: NDArray, vs: NDArray, alpha: NDArray | None) -> NDArray:
    """:func:`contact_row` of every row, its contact state that of the step that ended at it
    (``alpha``) or else its own."""
    n = s.n
    rows = []
    for i in range(ys.shape[0]):
        yc, vc = (alpha[i, :n], alpha[i, n:]) if alpha is not None else (ys[i], vs[i])
        rows.append(contact_row(s, yc, vc, ys[i]))
    return np.array(rows).reshape(ys.shape[0], -1)


def contact_row(s: Any, yc: NDArray, vc: NDArray | None, y1: NDArray | None) -> NDArray:
    """The contact columns of one row: per obstacle the normal and friction force, moment,
    contact length and penetration (:func:`rancf.system.contact_states.contact_outputs` at
    the contact state ``yc``, ``vc``, ``y1``), per pair of flexible bodies the contact force
    and penetration (at ``yc``)."""
    from rancf.system.contact_states import contact_outputs  # loaded with contact only

    parts: list = []
    totals: dict = {}  # a static state's seabed friction (static_friction)
    if vc is None and getattr(s, "static_friction", False):
        seabed_friction(s, yc, totals)
    for name, c in contact_outputs(s, yc, vc, y1).items():
        fr = totals.get(name, c.friction)
        parts += [c.normal, fr, np.atleast_1d(c.moment), [c.length, c.penetration]]
    if s.body_contacts:
        bo = np.empty(3 * len(s.body_contacts))
        s.contact.body_outputs(np.ascontiguousarray(yc), bo)
        parts += [[bo[3 * j + 2], max(0.0, -bo[3 * j])] for j in range(len(s.body_contacts))]
    return np.concatenate(parts) if parts else np.empty(0)


def block_sections(
    outputs: Any,
    raws: dict[str, list[NDArray]],
    factors: dict[str, list[float]],
    ys: NDArray,
    t: NDArray,
    nodal: dict[str, list[NDArray]],
    res0: NDArray,
    internal: NDArray | None = None,
) -> None:
    """Strains and curvatures ``(k, n_points, w)`` of the rows ``ys`` into ``raws``, their
    bodies' length factors (:func:`~rancf.system.winches.winch_factor`) into ``factors`` and,
    for the bodies whose axial force comes from the nodal forces, those of the bodies' own
    terms ``res0`` ``(k, n...)`` and element forces ``internal`` (``(k, n)``; computed if not
    given) into ``nodal``, ``(k, n_nodes)`` a block."""
    s = outputs.system
    for name, b in outputs.flex:
        sl, samp = s.body_slice(name), outputs.samplers[name]
        if name in outputs.recovered:  # the axial force from the nodal forces
            fi = None if internal is None else internal[:, sl]
            nodal[name].append(nodal_axial_forces(b, ys[:, sl], res0[:, sl], fi))
        if not getattr(s, "winches", ()):  # the same length at every row: one call
            factors[name] += [1.0] * len(t)
            raws[name].append(samp.raw(ys[:, sl], 1.0))
            continue
        from rancf.system.winches import winch_factor  # the body's length at each row

        fs = [winch_factor(s, name, float(x), y) for x, y in zip(t, ys, strict=True)]
        factors[name] += fs
        if all(f == fs[0] for f in fs):
            raws[name].append(samp.raw(ys[:, sl], fs[0]))
        else:
            raws[name] += [samp.raw(y[None, sl], f) for y, f in zip(ys, fs, strict=True)]


@contextlib.contextmanager
def rod_triads(system: Any, flex: Sequence[tuple[str, Any]]) -> Iterator:
    """Rods: a setter of the triads of a row from its directors (``flex``: the system's
    flexible bodies by name); restored at the end."""
    rods = [
        (b, kern, system.body_slice(name))
        for name, b in flex
        if (kern := b.family.rod_kernel(b.kernel)) is not None
    ]
    saved = [(kern.tref.copy(), kern.m1ref.copy()) for _, kern, _ in rods]

    def set_row(y: NDArray, m1: NDArray) -> None:
        start = 0
        for b, kern, sl in rods:
            g = b.q_from_y(y[sl]).reshape(b.n_nodes, b.dpn)[:, 3:6]
            kern.tref[...] = (g / np.linalg.norm(g, axis=1, keepdims=True)).reshape(kern.tref.shape)
            kern.m1ref[...] = m1[start : start + 3 * b.n_nodes].reshape(kern.m1ref.shape)
            y[sl][b.twist_indices()] = 0.0
            start += 3 * b.n_nodes

    try:
        yield set_row
    finally:
        for (_, kern, _), (tr, m1) in zip(rods, saved, strict=True):
            kern.tref[...] = tr
            kern.m1ref[...] = m1
