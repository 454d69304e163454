"""Modes about a static equilibrium under point moments: the tangent includes the moments'
(non-symmetric) load stiffness and the general eigenproblem reports flutter and divergence."""

from __future__ import annotations

import json

import numpy as np
import pytest
import scipy.linalg

from rancf.bodies.flexible import Model
from rancf.bodies.properties import Material, PointLoad, Section, Support
from rancf.cli import main
from rancf.geometry.conic import conic_arc_through
from rancf.mesh.factories import mesh_conic, mesh_line
from rancf.solvers.dynamic import GeneralizedAlpha
from rancf.solvers.modal import natural_modes, tangent_stiffness
from rancf.solvers.static import solve_static
from tests.numbers import text_matches

SEC = Section.circular(0.03)
ROD = Material(6000.0, 2.0e7, poisson_ratio=0.3)
SAG = 0.5 * (1 - np.cos(np.pi / 6))  # the clamped arc of example 6.3's shape


def cantilever(moment, n: int = 8, geo: str = "straight") -> Model:
    """A rod clamped at its start with a point moment (and, curved, a force) at its tip."""
    if geo == "straight":
        mesh = mesh_line([0, 0, 0], [0.5, 0, 0], n)
        loads = [PointLoad(-1, moment=moment)]
    else:
        mesh = mesh_conic(conic_arc_through([0, 0, 0], [0.5, 0, 0], [30, 30], [0.25, SAG, 0]), n)
        loads = [PointLoad(-1, (0.0, 0.0, -1.0), moment=moment)]
    return Model(mesh, "rod", SEC, ROD, [Support(0, "clamp")], point_loads=loads)


def residual(model: Model, y: np.ndarray) -> np.ndarray:
    """Internal minus external force (moments included), loads at their amplitude."""
    return model.internal_force(y) - model.external_force(0.0, y, amplitude=True)


@pytest.mark.parametrize(
    ("geo", "moment"),
    [("straight", (3.0, -2.0, 20.0)), ("curved", (0.5, 0.3, 2.0)), ("curved", (2.0, -1.0, 0.0))],
)
def test_modes_tangent_is_the_derivative_of_the_full_residual(geo, moment):
    """At the static equilibrium the tangent of ``modes --about static`` equals the central
    difference (h = 1e-6) of the residual ``f_int - f_ext`` with the moments' configuration
    dependence.  Entries are compared relative to ``√(|K_ii K_jj|)`` (the axial terms are 1e6
    times the moment's): error <= 1e-7 (measured 4e-10 .. 2e-9), while the load stiffness is
    >= 1e-3 on that scale, so the former tangent without it fails; on the tip node's (r_x, φ)
    block the error is <= 1e-6 of the load stiffness (measured <= 3e-8)."""
    m = cantilever(moment, geo=geo)
    y = solve_static(m, 10).y
    assert np.abs(residual(m, y)[~m.fixed]).max() < 1e-8
    k, symmetric = tangent_stiffness(m, y)
    assert not symmetric
    h, n = 1e-6, m.n
    fd = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = h
        fd[:, j] = (residual(m, y + e) - residual(m, y - e)) / (2 * h)
    free = ~m.fixed
    d = np.sqrt(np.abs(np.diag(k)))[free]
    scale = np.outer(d, d)
    err = (np.abs(fd - k)[np.ix_(free, free)] / scale).max()
    assert err <= 1e-7
    load = (k - m.dense(m.internal_force_and_tangent(y)[1]))[np.ix_(free, free)]
    assert (np.abs(load) / scale).max() >= 1e-3
    tip = slice(n - 4, n)  # (the held coordinates are the first node's)
    assert np.abs(fd - k)[tip, tip].max() <= 1e-6 * np.abs(load).max()
    assert np.abs(k - k.T).max() >= 1e-3 * np.abs(load).max()  # K is not symmetric
    # the modes are those of this tangent (general eigenproblem on the free coordinates)
    free = ~m.fixed
    mass = m.dense(m.mass_matrix(y))[np.ix_(free, free)]
    lam = scipy.linalg.eigvals(k[np.ix_(free, free)], mass)
    lam = np.sort_complex(lam)
    res = natural_modes(m, y, count=6)
    assert not res.symmetric
    assert np.allclose(res.eigenvalues, lam[:6], rtol=1e-9)


