"""Free vibration of a clamped-free steel cable with Kelvin-Voigt strain-rate damping
(docs/derivations/strain-rate-damping.md §4): started with the velocity of one natural mode and
integrated without numerical damping (``rho_inf = 1``), the mode decays with the damping ratio
``ζ = c_a ω / (2 EA)`` (the first axial mode, ``[damping] axial``) or ``ζ = c_b ω / (2 EI)``
(the first bending mode, ``[damping] bending``), ``ω`` the run's own frequency; the logarithmic
decrement of the tip's peaks gives ``ζ``."""

from __future__ import annotations

import numpy as np
import pytest

import rancf
from rancf.bodies.properties import StrainRateDamping

L, N_EL = 1.0, 8
SECTION = rancf.Section.circular(0.01)  # 10 mm steel bar
STEEL = rancf.Material(density=7850.0, youngs_modulus=2.1e11)
ZETA = 0.02  # the damping ratio the coefficient is chosen for (at the modal frequency)


def _model(kv: StrainRateDamping | None = None) -> rancf.Model:
    return rancf.Model(rancf.mesh_line([0.0, 0.0], [L, 0.0], N_EL), "ancf", SECTION, STEEL,
                       supports=[rancf.Support(0, "clamp")], strain_rate_damping=kv)  # fmt: skip


def _first_mode(model: rancf.Model, comp: int) -> tuple[float, np.ndarray]:
    """The lowest mode whose tip moves along ``comp`` (0: axially, 1: transversely)."""
    modes = rancf.natural_modes(model)
    tip = (model.n_nodes - 1) * model.dpn + comp
    for f, phi in zip(modes.frequencies_hz, modes.modes, strict=True):
        if abs(phi[tip]) > 0.5 * np.abs(phi[tip - comp : tip - comp + 2]).max():
            return 2.0 * np.pi * f, phi
    raise AssertionError("no such mode")


def _decay(signal: np.ndarray, t: np.ndarray) -> tuple[float, float, int]:
    """Damping ratio and frequency of a decaying oscillation from its peaks (of |signal|,
    parabola-interpolated): ``ln |peak|`` fitted linearly in time gives ``σ = ζ ω``, the peaks'
    spacing ``π / ω_d``; ``ω = √(σ² + ω_d²)``."""
    s = np.abs(signal)
    i = np.flatnonzero((s[1:-1] >= s[:-2]) & (s[1:-1] > s[2:])) + 1
    a, b, c = s[i - 1], s[i], s[i + 1]
    d = 0.5 * (a - c) / (a - 2.0 * b + c)
    tp, peak = t[i] + d * (t[1] - t[0]), b - 0.25 * (a - c) * d
    sigma = -np.polyfit(tp, np.log(peak), 1)[0]
    omega = np.hypot(sigma, np.pi / np.mean(np.diff(tp)))
    return sigma / omega, omega, tp.size


def _run(kv: StrainRateDamping | None, comp: int, per_period: int) -> tuple[float, float, int]:
    """ζ, ω and the number of peaks of 8 periods of the first axial (comp 0) or bending (1)
    mode, started with a velocity in its shape (tip speed 1 mm/s)."""
    model = _model(kv)
    omega, phi = _first_mode(model, comp)
    tip = (model.n_nodes - 1) * model.dpn + comp
    model.v0 = 1e-3 * phi / phi[tip]
    step = 2.0 * np.pi / omega / per_period
    res = rancf.integrate(model, rancf.DynamicOptions(
        t_end=8 * per_period * step, step=step, output_step=step, rho_inf=1.0))  # fmt: skip
    assert res.status.value == "completed"
    return _decay(res.q[:, tip] - model.y0[tip], res.t)


@pytest.mark.parametrize(("key", "comp", "per_period"), [("axial", 0, 100), ("bending", 1, 200)])
def test_first_mode_decays_with_the_closed_form_damping_ratio(key, comp, per_period):
    bare = _model()
    stiffness = bare.props.ea if key == "axial" else bare.props.ei
    omega0, _ = _first_mode(bare, comp)
    c = 2.0 * ZETA * stiffness / omega0  # N s (axial) or N m^2 s (bending)
    zeta, omega, peaks = _run(StrainRateDamping(**{key: c}), comp, per_period)
    assert peaks >= 14
    closed_form = c * omega / (2.0 * stiffness)
    assert abs(zeta / closed_form - 1.0) < 0.05, (zeta, closed_form)
    undamped, _, _ = _run(None, comp, per_period)  # the scheme and the fit add no damping
    assert abs(undamped) < 0.02 * closed_form, undamped
