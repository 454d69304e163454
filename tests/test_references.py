"""The independent references of ``tests/references`` checked on their own (no rancf here).

Closed forms (the inextensible elastica, Irvine's catenary, Euler's buckling load), convergence in
the integration tolerance, the balance of the reactions with the weight, the hanging chain by a
finite-difference eigenproblem, and that the shooting's stress resultants are the derivatives of
rancf's energy (the first variation of the total potential vanishes at the solution).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.linalg import eigh_tridiagonal

from tests.references import catenary as cat
from tests.references import elastica as el

H = el.HOSE
AREA, INERTIA = np.pi * H["radius"] ** 2, np.pi * H["radius"] ** 4 / 4.0
EA, EI = H["youngs"] * AREA, H["youngs"] * INERTIA
WEIGHT = H["density"] * AREA * H["g"]


@pytest.fixture(scope="module")
def hose() -> el.Elastica:
    return el.installed_hose()


def test_stretch_inverts_the_law():
    rng = np.random.default_rng(1)
    for lam, kappa in zip(rng.uniform(0.7, 1.4, 20), rng.uniform(-30, 30, 20), strict=True):
        eps = 0.5 * (lam * lam - 1.0)
        axial, moment = EA * eps * lam - EI * kappa**2 / lam, EI * kappa / lam  # eqs. (1)-(2)
        assert el.stretch(axial, moment, EA, EI) == pytest.approx(lam, rel=1e-13)
        assert el.stretch(EA * eps * lam, EI * kappa, EA, EI, "simple") == pytest.approx(lam, 1e-13)


def test_closed_form_elastica_starts_at_euler_load():
    """Small k: the clamped-clamped Euler load 4 pi^2 EI / L^2 and a vanishing deflection."""
    c = el.clamped_elastica_inextensible(1.0, 1.0 - 1e-8, EI)
    assert c["force"] == pytest.approx(4.0 * np.pi**2 * EI, rel=1e-7)
    assert c["mid_deflection"] < 1e-3


def test_inextensible_weightless_limit_matches_the_elliptic_solution():
    """EA = 1e4 x the hose's (strain ~ 1e-7), no weight: the classical elastica."""
    e = el.clamped_elastica(1.0, 0.8, 1e4 * EA, EI, 0.0)
    c = el.clamped_elastica_inextensible(1.0, 0.8, EI)
    assert e.start_force[0] == pytest.approx(c["force"], rel=1e-5)  # pushes the rod along +x
    assert e.end_force[0] == pytest.approx(-c["force"], rel=1e-5)
    assert e.mid_sag == pytest.approx(c["mid_deflection"], rel=1e-5)  # buckled downward
    assert e.start_moment == pytest.approx(c["end_moment"], rel=1e-5)


def test_hose_tolerance_and_path_convergence(hose):
    coarse = el.installed_hose(tol=1e-9)
    other_path = el.installed_hose(sag_step=0.05)
    assert coarse.mid_sag == pytest.approx(hose.mid_sag, rel=1e-7)
    assert other_path.mid_sag == pytest.approx(hose.mid_sag, rel=1e-10)
    assert other_path.start_moment == pytest.approx(hose.start_moment, rel=1e-9)
    # downward, buckled (compressed) and symmetric
    assert 0.2 < hose.mid_sag < 0.4 and hose.start_force[0] > 0
    assert np.argmin(hose.y) == len(hose.y) // 2
    np.testing.assert_allclose(hose.y, hose.y[::-1], atol=1e-10)
    np.testing.assert_allclose(hose.x + hose.x[::-1], H["span"], atol=1e-10)


