"""Compiled (Numba) hot paths: element kernels, banded assembly, banded LU, one Newton step.

These functions implement exactly the same formulas as the NumPy reference kernels
(:mod:`rancf.elements.cable_mechanics`, :mod:`rancf.elements.beam`) and the generalized-α step of
:mod:`rancf.solvers.dynamic`; a test compares the two paths to round-off.  Everything here works on
plain arrays so that one call does a whole Newton iteration loop without Python overhead per
element, quadrature point or iteration.  Compiled code is cached on disk (``cache=True``), so a
second process does not recompile.

Model arrays (see :class:`CompiledModel`): element kind ``kind`` (0 cable, 1 beam), ``dim``,
``dpn`` (coordinates per node), cable quadrature data ``n1, n2 (n_el, n_qp, 4)``, ``gw (n_qp,)``,
``s0, k0, j0 (n_el, n_qp)``; beam data ``l0 (n_el,)``, ``d0 (n_el, 2)``; clamp rotations
``rot_of_node (n_nodes,)`` (index into ``rot (n_rot, dim, dim)`` or -1).  Band storage is
``ab[ku + i - j, j] = A[i, j]``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from rancf.elements.cable_mechanics import ETA

__all__ = [
    "assemble",
    "strain_energy",
    "band_matvec",
    "band_lu_solve",
    "newton_step",
]

_CACHE = True
_ETA2 = ETA**2


_FM = {"contract", "arcp", "reassoc"}  # no "nnan"/"ninf": NaN checks stay meaningful


@njit(cache=_CACHE, fastmath=_FM, inline="always", error_model="numpy")
def _cable_qp_2d(a0, a1, b0, b1, s0, k0, j0, ea, ei, g, h, want_h):  # noqa: PLR0913
    """Gradient ``g (4,)`` and Hessian ``h (4, 4)`` of the energy density, planar (z = a, b)."""
    aa = a0 * a0 + a1 * a1
    inv = 1.0 / aa
    p = inv / math.sqrt(aa)  # |a|^-3
    q25 = -3.0 * p * inv  # d p / d(a_i) = q25 a_i
    eps = (aa - s0) / (2.0 * s0)
    fe = ea * j0 * eps / s0
    c = a0 * b1 - a1 * b0
    delta = c * p - k0
    ca0, ca1 = b1, -b0
    cb0, cb1 = -a1, a0
    pa0, pa1 = q25 * a0, q25 * a1
    ka0 = p * ca0 + c * pa0
    ka1 = p * ca1 + c * pa1
    kb0, kb1 = p * cb0, p * cb1
    f = ei * j0 * delta
    g[0] = fe * a0 + f * ka0
    g[1] = fe * a1 + f * ka1
    g[2] = f * kb0
    g[3] = f * kb1
    if not want_h:
        return
    s = ei * j0
    q35 = 15.0 * p * inv * inv
    eaj = ea * j0 / (s0 * s0)
    sd = s * delta
    # a-a block (symmetric)
    paa00 = q25 + q35 * a0 * a0
    paa01 = q35 * a0 * a1
    paa11 = q25 + q35 * a1 * a1
    h[0, 0] = eaj * a0 * a0 + fe + s * ka0 * ka0 + sd * (2.0 * ca0 * pa0 + c * paa00)
    h[0, 1] = eaj * a0 * a1 + s * ka0 * ka1 + sd * (ca0 * pa1 + pa0 * ca1 + c * paa01)
    h[1, 1] = eaj * a1 * a1 + fe + s * ka1 * ka1 + sd * (2.0 * ca1 * pa1 + c * paa11)
    h[1, 0] = h[0, 1]
    # a-b block: k_ab = p [[0, 1], [-1, 0]] + p_a c_b^T
    h[0, 2] = s * ka0 * kb0 + sd * (pa0 * cb0)
    h[0, 3] = s * ka0 * kb1 + sd * (p + pa0 * cb1)
    h[1, 2] = s * ka1 * kb0 + sd * (-p + pa1 * cb0)
    h[1, 3] = s * ka1 * kb1 + sd * (pa1 * cb1)
    h[2, 0] = h[0, 2]
    h[3, 0] = h[0, 3]
    h[2, 1] = h[1, 2]
    h[3, 1] = h[1, 3]
    h[2, 2] = s * kb0 * kb0
    h[2, 3] = s * kb0 * kb1
    h[3, 2] = h[2, 3]
    h[3, 3] = s * kb1 * kb1


@njit(cache=_CACHE, fastmath=_FM, inline="always", error_model="numpy")
def _cable_qp_3d(a, b, s0, k0, j0, qr, ea, ei, g, h, want_h):  # noqa: PLR0913
    """Gradient ``g (6,)`` and Hessian ``h (6, 6)`` of the energy density, spatial.

    ``u = κ² = |a × b|² / |a|⁶``; at curved reference points (``qr = η² κ0² > 0``) the bending
    term is ``½ EI (1 + η²)(κr - κr0)²`` with ``κr = sqrt(u + qr)``, ``κr0 = κ0 sqrt(1 + η²)``.
    """
    aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2]
    bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2]
    ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    eps = (aa - s0) / (2.0 * s0)
    fe = ea * j0 * eps / s0
    c0 = a[1] * b[2] - a[2] * b[1]
    c1 = a[2] * b[0] - a[0] * b[2]
    c2 = a[0] * b[1] - a[1] * b[0]
    q = c0 * c0 + c1 * c1 + c2 * c2
    sx = aa**-3.0
    u = q * sx
    curved = qr > 0.0
    half = 0.5 * ei * j0 * (1.0 + _ETA2 if curved else 1.0)
    ratio = 0.0
    h2 = 0.0
    if curved:
        kr2 = u + qr
        ratio = k0 * math.sqrt(1.0 + _ETA2) / math.sqrt(kr2)
        h2 = half * ratio / (2.0 * kr2)
    h1 = half * (1.0 - ratio)
    qa = np.empty(3)
    qb = np.empty(3)
    sa = np.empty(3)
    ua = np.empty(3)
    ub = np.empty(3)
    s4 = -6.0 * aa**-4.0
    for i in range(3):
        qa[i] = 2.0 * bb * a[i] - 2.0 * ab * b[i]
        qb[i] = 2.0 * aa * b[i] - 2.0 * ab * a[i]
        sa[i] = s4 * a[i]
        ua[i] = qa[i] * sx + q * sa[i]
        ub[i] = qb[i] * sx
        g[i] = fe * a[i] + h1 * ua[i]
        g[3 + i] = h1 * ub[i]
    if not want_h:
        return
    s5 = 48.0 * aa**-5.0
    for i in range(3):
        for j in range(3):
            eye = 1.0 if i == j else 0.0
            qaa = 2.0 * bb * eye - 2.0 * b[i] * b[j]
            qbb = 2.0 * aa * eye - 2.0 * a[i] * a[j]
            qab = 4.0 * a[i] * b[j] - 2.0 * b[i] * a[j] - 2.0 * ab * eye
            saa = s4 * eye + s5 * a[i] * a[j]
            uaa = qaa * sx + qa[i] * sa[j] + sa[i] * qa[j] + q * saa
            uab = qab * sx + sa[i] * qb[j]
            ubb = qbb * sx
            h[i, j] = ea * j0 / (s0 * s0) * a[i] * a[j] + fe * eye + h1 * uaa + h2 * ua[i] * ua[j]
            h[i, 3 + j] = h1 * uab + h2 * ua[i] * ub[j]
            h[3 + j, i] = h[i, 3 + j]
            h[3 + i, 3 + j] = h1 * ubb + h2 * ub[i] * ub[j]


@njit(cache=_CACHE, fastmath=_FM, error_model="numpy")
def _cable_element(e, el, n1, n2, gw, s0, k0, j0, qr, ea, ei, dim, fe, ke, want_k, a, b, g, h):  # noqa: PLR0913
    """Forces ``fe (4 dim,)`` and stiffness ``ke`` of cable element ``el`` with coordinates ``e``.

    ``a, b, g, h`` are work arrays of sizes ``dim, dim, 2 dim, (2 dim, 2 dim)``.
    """
    nq = gw.size
    fe[:] = 0.0
    if want_k:
        ke[:, :] = 0.0
    for q in range(nq):
        for i in range(dim):
            ai = 0.0
            bi = 0.0
            for k in range(4):
                ai += n1[el, q, k] * e[k * dim + i]
                bi += n2[el, q, k] * e[k * dim + i]
            a[i] = ai
            b[i] = bi
        if dim == 2:
            _cable_qp_2d(
                a[0], a[1], b[0], b[1], s0[el, q], k0[el, q], j0[el, q], ea, ei, g, h, want_k
            )
        else:
            _cable_qp_3d(a, b, s0[el, q], k0[el, q], j0[el, q], qr[el, q], ea, ei, g, h, want_k)
        w = gw[q]
        for k in range(4):
            for i in range(dim):
                fe[k * dim + i] += w * (n1[el, q, k] * g[i] + n2[el, q, k] * g[dim + i])
        if want_k:
            for k in range(4):
                for l in range(k, 4):
                    c11 = w * n1[el, q, k] * n1[el, q, l]
                    c12 = w * n1[el, q, k] * n2[el, q, l]
                    c21 = w * n2[el, q, k] * n1[el, q, l]
                    c22 = w * n2[el, q, k] * n2[el, q, l]
                    for i in range(dim):
                        for j in range(dim):
                            ke[k * dim + i, l * dim + j] += (
                                c11 * h[i, j]
                                + c12 * h[i, dim + j]
                                + c21 * h[dim + i, j]
                                + c22 * h[dim + i, dim + j]
                            )
    if want_k:  # the lower block triangle from the upper one (K is symmetric)
        for k in range(4):
            for l in range(k + 1, 4):
                for i in range(dim):
                    for j in range(dim):
                        ke[l * dim + j, k * dim + i] = ke[k * dim + i, l * dim + j]


@njit(cache=_CACHE, error_model="numpy")
def _cable_energy(e, n1, n2, gw, s0, k0, j0, qr, ea, ei, dim):  # noqa: PLR0913
    total = 0.0
    for q in range(gw.size):
        a = np.zeros(dim)
        b = np.zeros(dim)
        for i in range(dim):
            for k in range(4):
                a[i] += n1[q, k] * e[k * dim + i]
                b[i] += n2[q, k] * e[k * dim + i]
        aa = 0.0
        for i in range(dim):
            aa += a[i] * a[i]
        eps = (aa - s0[q]) / (2.0 * s0[q])
        if dim == 2:
            kappa = (a[0] * b[1] - a[1] * b[0]) * aa**-1.5
            bend = (kappa - k0[q]) ** 2
        else:
            c0 = a[1] * b[2] - a[2] * b[1]
            c1 = a[2] * b[0] - a[0] * b[2]
            c2 = a[0] * b[1] - a[1] * b[0]
            u = (c0 * c0 + c1 * c1 + c2 * c2) * aa**-3.0
            if qr[q] > 0.0:  # regularized magnitude curvature, see _cable_qp_3d
                kr = math.sqrt(u + qr[q])
                bend = (1.0 + _ETA2) * (kr - k0[q] * math.sqrt(1.0 + _ETA2)) ** 2
            else:
                bend = u
        total += gw[q] * 0.5 * (ea * eps * eps + ei * bend) * j0[q]
    return total


@njit(cache=_CACHE, inline="always", error_model="numpy")
def _beam_local(e, l0, d0x, d0y):
    """Chord length, direction cosines, chord strain and local rotations of a beam element."""
    dx = e[3] - e[0]
    dy = e[4] - e[1]
    length = math.sqrt(dx * dx + dy * dy)
    tm = 0.5 * (e[2] + e[5])
    cr, sr = math.cos(tm), math.sin(tm)
    rx = cr * d0x - sr * d0y
    ry = sr * d0x + cr * d0y
    alpha = tm + math.atan2(rx * dy - ry * dx, rx * dx + ry * dy)
    eps = (length * length - l0 * l0) / (2.0 * l0 * l0)
    return length, dx / length, dy / length, eps, e[2] - alpha, e[5] - alpha


@njit(cache=_CACHE, error_model="numpy")
def _beam_element(e, l0, d0x, d0y, ea, ei, fe, ke, want_k):  # noqa: PLR0913
    length, c, s, eps, t1, t2 = _beam_local(e, l0, d0x, d0y)
    n = ea * eps * length / l0
    m1 = ei / l0 * (4.0 * t1 + 2.0 * t2)
    m2 = ei / l0 * (2.0 * t1 + 4.0 * t2)
    r = (-c, -s, 0.0, c, s, 0.0)
    z = (s, -c, 0.0, -s, c, 0.0)
    bm = np.zeros((3, 6))
    for j in range(6):
        bm[0, j] = r[j]
        bm[1, j] = -z[j] / length
        bm[2, j] = -z[j] / length
    bm[1, 2] += 1.0
    bm[2, 5] += 1.0
    for j in range(6):
        fe[j] = bm[0, j] * n + bm[1, j] * m1 + bm[2, j] * m2
    if not want_k:
        return
    d00 = ea * (length * length / (l0 * l0 * l0) + eps / l0)
    k4 = 4.0 * ei / l0
    k2 = 2.0 * ei / l0
    for i in range(6):
        for j in range(6):
            v = d00 * bm[0, i] * bm[0, j]
            v += k4 * (bm[1, i] * bm[1, j] + bm[2, i] * bm[2, j])
            v += k2 * (bm[1, i] * bm[2, j] + bm[2, i] * bm[1, j])
            v += n / length * z[i] * z[j]
            v += (m1 + m2) / (length * length) * (r[i] * z[j] + z[i] * r[j])
            ke[i, j] = v


@njit(cache=_CACHE, error_model="numpy")
def _beam_energy(e, l0, d0x, d0y, ea, ei):
    _, _, _, eps, t1, t2 = _beam_local(e, l0, d0x, d0y)
    return 0.5 * ea * eps * eps * l0 + 2.0 * ei / l0 * (t1 * t1 + t1 * t2 + t2 * t2)


@njit(cache=_CACHE, inline="always", error_model="numpy")
def _rotate_element(e_vec, ke, fe, el, dim, dpn, rot_of_node, rot, to_q):  # noqa: PLR0913
    """Apply the clamp rotations of the element's two nodes.

    ``to_q``: map element coordinates ``y -> q`` (``e_vec`` only); otherwise map forces and
    stiffness back, ``f_y = Tᵀ f_q``, ``K_y = Tᵀ K_q T``.
    """
    for a in range(2):
        r = rot_of_node[el + a]
        if r < 0:
            continue
        o = a * dpn + dim
        bas = rot[r]
        if to_q:
            tmp = np.zeros(dim)
            for i in range(dim):
                for j in range(dim):
                    tmp[i] += bas[i, j] * e_vec[o + j]
            e_vec[o : o + dim] = tmp
            continue
        tmp = np.zeros(dim)
        for i in range(dim):
            for j in range(dim):
                tmp[i] += bas[j, i] * fe[o + j]
        fe[o : o + dim] = tmp
        if ke.shape[0] == 0:
            continue
        nde = ke.shape[0]
        rows = np.zeros((dim, nde))
        for i in range(dim):
            for j in range(dim):
                for c in range(nde):
                    rows[i, c] += bas[j, i] * ke[o + j, c]
        ke[o : o + dim, :] = rows
        cols = np.zeros((nde, dim))
        for c in range(nde):
            for i in range(dim):
                for j in range(dim):
                    cols[c, i] += ke[c, o + j] * bas[j, i]
        ke[:, o : o + dim] = cols


@njit(cache=_CACHE, fastmath=_FM, error_model="numpy")
def _assemble_cable_2d(  # noqa: PLR0913
    y, n_el, n1, n2, gw, s0, k0, j0, ea, ei, rot_of_node, rot, f_out, ab_out, want_k
):
    """Planar cable assembly with the element loop written out (no per-element calls)."""
    ku = 7
    nq = gw.size
    e = np.empty(8)
    fe = np.empty(8)
    ke = np.zeros((8, 8)) if want_k else np.zeros((0, 0))
    g = np.empty(4)
    h = np.empty((4, 4))
    for el in range(n_el):
        base = el * 4
        for i in range(8):
            e[i] = y[base + i]
        rotated = rot_of_node[el] >= 0 or rot_of_node[el + 1] >= 0
        if rotated:
            _rotate_element(e, ke, fe, el, 2, 4, rot_of_node, rot, True)
        for i in range(8):
            fe[i] = 0.0
        if want_k:
            for i in range(8):
                for j in range(8):
                    ke[i, j] = 0.0
        for q in range(nq):
            p0, p1, p2, p3 = n1[el, q, 0], n1[el, q, 1], n1[el, q, 2], n1[el, q, 3]
            r0, r1, r2, r3 = n2[el, q, 0], n2[el, q, 1], n2[el, q, 2], n2[el, q, 3]
            a0 = p0 * e[0] + p1 * e[2] + p2 * e[4] + p3 * e[6]
            a1 = p0 * e[1] + p1 * e[3] + p2 * e[5] + p3 * e[7]
            b0 = r0 * e[0] + r1 * e[2] + r2 * e[4] + r3 * e[6]
            b1 = r0 * e[1] + r1 * e[3] + r2 * e[5] + r3 * e[7]
            _cable_qp_2d(a0, a1, b0, b1, s0[el, q], k0[el, q], j0[el, q], ea, ei, g, h, want_k)
            w = gw[q]
            pk = (p0, p1, p2, p3)
            rk = (r0, r1, r2, r3)
            for k in range(4):
                fe[2 * k] += w * (pk[k] * g[0] + rk[k] * g[2])
                fe[2 * k + 1] += w * (pk[k] * g[1] + rk[k] * g[3])
            if want_k:
                for k in range(4):
                    for l in range(k, 4):
                        c11 = w * pk[k] * pk[l]
                        c12 = w * pk[k] * rk[l]
                        c21 = w * rk[k] * pk[l]
                        c22 = w * rk[k] * rk[l]
                        for i in range(2):
                            for j in range(2):
                                ke[2 * k + i, 2 * l + j] += (
                                    c11 * h[i, j]
                                    + c12 * h[i, 2 + j]
                                    + c21 * h[2 + i, j]
                                    + c22 * h[2 + i, 2 + j]
                                )
        if want_k:
            for k in range(4):
                for l in range(k + 1, 4):
                    for i in range(2):
                        for j in range(2):
                            ke[2 * l + j, 2 * k + i] = ke[2 * k + i, 2 * l + j]
        if rotated:
            _rotate_element(e, ke, fe, el, 2, 4, rot_of_node, rot, False)
        for i in range(8):
            f_out[base + i] += fe[i]
        if want_k:
            for i in range(8):
                for j in range(8):
                    ab_out[ku + i - j, base + j] += ke[i, j]


@njit(cache=_CACHE, error_model="numpy")
def assemble(y, arrs, f_out, ab_out, want_k):
    """Internal force ``f_out (n,)`` and, if ``want_k``, tangent ``ab_out`` in model coordinates."""
    kind, dim, dpn, n_el, n1, n2, gw, s0, k0, j0, qr, l0, d0, ea, ei, rot_of_node, rot = arrs
    nde = 2 * dpn
    ku = nde - 1
    f_out[:] = 0.0
    if want_k:
        ab_out[:, :] = 0.0
    if kind == 0 and dim == 2:
        _assemble_cable_2d(
            y, n_el, n1, n2, gw, s0, k0, j0, ea, ei, rot_of_node, rot, f_out, ab_out, want_k
        )
        return
    e = np.empty(nde)
    fe = np.empty(nde)
    ke = np.zeros((nde, nde)) if want_k else np.zeros((0, 0))
    wa = np.empty(dim)
    wb = np.empty(dim)
    wg = np.empty(2 * dim)
    wh = np.empty((2 * dim, 2 * dim))
    for el in range(n_el):
        base = el * dpn
        for i in range(nde):
            e[i] = y[base + i]
        _rotate_element(e, ke, fe, el, dim, dpn, rot_of_node, rot, True)
        if kind == 0:
            _cable_element(
                e, el, n1, n2, gw, s0, k0, j0, qr, ea, ei, dim, fe, ke, want_k, wa, wb, wg, wh
            )
        else:
            _beam_element(e, l0[el], d0[el, 0], d0[el, 1], ea, ei, fe, ke, want_k)
        _rotate_element(e, ke, fe, el, dim, dpn, rot_of_node, rot, False)
        for i in range(nde):
            f_out[base + i] += fe[i]
        if want_k:
            for i in range(nde):
                for j in range(nde):
                    ab_out[ku + i - j, base + j] += ke[i, j]


@njit(cache=_CACHE, error_model="numpy")
def strain_energy(y, arrs):
    """Total strain energy of model coordinates ``y`` (``arrs``: the model arrays)."""
    kind, dim, dpn, n_el, n1, n2, gw, s0, k0, j0, qr, l0, d0, ea, ei, rot_of_node, rot = arrs
    nde = 2 * dpn
    e = np.empty(nde)
    dummy_f = np.empty(nde)
    dummy_k = np.zeros((0, 0))
    total = 0.0
    for el in range(n_el):
        for i in range(nde):
            e[i] = y[el * dpn + i]
        _rotate_element(e, dummy_k, dummy_f, el, dim, dpn, rot_of_node, rot, True)
        if kind == 0:
            total += _cable_energy(
                e, n1[el], n2[el], gw, s0[el], k0[el], j0[el], qr[el], ea, ei, dim
            )
        else:
            total += _beam_energy(e, l0[el], d0[el, 0], d0[el, 1], ea, ei)
    return total


@njit(cache=_CACHE, error_model="numpy")
def band_matvec(ab, x, ku, out):
    """``out = A x`` for a band-stored square matrix."""
    n = x.size
    for i in range(n):
        s = 0.0
        for j in range(max(0, i - ku), min(n, i + ku + 1)):
            s += ab[ku + i - j, j] * x[j]
        out[i] = s


@njit(cache=_CACHE, error_model="numpy")
def band_lu_factor(ab, ku, fixed):
    """In-place band LU without pivoting of ``A`` with fixed rows/columns set to the identity.

    The dynamic Jacobians are dominated by the mass term; returns False, leaving the caller to
    use a pivoting solver, if a pivot is tiny relative to the largest diagonal entry.
    """
    n = ab.shape[1]
    for i in range(n):
        if fixed[i]:
            for j in range(max(0, i - ku), min(n, i + ku + 1)):
                ab[ku + i - j, j] = 0.0
                ab[ku + j - i, i] = 0.0
            ab[ku, i] = 1.0
    scale = 0.0
    for i in range(n):
        scale = max(scale, abs(ab[ku, i]))
    for k in range(n):
        piv = ab[ku, k]
        if not abs(piv) > 1e-13 * scale:
            return False
        for i in range(k + 1, min(n, k + ku + 1)):
            lik = ab[ku + i - k, k] / piv
            ab[ku + i - k, k] = lik
            if lik == 0.0:
                continue
            for j in range(k + 1, min(n, k + ku + 1)):
                ab[ku + i - j, j] -= lik * ab[ku + k - j, j]
    return True


@njit(cache=_CACHE, error_model="numpy")
def band_lu_apply(lu, rhs, ku, fixed):
    """Solve in place with factors from :func:`band_lu_factor` (``rhs[fixed]`` set to zero)."""
    n = rhs.size
    for i in range(n):
        if fixed[i]:
            rhs[i] = 0.0
    for k in range(n):
        rk = rhs[k]
        if rk != 0.0:
            for i in range(k + 1, min(n, k + ku + 1)):
                rhs[i] -= lu[ku + i - k, k] * rk
    for k in range(n - 1, -1, -1):
        sm = rhs[k]
        for j in range(k + 1, min(n, k + ku + 1)):
            sm -= lu[ku + k - j, j] * rhs[j]
        rhs[k] = sm / lu[ku, k]


@njit(cache=_CACHE, error_model="numpy")
def band_lu_solve(ab, rhs, ku, fixed):
    """Factor ``ab`` in place and solve ``A x = rhs`` in place (``x[fixed] = 0``)."""
    if not band_lu_factor(ab, ku, fixed):
        return False
    band_lu_apply(ab, rhs, ku, fixed)
    return True


@njit(cache=_CACHE, error_model="numpy")
def newton_step(  # noqa: PLR0913
    y0, v0, a0, t, h, scheme, mass_band, f_grav, loads, arrs, fixed, y1, v1, a1, lu, lu_state
):
    """One generalized-α step (see :mod:`rancf.solvers.dynamic`); fills ``y1, v1, a1``.

    ``lu`` holds band LU factors of the Jacobian and ``lu_state[0]`` says whether they are
    valid for the present step size; ``lu_state[1]`` selects the Newton variant: 0 full Newton
    (exact tangent at every iteration), 1 modified Newton (factors reused across iterations and
    steps, refreshed from the exact tangent whenever the increments shrink by less than a factor
    4 per iteration or the step size changes).  ``lu_state[2]`` counts factorizations.

    Modified Newton may take up to three times ``max_iter`` iterations.

    Returns ``(status, iterations)``: status 1 converged, 0 not converged, -1 a tiny pivot (the
    caller repeats the step on the pivoting path).
    """
    am, af, gamma, beta, damping, tol, max_iter = scheme
    load_base, load_f0, load_freq = loads
    dim, dpn = arrs[1], arrs[2]
    n = y0.size
    ku = 2 * dpn - 1
    bh2 = beta * h * h
    modified = lu_state[1] == 1
    if modified:  # linear convergence: allow more iterations before giving up the step
        max_iter = 3 * max_iter
    base = y0 + h * v0 + h * h * (0.5 - beta) * a0
    tf = t + (1.0 - af) * h
    f_ext = f_grav.copy()
    for ld in range(load_base.size):
        fac = 1.0
        if load_freq[ld] > 0.0:
            fac = math.sin(2.0 * math.pi * load_freq[ld] * tf)
        for i in range(dim):
            f_ext[load_base[ld] + i] += load_f0[ld, i] * fac
    cm = (1.0 - am) / bh2 + damping * (1.0 - af) * gamma / (beta * h)
    y1[:] = y0 + h * v0 + 0.5 * h * h * a0
    yf = np.empty(n)
    fi = np.empty(n)
    kab = np.empty((2 * ku + 1, n)) if not modified else np.empty((0, 0))
    mv = np.empty(n)
    tmp = np.empty(n)
    prev = np.inf
    for it in range(1, max_iter + 1):
        for i in range(n):
            a1[i] = (y1[i] - base[i]) / bh2
            v1[i] = v0[i] + h * ((1.0 - gamma) * a0[i] + gamma * a1[i])
            yf[i] = (1.0 - af) * y1[i] + af * y0[i]
            tmp[i] = (1.0 - am) * a1[i] + am * a0[i] + damping * ((1.0 - af) * v1[i] + af * v0[i])
        fresh = (not modified) or lu_state[0] == 0
        target = lu if modified else kab
        assemble(yf, arrs, fi, target, fresh)
        band_matvec(mass_band, tmp, ku, mv)
        for i in range(n):
            tmp[i] = mv[i] + fi[i] - f_ext[i]
        if fresh:
            for r in range(2 * ku + 1):
                for c in range(n):
                    target[r, c] = cm * mass_band[r, c] + (1.0 - af) * target[r, c]
            lu_state[2] += 1
            if not band_lu_factor(target, ku, fixed):
                lu_state[0] = 0
                return -1, it
            lu_state[0] = 1
        band_lu_apply(target, tmp, ku, fixed)
        norm = 0.0
        for i in range(n):
            y1[i] -= tmp[i]
            norm = max(norm, abs(tmp[i]))
        if not math.isfinite(norm):
            lu_state[0] = 0
            return 0, it
        # with an exact (fresh) tangent convergence is quadratic and a small increment means a
        # small error; with reused factors the error is about |Δ| r / (1 - r), r = |Δ| / |Δ_prev|
        done = norm <= tol
        if done and not fresh:
            r = norm / prev
            done = r < 1.0 and norm * r / (1.0 - r) <= tol
        if done:
            for i in range(n):
                a1[i] = (y1[i] - base[i]) / bh2
                v1[i] = v0[i] + h * ((1.0 - gamma) * a0[i] + gamma * a1[i])
            return 1, it
        if modified and not fresh and norm > 0.25 * prev:
            lu_state[0] = 0  # slow contraction: refresh the tangent at the next iteration
        prev = norm
    lu_state[0] = 0
    return 0, max_iter


@njit(cache=_CACHE, error_model="numpy")
def run_steps(  # noqa: PLR0913
    y,
    v,
    a,
    t0,
    h,
    n_steps,
    out_every,
    scheme,
    mass_band,
    f_grav,
    y_ref,
    loads,
    arrs,
    fixed,
    out_y,
    out_v,
    out_e,
    lu,
    lu_state,
):
    """Up to ``n_steps`` fixed steps of size ``h`` from time ``t0``; ``y, v, a`` updated in place.

    Every ``out_every`` steps the state and the energies ``(kinetic, strain, gravity)`` are stored
    in the next rows of ``out_y, out_v, out_e``.  Returns ``(steps done, status of the last step,
    Newton iterations, outputs stored)``; a step that fails is not taken (status 0 or -1).
    """
    dpn = arrs[2]
    n = y.size
    ku = 2 * dpn - 1
    y1 = np.empty(n)
    v1 = np.empty(n)
    a1 = np.empty(n)
    mv = np.empty(n)
    iters = 0
    stored = 0
    for s in range(n_steps):
        t = t0 + s * h
        status, it = newton_step(
            y, v, a, t, h, scheme, mass_band, f_grav, loads, arrs, fixed, y1, v1, a1, lu, lu_state
        )
        iters += it
        if status != 1:
            return s, status, iters, stored
        y[:] = y1
        v[:] = v1
        a[:] = a1
        if (s + 1) % out_every == 0:
            out_y[stored] = y
            out_v[stored] = v
            band_matvec(mass_band, v, ku, mv)
            kin = 0.0
            grav = 0.0
            for i in range(n):
                kin += 0.5 * v[i] * mv[i]
                grav -= f_grav[i] * (y[i] - y_ref[i])
            out_e[stored, 0] = kin
            out_e[stored, 1] = strain_energy(y, arrs)
            out_e[stored, 2] = grav
            stored += 1
    return n_steps, 1, iters, stored