def test_modes_without_moments_keep_the_symmetric_problem():
    """Only forces (no configuration-dependent load): the symmetric problem, whose eigenvalues
    are those of the model's own tangent to 1e-9 (the system's core assembles it)."""
    m = cantilever((0.0, 0.0, 0.0), geo="curved")
    y = solve_static(m, 10).y
    res = natural_modes(m, y, count=4)
    assert res.symmetric and np.all(res.growth_rates == 0.0)
    _, kb = m.internal_force_and_tangent(y)
    free = ~m.fixed
    k = m.dense(kb)[np.ix_(free, free)]
    lam = scipy.linalg.eigh(0.5 * (k + k.T), m.dense(m.mass_matrix(y))[np.ix_(free, free)])[0]
    assert np.allclose(res.eigenvalues, lam[:4], rtol=1e-9, atol=0)
    assert np.allclose(res.frequencies_hz, np.sqrt(lam[:4]) / (2 * np.pi), rtol=1e-9, atol=0)


def test_small_moments_tend_to_the_unloaded_modes():
    """Straight cantilever, 8 el.: as the tip moment M goes to zero the frequencies tend to the
    unloaded ones, the deviation second order: ``max |f - f0| / f0 = a M²`` with the same ``a``
    to 1 % over two decades (measured a = 1.14e-4 for an axial torque, 1.60e-3 for a transverse
    moment, per (N m)²).  An axial torque on a rod with equal bending stiffnesses splits each
    double bending frequency into a flutter pair for any torque (Ziegler's cantilever under an
    axial torque): the growth rate is first order, ``g = c M``, with the same ``c`` to 1e-4
    (measured 0.07336 1/s per N m); a transverse moment gives no growth."""
    f0 = natural_modes(cantilever((0.0, 0.0, 0.0))).frequencies_hz[:6]
    assert f0[0] == pytest.approx(f0[1], rel=1e-9)  # the double bending frequency
    for direction in ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.6, 0.8)):
        dev, rates = [], []
        for mag in (1e-2, 1e-1, 1.0):
            m = cantilever(tuple(mag * np.array(direction)))
            res = natural_modes(m, solve_static(m, 10).y, count=6)
            assert not res.symmetric
            dev.append(np.abs(res.frequencies_hz - f0).max() / f0[0] / mag**2)
            g = res.growth_rates
            if direction[0]:
                assert g[0] == pytest.approx(g[1], rel=1e-9) and g[0] > 0  # a flutter pair
                rates.append(g[0] / mag)
            else:
                assert np.all(g == 0.0)
        assert np.ptp(dev) <= 1e-2 * dev[0] and dev[0] <= 2e-3
        if rates:
            assert np.ptp(rates) <= 1e-4 * rates[0]
            assert rates[0] == pytest.approx(0.07336, rel=1e-3)


def _start_along(m: Model, y: np.ndarray, res, j: int, amp: float = 1e-5):
    """State on the linearized motion ``Re(φ e^{μt})`` of mode ``j``: ``(y, v, μ, φ)``."""
    free = ~m.fixed
    lam = complex(res.eigenvalues[j])
    mu = 1j * np.sqrt(lam)
    mu = -mu if mu.real < 0 else mu  # the growing root (or +iω)
    k, _ = tangent_stiffness(m, y)
    mass = m.dense(m.mass_matrix(y))[np.ix_(free, free)]
    w, v = scipy.linalg.eig(k[np.ix_(free, free)], mass)
    phi = v[:, np.argmin(np.abs(w - lam))]
    phi = amp * phi / np.abs(phi).max()
    y1, v1 = y.copy(), np.zeros(m.n)
    y1[free] += phi.real
    v1[free] = (mu * phi).real
    return y1, v1, mu, phi


def _run(m: Model, y: np.ndarray, v: np.ndarray, h: float, t_end: float) -> np.ndarray:
    """Trapezoidal rule (ρ∞ = 1, no numerical damping) from (y, v): the states ``(n_steps, n)``."""
    integ = GeneralizedAlpha(m, 1.0, 1e-12, 20)
    a = integ.initial_acceleration(y, v, 0.0)
    n = round(t_end / h)
    done, ok, _, _, oy, *_ = integ.run_steps(y.copy(), v.copy(), a, a.copy(), 0.0, h, n, 1)
    assert done == n and ok == 1
    return oy