def test_hose_reactions_balance_the_weight(hose):
    """Forces and moments about the origin on the whole hose, to the integration tolerance."""
    w, length = WEIGHT, H["length"]
    end = hose.solution(length)
    np.testing.assert_allclose(end[:3], [H["span"], 0.0, 0.0], atol=1e-9)  # the far clamp
    total = hose.start_force + hose.end_force
    np.testing.assert_allclose(total, [0.0, w * length], rtol=1e-12, atol=1e-12)
    x_moment = quad(lambda s: hose.solution(s)[0], 0.0, length, epsabs=1e-13)[0]
    moments = (
        hose.start_moment
        + hose.end_moment
        + H["span"] * hose.end_force[1]  # r(L) x end force, r(L) = (span, 0)
        - w * x_moment  # weight (0, -w) at x(s)
    )
    assert abs(moments) < 1e-9 * w * length * H["span"]
    assert hose.start_moment == pytest.approx(-hose.end_moment, rel=1e-9)


def _potential_variation(e: el.Elastica, law: el.Law) -> tuple[float, float]:
    """d/d(eps) of the hose's total potential with the end force as multiplier, at ``e``:

    P = int W(lambda, theta'/lambda) ds0 + int w y ds0 - F_end . (r(L) - (span, 0)),

    varied by ``theta + eps phi`` (``phi = 0`` at both clamps) and ``lambda + eps psi``
    (complex step), with Gauss quadrature over the shooting's dense solution.
    Returns (the variation, the sum of the magnitudes of its three terms).
    """
    length, w = H["length"], WEIGHT
    xg, wg = np.polynomial.legendre.leggauss(40)
    edges = np.linspace(0.0, length, 9)
    s = np.concatenate(
        [0.5 * (b - a) * xg + 0.5 * (a + b) for a, b in zip(edges[:-1], edges[1:], strict=True)]
    )
    ws = np.concatenate([0.5 * (b - a) * wg for a, b in zip(edges[:-1], edges[1:], strict=True)])
    _, _, th, nx, ny, m = e.solution(s)
    axial = nx * np.cos(th) + ny * np.sin(th)
    lam = np.array([el.stretch(a, b, EA, EI, law) for a, b in zip(axial, m, strict=True)])
    th_s = m * lam**2 / EI if law == "energy" else m * lam / EI  # theta' = lambda kappa
    k = np.pi / length
    phi = np.sin(2 * k * s) + 0.3 * np.sin(3 * k * s)
    phi_s = 2 * k * np.cos(2 * k * s) + 0.9 * k * np.cos(3 * k * s)
    psi = 1e-3 * (np.cos(k * s) + 0.5)

    def terms(eps: complex) -> np.ndarray:
        la, t, t_s = lam + eps * psi, th + eps * phi, th_s + eps * phi_s
        strain, kappa = 0.5 * (la * la - 1.0), t_s / la
        elastic = np.sum(ws * 0.5 * (EA * strain**2 + EI * kappa**2))
        gravity = np.sum(ws * w * (length - s) * la * np.sin(t))  # int w y ds0
        end = [np.sum(ws * la * np.cos(t)) - H["span"], np.sum(ws * la * np.sin(t))]
        return np.array([elastic, gravity, -(e.end_force @ np.array(end))])

    h = 1e-30
    d = terms(1j * h).imag / h
    return float(np.sum(d)), float(np.sum(np.abs(d)))


def test_shooting_is_stationary_for_rancfs_energy(hose):
    """Eqs. (1)-(2) are the derivatives of rancf's energy: the first variation vanishes; the
    "simple" law (m = EI kappa, n.t = EA eps lambda) is not, and its variation does not."""
    variation, scale = _potential_variation(hose, "energy")
    assert abs(variation) < 1e-9 * scale
    simple = el.installed_hose(law="simple")
    variation_simple, _ = _potential_variation(simple, "simple")
    assert abs(variation_simple) > 1e-5 * scale
    # the two laws differ by about 0.1 % in the sag of the hose
    assert simple.mid_sag == pytest.approx(hose.mid_sag, rel=3e-3)
    assert simple.mid_sag != pytest.approx(hose.mid_sag, rel=1e-4)


