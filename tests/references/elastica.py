"""The planar extensible elastica with rancf's cable law, solved independently of rancf.

**The law** (``docs/derivations/cable.md`` section 6): the strain energy per unit reference length
is

    W(lambda, kappa) = EA eps^2 / 2 + EI kappa^2 / 2,    eps = (lambda^2 - 1) / 2,

with ``lambda = |dr/ds0|`` the stretch (``s0`` the reference arc length, Green–Lagrange ``eps``)
and ``kappa = dtheta/ds`` the geometric curvature per *current* arc length (``theta`` the tangent
angle, so ``dtheta/ds0 = lambda kappa``).  With ``r' = lambda (cos theta, sin theta)`` the internal
virtual work ``int (n . delta r' + m delta theta') ds0 = delta int W ds0`` gives the stress
resultants as the derivatives of ``W(lambda, theta' / lambda)``:

    m   = dW/dtheta' = EI kappa / lambda                      (bending moment)       (1)
    n.t = dW/dlambda = EA eps lambda - EI kappa^2 / lambda    (axial force)          (2)

``law="simple"`` takes ``m = EI kappa`` and ``n.t = EA eps lambda`` instead (the law without the
terms that couple bending and stretch; it is *not* the derivative of ``W``, see
``tests/test_references.py``); it is kept to show how much those terms matter.

**Equilibrium** (``n`` the force of the part beyond ``s0`` on the part before it, ``m`` the
couple, ``f = (0, -w)`` the weight per reference length):

    n' = -f,    m' = -(r' x n)_z = -lambda (cos theta n_y - sin theta n_x),        (3)
    x' = lambda cos theta,  y' = lambda sin theta,  theta' = lambda kappa.          (4)

Given ``m`` and ``n.t``, (1)–(2) give ``kappa = m lambda / EI`` and the cubic
``EA/2 lambda^3 - (EA/2 + m^2/EI) lambda - n.t = 0`` for ``lambda`` (its largest root; Newton).

:func:`clamped_elastica` shoots (3)–(4) (DOP853, tight tolerances) with both ends clamped
horizontally at the same height (:func:`installed_hose`: the installed hose);
:func:`conjugate_points` tests its stability; :func:`clamped_elastica_inextensible` is the
classical closed form of the weightless inextensible clamped–clamped elastica (elliptic
integrals).  The cable without bending (catenary) is in :mod:`tests.references.catenary`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, root
from scipy.special import ellipe, ellipk

Law = Literal["energy", "simple"]


def stretch(axial: float, moment: float, ea: float, ei: float, law: Law = "energy") -> float:
    """The stretch ``lambda`` for an axial force ``n.t`` and bending moment ``m``, eqs. (1)-(2).

    The largest root of ``ea/2 lambda^3 - (ea/2 + c m^2/ei) lambda - axial = 0`` (``c = 1`` for
    ``law="energy"``, 0 for ``"simple"``): Newton from the linear estimate.
    """
    a = 0.5 * ea
    b = a + (moment * moment / ei if law == "energy" else 0.0)
    lam = 1.0 + axial / ea
    for _ in range(60):
        slope = 3.0 * a * lam * lam - b
        if slope <= 0.0:
            raise ValueError(f"axial force {axial} N beyond the material's compressive limit")
        step = (a * lam**3 - b * lam - axial) / slope
        lam -= step
        if abs(step) <= 1e-15 * lam:
            return lam
    raise RuntimeError("stretch: Newton did not converge")


def _rhs(ea: float, ei: float, w: float, law: Law) -> Callable[[float, np.ndarray], list[float]]:
    """Right-hand side of (3)-(4) for the state ``[x, y, theta, n_x, n_y, m]``."""

    def f(s: float, z: np.ndarray) -> list[float]:
        _, _, th, nx, ny, m = z
        c, sn = np.cos(th), np.sin(th)
        lam = stretch(nx * c + ny * sn, m, ea, ei, law)
        kappa = m * lam / ei if law == "energy" else m / ei
        return [lam * c, lam * sn, lam * kappa, 0.0, w, -lam * (c * ny - sn * nx)]

    return f


@dataclass(frozen=True)
class Elastica:
    """A solution of the clamped elastica, sampled at the reference arc lengths ``s``.

    ``force`` and ``moment`` are the internal force ``n`` and couple ``m`` (of the part beyond
    ``s`` on the part before); ``axial = n . t``; ``stretch = lambda``.  Reactions are the force
    and the couple each support exerts on the rod: ``-n(0)``, ``-m(0)`` at the start, ``n(L)``,
    ``m(L)`` at the end.  ``mid_sag`` is the depth of the midpoint below the ends (positive down).
    """

    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    axial: np.ndarray
    stretch: np.ndarray
    mid_sag: float
    start_force: np.ndarray
    start_moment: float
    end_force: np.ndarray
    end_moment: float
    #: the dense solution of (3)-(4) over [0, L]: ``solution(s) -> state``
    solution: Callable[[np.ndarray], np.ndarray]
    #: the problem: reference length, EA, EI, weight per reference length, law, tolerance
    problem: tuple[float, float, float, float, Law, float]


def _midpoint(
    u: np.ndarray, length: float, ea: float, ei: float, w: float, law: Law, tol: float
) -> np.ndarray:
    """The state ``[x, y, theta, n_x, n_y, m]`` at ``s0 = L/2`` from the start values
    ``u = [n_x(0), m(0)]`` at the clamp ``x = y = theta = 0``; NaN where the integration fails.

    ``n_y(0) = -w L / 2``: half the weight hangs on each support (symmetry).
    """
    z0 = [0.0, 0.0, 0.0, u[0], -0.5 * w * length, u[1]]
    try:
        sol = solve_ivp(
            _rhs(ea, ei, w, law), (0.0, 0.5 * length), z0, method="DOP853", rtol=tol, atol=tol
        )
    except (ValueError, RuntimeError):  # a trial far off: beyond the compressive limit
        return np.full(6, np.nan)
    return sol.y[:, -1] if sol.success else np.full(6, np.nan)


def _solve(
    residual: Callable[[np.ndarray], np.ndarray], guess: np.ndarray, tol: float
) -> np.ndarray | None:
    """A root of ``residual`` near ``guess`` (MINPACK hybrd); None where it fails."""
    res = root(residual, guess, method="hybr", options={"xtol": 1e-13})
    r = residual(res.x)
    if not np.all(np.isfinite(r)) or np.max(np.abs(r)) > 1e3 * tol:
        return None
    return res.x


def _follow(
    u: np.ndarray,
    residual: Callable[[float], Callable[[np.ndarray], np.ndarray]],
    tol: float,
    steps: int,
) -> np.ndarray:
    """Follow the root ``u`` of ``residual(0)`` to a root of ``residual(1)``.

    Secant predictor from the last two roots; a step that fails is halved.
    """
    tau, h, prev = 0.0, 1.0 / steps, None
    while tau < 1.0:
        h = min(h, 1.0 - tau)
        pred = u if prev is None else u + (u - prev[1]) * h / (tau - prev[0])
        new = _solve(residual(tau + h), pred, tol)
        if new is None:
            h *= 0.5
            if h < 1e-8:
                raise RuntimeError(f"continuation stalled at tau = {tau}")
            continue
        prev, u, tau = (tau, u), new, tau + h
    return u


def clamped_elastica(
    length: float,
    span: float,
    ea: float,
    ei: float,
    weight: float,
    *,
    law: Law = "energy",
    tol: float = 1e-12,
    points: int = 401,
    sag_step: float = 0.02,
    branch: Literal["down", "up"] = "down",
) -> Elastica:
    """The rod of reference ``length`` under its ``weight`` [N/m of reference length], both ends
    clamped horizontally at height 0, ``x = 0`` and ``x = span`` (``span <= length``).

    **Shooting.** Symmetric: from the clamp ``x = y = theta = 0`` with ``n_y(0) = -wL/2`` and the
    unknowns ``n_x(0)``, ``m(0)`` to ``s0 = L/2``, where ``theta = 0`` and ``x = span/2``;
    this excludes the antisymmetric modes.  ``tol``: relative and absolute tolerance of the
    integration (DOP853).

    **Which solution: the downward-sagging first mode reached by installing the rod.** The rod
    is first solved with its midpoint at the linear clamped beam's sag ``w L^4 / (384 EI)``
    (from that beam's end moment ``-wL^2/12``; the span is then an output, near ``L``), then
    the midpoint is lowered in steps of ``sag_step * L`` until the span is passed (raised, if
    the span must grow), and finally the span is set from the two solutions that bracket it.
    The sag is the continuation parameter because pushing the ends together directly jumps to
    the almost straight, strongly compressed branch.  Along this path the sag grows from the
    beam's to the buckled rod's, downward, without a bifurcation.  ``weight = 0``: the path is
    followed with the weight ``10 EI/L^3``, which is then taken to zero at the final span (the
    downward-buckled weightless elastica).

    ``branch="up"``: the arch, the other symmetric first-mode equilibrium: the weightless
    solution mirrored (``y -> -y``), then the weight raised from 0 (a RuntimeError if the arch
    stops existing on the way: it snaps through).  For the installed hose both
    exist and neither has a conjugate point (:func:`conjugate_points`): both are stable, so
    which one a solver finds depends on its load path.
    """
    if not 0.0 < span <= length:
        raise ValueError(f"span {span} must be in (0, length = {length}]")
    if branch == "up":
        flat = clamped_elastica(length, span, ea, ei, 0.0, law=law, tol=tol, sag_step=sag_step)
        u = np.array([-flat.start_force[0], flat.start_moment])  # mirrored: m(0) -> -m(0)
        arch = lambda tau: (  # noqa: E731
            lambda v: (lambda z: np.array([z[0] - 0.5 * span, z[2]]))(
                _midpoint(v, length, ea, ei, tau * weight, law, tol)
            )
        )
        try:
            u = _follow(u, arch, tol, 10)
        except RuntimeError as err:
            raise RuntimeError(f"no arch (branch 'up') under this weight: {err}") from None
        return _shape(u, length, ea, ei, weight, law, tol, points)
    w1 = weight if weight > 0.0 else 10.0 * ei / length**3

    def mid(u: np.ndarray, w: float) -> np.ndarray:
        return _midpoint(u, length, ea, ei, w, law, tol)

    def at_span(d: float, w: float) -> Callable[[np.ndarray], np.ndarray]:
        return lambda u: (lambda z: np.array([z[0] - 0.5 * d, z[2]]))(mid(u, w))

    def at_sag(sag: float) -> Callable[[np.ndarray], np.ndarray]:
        return lambda u: (lambda z: np.array([z[1] + sag, z[2]]))(mid(u, w1))

    sag = w1 * length**4 / (384.0 * ei)  # the clamped beam's, with its end moment -wL^2/12
    u = _solve(at_sag(sag), np.array([0.0, -w1 * length**2 / 12.0]), tol)
    if u is None:
        raise RuntimeError(f"no solution at the beam's sag {sag} m")
    d = 2.0 * mid(u, w1)[0]
    down = d > span  # lower the midpoint to bring the ends together, raise it to pull them apart
    path = [(d, u)]
    while (d > span) == down:
        sag += sag_step * length if down else -min(sag_step * length, 0.5 * sag)
        nxt = _solve(at_sag(sag), u, tol)
        if nxt is None:
            raise RuntimeError(f"no solution at the sag {sag} m")
        u, d = nxt, 2.0 * mid(nxt, w1)[0]
        path.append((d, u))
    (d0, u0), (d1, u1) = path[-2], path[-1]
    guess = u0 + (u1 - u0) * (span - d0) / (d1 - d0) if d1 != d0 else u1
    u = _solve(at_span(span, w1), guess, tol)
    if u is None:
        raise RuntimeError("no solution at the span")
    if w1 != weight:
        u = _follow(u, lambda tau: at_span(span, w1 + tau * (weight - w1)), tol, 10)
    return _shape(u, length, ea, ei, weight, law, tol, points)


def _shape(
    u: np.ndarray,
    length: float,
    ea: float,
    ei: float,
    weight: float,
    law: Law,
    tol: float,
    points: int,
) -> Elastica:
    """The :class:`Elastica` integrated over the whole rod from ``u = [n_x(0), m(0)]``."""
    z0 = [0.0, 0.0, 0.0, u[0], -0.5 * weight * length, u[1]]
    full = solve_ivp(
        _rhs(ea, ei, weight, law),
        (0.0, length),
        z0,
        method="DOP853",
        rtol=tol,
        atol=tol,
        dense_output=True,
    )
    s = np.linspace(0.0, length, points)
    x, y, th, nx, ny, m = full.sol(s)
    axial = nx * np.cos(th) + ny * np.sin(th)
    lam = np.array([stretch(a, b, ea, ei, law) for a, b in zip(axial, m, strict=True)])
    end = full.y[:, -1]
    return Elastica(
        s=s,
        x=x,
        y=y,
        theta=th,
        force=np.column_stack([nx, ny]),
        moment=m,
        axial=axial,
        stretch=lam,
        mid_sag=float(-full.sol(0.5 * length)[1]),
        start_force=-np.array([u[0], z0[4]]),
        start_moment=float(-u[1]),
        end_force=np.array(end[3:5]),
        end_moment=float(end[5]),
        solution=full.sol,
        problem=(length, ea, ei, weight, law, tol),
    )


def conjugate_points(e: Elastica, samples: int = 2000, delta: float = 1e-6) -> np.ndarray:
    """Arc lengths in (0, L) where ``det d(x, y, theta)(s) / d(n_x, n_y, m)(0)`` changes sign.

    Jacobi's test for the rod clamped at both ends under dead loads (Manning, Rogers & Maddocks,
    Proc. R. Soc. A 454, 1998): an equilibrium without conjugate points is stable, one with a
    conjugate point is not.  The Jacobian comes from three integrations with the start values
    perturbed by ``delta`` (relative); ``samples`` points in (0, L].  Meant for compressed rods
    (in strong tension the determinant grows exponentially and the differences lose it).
    """
    length, ea, ei, weight, law, tol = e.problem
    s = np.linspace(length / samples, length, samples)
    z0 = np.array(e.solution(0.0))

    def shoot(z: np.ndarray) -> np.ndarray:
        sol = solve_ivp(
            _rhs(ea, ei, weight, law),
            (0.0, length),
            z,
            method="DOP853",
            rtol=tol,
            atol=tol,
            dense_output=True,
        )
        return sol.sol(s)[:3]

    base = shoot(z0)
    columns = []
    for k in (3, 4, 5):
        z = z0.copy()
        step = delta * max(1.0, abs(z[k]))
        z[k] += step
        columns.append((shoot(z) - base) / step)
    det = np.linalg.det(np.moveaxis(np.stack(columns, axis=1), -1, 0))
    return s[:-1][np.diff(np.sign(det)) != 0]


def clamped_elastica_inextensible(length: float, span: float, ei: float) -> dict[str, float]:
    """The weightless inextensible elastica clamped horizontally at both ends, first mode.

    Four quarter waves of the Euler elastica of wave number ``omega = sqrt(P/EI)``, each
    ``K(k)/omega = L/4`` long, ``k = sin(alpha/2)`` (``alpha`` the slope at the inflection
    points): ``span/L = 2 E(k)/K(k) - 1``, ``P = 16 K(k)^2 EI / L^2``, midpoint deflection
    ``4k/omega = k L / K(k)``, clamp moment ``2 k omega EI``.  Returns ``force`` (the compressive
    end force P), ``mid_deflection``, ``end_moment`` and ``k``.
    """
    ratio = span / length

    def f(k: float) -> float:
        return 2.0 * ellipe(k * k) / ellipk(k * k) - 1.0 - ratio

    k = brentq(f, 1e-12, 1.0 - 1e-15, xtol=1e-15)
    kk = ellipk(k * k)
    omega = 4.0 * kk / length
    return {
        "force": float(omega * omega * ei),
        "mid_deflection": float(k * length / kk),
        "end_moment": float(2.0 * k * omega * ei),
        "k": float(k),
    }


#: The installed hose: length [m], span [m], radius [m], E [Pa], rho [kg/m^3], g [m/s^2].
HOSE = {"length": 1.0, "span": 0.8, "radius": 0.01, "youngs": 1e7, "density": 1200.0, "g": 9.81}


def installed_hose(law: Law = "energy", **options: float) -> Elastica:
    """The installed hose: 1 m, radius 0.01 m, E = 1e7 Pa, rho = 1200 kg/m^3, under gravity, both
    ends clamped horizontally at the same height 0.8 m apart (:func:`clamped_elastica`)."""
    h = HOSE
    area, inertia = np.pi * h["radius"] ** 2, np.pi * h["radius"] ** 4 / 4.0
    weight = h["density"] * area * h["g"]
    ea, ei = h["youngs"] * area, h["youngs"] * inertia
    return clamped_elastica(h["length"], h["span"], ea, ei, weight, law=law, **options)