def test_flutter_growth_rate_matches_the_dynamic_response():
    """A straight cantilever under an axial tip torque of 10 N m flutters: modes reports the
    lowest pair at 1.9375 Hz growing at 0.734 1/s.  The full nonlinear dynamics started on that
    mode (amplitude 1e-5 m, trapezoidal rule, h = 1 ms, 4 s) stays on it, and a fit of its
    complex amplitude gives the frequency and growth rate to 1e-4 (measured: 1.2e-5 and
    3.7e-5).  The elastic tangent alone (the former modes) has no growth and 1.9249 Hz."""
    m = cantilever((10.0, 0.0, 0.0))
    y = solve_static(m, 10).y
    res = natural_modes(m, y, count=2)
    assert res.frequencies_hz[0] == pytest.approx(1.9375, abs=1e-4)
    assert res.growth_rates[0] == pytest.approx(0.734, abs=1e-3)
    y1, v1, mu, phi = _start_along(m, y, res, 0)
    assert mu.real == pytest.approx(res.growth_rates[0], rel=1e-12)
    h = 1e-3
    oy = _run(m, y1, v1, h, 4.0)
    d = (oy - y)[:, ~m.fixed]
    basis = np.column_stack([phi.real, phi.imag])  # Re(z φ) = Re z Re φ - Im z Im φ
    c, *_ = np.linalg.lstsq(basis, d.T, rcond=None)
    assert np.linalg.norm(basis @ c - d.T) <= 1e-2 * np.linalg.norm(d)  # stays on the mode
    z = c[0] - 1j * c[1]
    t = h * np.arange(1, len(z) + 1)
    growth = np.polyfit(t, np.log(np.abs(z)), 1)[0]
    omega = np.polyfit(t, np.unwrap(np.angle(z)), 1)[0]
    assert growth == pytest.approx(mu.real, rel=1e-4)
    assert omega == pytest.approx(mu.imag, rel=1e-4)


def test_lowest_frequency_under_a_bending_moment_matches_the_dynamic_response():
    """A straight cantilever rolled by a tip moment M_z = 40 N m (about a quarter turn):
    modes gives 2.02440 Hz, all growth rates 0.  The nonlinear dynamics released from the
    equilibrium displaced 1e-5 m along that mode oscillates at the same frequency to 1e-4
    (zero crossings over 3 s, trapezoidal rule h = 1 ms; measured 1.4e-5).  Without the load
    stiffness the lowest eigenvalue is negative (a spurious divergence) and the next 1.923 Hz."""
    m = cantilever((0.0, 0.0, 40.0))
    y = solve_static(m, 20).y
    res = natural_modes(m, y, count=4)
    assert np.all(res.growth_rates == 0.0) and not res.symmetric
    f1 = res.frequencies_hz[0]
    assert f1 == pytest.approx(2.0244, abs=1e-4)
    y1, v1, mu, phi = _start_along(m, y, res, 0)
    assert np.all(phi.imag == 0.0) and np.all(v1 == 0.0)
    h = 1e-3
    d = (_run(m, y1, v1, h, 3.0) - y)[:, ~m.fixed]
    s = d @ phi.real
    t = h * np.arange(1, len(s) + 1)
    i = np.where(np.diff(np.sign(s)) != 0)[0]
    tz = t[i] - s[i] * h / (s[i + 1] - s[i])
    f_dyn = (len(tz) - 1) / (2 * (tz[-1] - tz[0]))
    assert f_dyn == pytest.approx(f1, rel=1e-4)
    elastic = m.dense(m.internal_force_and_tangent(y)[1])[np.ix_(~m.fixed, ~m.fixed)]
    old = scipy.linalg.eigh(elastic, m.dense(m.mass_matrix(y))[np.ix_(~m.fixed, ~m.fixed)])[0]
    assert old[0] < 0 and abs(np.sqrt(old[1]) / (2 * np.pi) / f1 - 1) > 0.04


def test_cli_modes_about_static_reports_growth_rates(tmp_path, capsys):
    """The CLI: the general problem is named, growth rates printed, in the JSON and plotted."""
    f = tmp_path / "torque.toml"
    f.write_text(
        '[geometry]\nkind = "line"\nstart = [0.0, 0.0, 0.0]\nend = [0.5, 0.0, 0.0]\n'
        '[mesh]\nelements = 8\nelement = "rod"\n[section]\nradius = 0.03\n'
        "[material]\ndensity = 6000.0\nyoungs_modulus = 2.0e7\npoisson_ratio = 0.3\n"
        '[[supports]]\nat = "start"\nkind = "clamp"\n'
        '[[loads.point]]\nat = "end"\nmoment = [10.0, 0.0, 0.0]\n'
    )
    assert main(["modes", str(f), "--about", "static", "--count", "2", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["eigenproblem"] == "general"
    assert d["growth_rates_per_s"][0] == pytest.approx(0.734, abs=1e-3)
    png = tmp_path / "modes.png"
    assert main(["modes", str(f), "--about", "static", "--count", "2", "--plot", str(png)]) == 0
    assert png.stat().st_size > 0  # mode shapes of a rod (its twist left out of the centreline)
    out = capsys.readouterr().out.splitlines()
    assert text_matches(out[1], "  mode  1      1.937528 Hz  growth rate 0.734094 1/s")
    assert "flutter" in out[-2] and out[-1] == f"mode shapes written to {png}"
    assert main(["modes", str(f), "--count", "2", "--json"]) == 0  # the reference: unloaded
    d = json.loads(capsys.readouterr().out)
    assert d["eigenproblem"] == "symmetric" and d["growth_rates_per_s"] == [0.0, 0.0]