def test_elastic_catenary_quadrature_matches_irvine_and_ssnl114():
    c = cat.SSNL114
    ea, w = c["youngs"] * c["area"], c["density"] * c["area"] * 9.81
    eng = cat.ssnl114("engineering")
    irvine = cat.irvine_catenary(c["span"], c["length"], ea, w)
    for key in ("horizontal", "end_tension", "mid_sag"):
        assert getattr(eng, key) == pytest.approx(irvine[key], rel=1e-10)
    # Irvine's SSNL114 values (engineering strain): 6.352 m, 13206 N, 13247 N
    assert irvine["mid_sag"] == pytest.approx(6.352, abs=5e-4)
    assert irvine["horizontal"] == pytest.approx(13206, abs=0.5)
    assert irvine["end_tension"] == pytest.approx(13247, abs=0.5)
    gl = cat.ssnl114()  # rancf's Green-Lagrange law: 6.3489 m, 13213 N, 13253 N
    assert gl.mid_sag == pytest.approx(6.3489, abs=5e-5)
    assert gl.horizontal == pytest.approx(13213, abs=0.5)
    assert gl.end_tension == pytest.approx(13253, abs=0.5)
    assert gl.x[-1] == pytest.approx(c["span"], rel=1e-12) and abs(gl.y[-1]) < 1e-9
    assert gl.y[len(gl.y) // 2] == pytest.approx(-gl.mid_sag, rel=1e-12)


def test_hanging_chain_frequencies_by_finite_differences():
    """(g s u')' + omega^2 u = 0 on s in [0, L] (s from the free end), u(L) = 0, finite
    differences on 4000 cells (second order), against the Bessel zeros."""
    length, g, n = 1.0, 9.81, 4000
    f = cat.chain_frequencies(length, g, 3)
    np.testing.assert_allclose(f, [0.5994, 1.3758, 2.1569], atol=5e-5)
    ds = length / n
    # nodes s_i = i ds, i = 0..n-1 (u_n = 0); node 0 has half a cell and no flux at s = 0
    faces = (np.arange(n) + 0.5) * ds  # s_{i+1/2}
    stiff_diag = g * (faces + np.concatenate([[0.0], faces[:-1]])) / ds
    stiff_off = -g * faces[:-1] / ds
    mass = ds * np.concatenate([[0.5], np.ones(n - 1)])
    diag = stiff_diag / mass
    off = stiff_off / np.sqrt(mass[:-1] * mass[1:])
    omega2 = eigh_tridiagonal(diag, off, select="i", select_range=(0, 2))[0]
    np.testing.assert_allclose(np.sqrt(omega2) / (2 * np.pi), f, rtol=1e-5)


def test_conjugate_points_of_a_straight_compressed_rod():
    """Clamped-clamped: the first conjugate point of a straight rod under the compression P is
    where it would buckle, s = 2 pi sqrt(EI/P) (times the stretch, here 1 - 3e-3)."""
    for force, expected in ((10.0, 2 * np.pi * np.sqrt(EI / 10.0)), (3.0, None)):
        rod = el._shape(np.array([-force, 0.0]), 1.0, EA, EI, 0.0, "energy", 1e-12, 11)
        found = el.conjugate_points(rod)
        if expected is None:  # below the Euler load 4 pi^2 EI / L^2 = 3.10 N: stable
            assert found.size == 0
        else:
            assert found[0] == pytest.approx(expected, rel=5e-3)


def test_hose_hangs_down_or_arches_up_and_both_are_stable(hose):
    up = el.installed_hose(branch="up")
    assert -0.3 < up.mid_sag < -0.2 and np.argmax(up.y) == len(up.y) // 2
    assert up.start_force[0] > hose.start_force[0] > 0  # the arch is more compressed
    assert up.start_force[1] == pytest.approx(hose.start_force[1], rel=1e-12)  # half the weight
    assert el.conjugate_points(hose).size == 0 and el.conjugate_points(up).size == 0
