"""Irregular seas: the components of a JONSWAP sea and of a measured elevation record."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.signal import welch

from rancf.errors import InputError
from rancf.system.irregular_waves import jonswap, jonswap_components, record_components

HS, TP = 6.0, 10.0


def test_the_spectrum_holds_hs():
    """``4 sqrt(m0) = Hs`` within 1 % (DNV's ``A_γ`` normalization is approximate)."""
    for gamma in (1.0, 3.3, 5.0):
        m0, _ = quad(lambda w, g=gamma: float(jonswap(w, HS, TP, g)), 0.05, 20.0, limit=400)
        assert 4.0 * math.sqrt(m0) == pytest.approx(HS, rel=1e-2)


def test_an_hour_of_sea_has_hs_and_tp():
    """One hour at 4 Hz: the elevation's standard deviation is Hs / 4 within 3 %, the peak of
    its spectrum (Welch, 2048 s segments) within 5 % of Tp."""
    sea = jonswap_components(HS, TP, 3.3, depth=200.0, components=200, seed=7)
    t = np.arange(0.0, 3600.0, 0.25)
    eta = sea.elevation(t)
    assert np.std(eta) == pytest.approx(HS / 4.0, rel=3e-2)
    f, p = welch(eta, fs=4.0, nperseg=8192)
    assert 1.0 / f[np.argmax(p)] == pytest.approx(TP, rel=5e-2)


def test_the_same_seed_gives_the_same_sea():
    a = jonswap_components(HS, TP, seed=3).elevation(np.arange(0.0, 100.0, 0.5))
    b = jonswap_components(HS, TP, seed=3).elevation(np.arange(0.0, 100.0, 0.5))
    c = jonswap_components(HS, TP, seed=4).elevation(np.arange(0.0, 100.0, 0.5))
    np.testing.assert_array_equal(a, b)
    assert np.max(np.abs(a - c)) > 0.1 * HS


def test_components_travel_with_the_dispersion_relation():
    """A component's crest at ``x`` arrives ``k x / ω`` later; deep water: ``k = ω² / g``."""
    sea = jonswap_components(HS, TP, depth=5000.0, components=5, seed=1, direction_deg=90.0)
    np.testing.assert_allclose(sea.k, sea.omega**2 / 9.80665, rtol=1e-9)
    t = np.linspace(0.0, 50.0, 11)
    one = jonswap_components(HS, TP, depth=5000.0, components=1, seed=1, direction_deg=90.0)
    shift = one.k[0] * 30.0 / one.omega[0]
    np.testing.assert_allclose(one.elevation(t + shift, (0.0, 30.0)), one.elevation(t), atol=1e-9)


def test_a_record_is_reproduced_at_the_origin():
    """A record (an irregular sea plus a mean level) sampled at 0.5 s, started at t = 12 s:
    reproduced at its times within 1e-3 Hs (to round-off)."""
    t = 12.0 + 0.5 * np.arange(1201)
    eta = jonswap_components(HS, TP, seed=2).elevation(t) + 0.3
    rec = record_components(t, eta, depth=100.0)
    assert np.max(np.abs(rec.elevation(t) - eta)) < 1e-3 * HS
    assert np.max(np.abs(rec.elevation(t) - eta)) < 1e-9 * HS


@pytest.mark.parametrize(
    "kwargs, match",
    [({"hs": -1.0}, "hs"), ({"gamma": 9.0}, "gamma"), ({"components": 0}, "components")],
)
def test_bad_sea_states_are_one_line(kwargs, match):
    args = {"hs": HS, "tp": TP, **kwargs}
    with pytest.raises(InputError, match=match) as e:
        jonswap_components(**args)
    assert "\n" not in str(e.value)


def test_an_uneven_record_is_refused():
    with pytest.raises(InputError, match="equal steps"):
        record_components([0.0, 1.0, 2.5, 3.0, 4.0], np.zeros(5), depth=10.0)
