"""Section values of cables and rods from their strains and curvatures, a stack of states in
one call of the core (``_core.section_forces``), against the formulas of
:mod:`rancf.bodies.section_outputs` evaluated here with NumPy:
``M_i = C_i (κ_i - κ_i⁰ / s) / λ`` and ``N = EA ε λ - Σ M_i κ_i`` (engineering strain:
``EA (λ - 1) - Σ M_i κ_i``), ``λ = sqrt(1 + 2 ε)``, ``s`` the length factor of each state."""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.bodies.flexible_core import section_stiffness
from rancf.bodies.section_outputs import SectionSampler
from rancf.mesh.factories import mesh_line
from rancf.scenario import load_scenario


def _body(name: str):
    if name == "engineering":
        mat = Material(density=3.0, youngs_modulus=1.0e3, axial_strain="engineering")
        return Model(mesh_line([0.0, 0.0], [1.0, 0.3], 6), "rancf", Section(1.0, 2.0e-3), mat)
    with resources.as_file(resources.files("rancf.examples") / f"{name}.toml") as p:
        return load_scenario(p).build_system().flex[0]


def _by_numpy(model, k0: np.ndarray, raw: np.ndarray, scale: np.ndarray) -> np.ndarray:
    st = section_stiffness(model)
    c = np.array([st.gj, st.ei2, st.ei3]) if model.element == "rod" else np.array([st.ei])
    eps, kappa = raw[..., 0], raw[..., 1:]
    lam = np.sqrt(1.0 + 2.0 * eps)
    moments = c * (kappa - k0 / scale[:, None, None]) / lam[..., None]
    conj = lam - 1.0 if st.engineering else eps * lam
    force = model.props.ea * conj - np.sum(moments * kappa, axis=-1)
    return np.concatenate([eps[..., None], force[..., None], kappa, moments], axis=-1)


# a curved cable (its moments relative to a stress-free curvature), rods in 3D, a cable with
# the engineering axial strain
@pytest.mark.parametrize("name", ["ring", "argyris-frame", "robot-cable", "engineering"])
def test_section_forces_of_a_stack_equal_the_formulas(name):
    model = _body(name)
    samp = SectionSampler(model, 3)
    rng = np.random.default_rng(2)
    ys = model.y0 + 2e-3 * rng.standard_normal((3, model.n))
    raw = samp.raw(ys)
    factors = np.array([1.0, 1.07, 0.95])
    got = samp.from_raw(raw, factors[:, None, None])
    scale = factors * getattr(getattr(model.kernel, "cable", model.kernel), "length_scale", 1.0)
    want = _by_numpy(model, samp._k0, raw, scale)
    assert got.shape == want.shape == (3, samp.n_points, 2 * raw.shape[-1])
    assert np.abs(want[..., 1]).max() > 0.0
    for j in range(want.shape[-1]):  # each column to 1e-12 of its size
        size = max(np.abs(want[..., j]).max(), 1e-300)
        assert np.abs(got[..., j] - want[..., j]).max() <= 1e-12 * size, j
    one = samp.from_raw(raw[1], 1.07)  # one state: the same numbers
    np.testing.assert_array_equal(one, got[1])
