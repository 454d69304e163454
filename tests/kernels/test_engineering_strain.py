"""The engineering axial strain of cable elements (``material.axial_strain = "engineering"``,
``W = ½ EA (λ − 1)²``; docs/derivations/cable.md §6): forces and tangents against finite
differences, objectivity, the exact tension of a uniform stretch, and the scenario key."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.bodies.section_outputs import SectionSampler
from rancf.cli import main
from rancf.errors import InputError
from rancf.mesh.factories import mesh_line
from rancf.post.results import load_results
from tests.kernels.test_elements import CASES, _fd_check, _mesh, _rotation

SEC = Section(area=1.0, inertia=2.0e-3)
ENG = Material(density=3.0, youngs_modulus=1.0e3, axial_strain="engineering")
EA = 1.0e3


def _model(mesh, material=ENG):
    return Model(mesh, "rancf", SEC, material)


@pytest.mark.parametrize(("dim", "geo", "k"), CASES)
def test_forces_and_tangent_against_finite_differences(dim, geo, k):
    model = _model(_mesh(dim, geo, k))
    rng = np.random.default_rng(11)
    _fd_check(model, model.y0 + 0.03 * rng.normal(size=model.n))  # stretched and compressed


@pytest.mark.parametrize(("dim", "geo", "k"), CASES)
def test_reference_and_its_rigid_motions_are_stress_free(dim, geo, k):
    model = _model(_mesh(dim, geo, k))
    assert np.abs(model.internal_force(model.y0)).max() <= 1e-10 * EA
    nodes = model.y0.reshape(model.n_nodes, 2, dim) @ _rotation(dim, 2.1).T
    nodes[:, 0] += np.arange(1, dim + 1) * 0.7
    assert np.abs(model.internal_force(nodes.ravel())).max() <= 1e-10 * EA


@pytest.mark.parametrize("dim", [2, 3])
def test_a_uniform_stretch_carries_ea_times_the_stretch_minus_one(dim):
    """A straight bar stretched uniformly to λ: tension EA (λ − 1) at every section, energy
    ½ EA (λ − 1)² L, and the end forces ±EA (λ − 1) (the Green–Lagrange law: EA ε λ)."""
    length, lam = 0.8, 1.25
    end = [length] + [0.0] * (dim - 1)
    models = {
        law: Model(
            mesh_line([0.0] * dim, end, 4), "rancf", SEC, Material(3.0, 1.0e3, axial_strain=law)
        )
        for law in ("engineering", "green_lagrange")
    }
    expected = {"engineering": EA * (lam - 1.0), "green_lagrange": EA * 0.5 * (lam**2 - 1) * lam}
    for law, model in models.items():
        y = model.y0.reshape(model.n_nodes, 2, dim).copy()
        y[:, 0, 0] *= lam  # positions stretched, gradients scaled
        y[:, 1, 0] *= lam
        y = y.ravel()
        sampler = SectionSampler(model, 4)
        names = ("strain", "axial_force")
        vals = sampler.values(y)[:, : len(names)]
        assert np.abs(vals[:, 1] / expected[law] - 1.0).max() <= 1e-12, law
        assert np.abs(vals[:, 0] / (0.5 * (lam**2 - 1)) - 1.0).max() <= 1e-12  # ε is G–L
        f = model.internal_force(y).reshape(model.n_nodes, 2, dim)
        assert f[-1, 0, 0] == pytest.approx(expected[law], rel=1e-12)
        assert f[0, 0, 0] == pytest.approx(-expected[law], rel=1e-12)
    energy = models["engineering"].strain_energy(
        (models["engineering"].y0.reshape(-1, 2, dim) * [[lam] + [1.0] * (dim - 1)]).ravel()
    )
    assert energy == pytest.approx(0.5 * EA * (lam - 1.0) ** 2 * length, rel=1e-12)


def test_other_elements_and_unknown_laws_are_refused():
    with pytest.raises(InputError, match="material.axial_strain"):
        Material(3.0, 1.0e3, axial_strain="hencky")
    mesh = mesh_line([0.0, 0.0], [1.0, 0.0], 2)
    with pytest.raises(InputError, match="material.axial_strain.*cable elements"):
        Model(mesh, "beam", SEC, ENG)


def test_scenario_key(tmp_path, capsys):
    """A bar pulled by P along its axis stretches by exactly P / EA (here 0.2) and carries P;
    with a beam element the key is refused in one line."""

    text = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [2.0, 0.0]
[mesh]
elements = 4
[section]
area = 1.0e-4
inertia = 1.0e-12
[material]
density = 1000.0
youngs_modulus = 1.0e9
axial_strain = "engineering"
[[supports]]
at = "start"
kind = "pin"
[[supports]]
at = "end"
kind = "roller"
axis = [1.0, 0.0]
[[loads.point]]
at = "end"
force = [2.0e4, 0.0]
[[sensors]]
name = "tip"
kind = "position"
at = "end"
"""
    f = tmp_path / "bar.toml"
    f.write_text(text)
    assert main(["static", str(f), "--out", str(tmp_path / "st")]) == 0
    body = load_results(tmp_path / "st" / "bodies" / "body" / "results.npz")
    tip = np.genfromtxt(tmp_path / "st" / "sensors.csv", delimiter=",", names=True)["tip_x"]
    assert tip[-1] == pytest.approx(2.4, rel=1e-9)
    assert body["along"][-1, :, 1] == pytest.approx(2.0e4, rel=1e-9)
    capsys.readouterr()
    beam = f.with_name("beam.toml")
    beam.write_text(text.replace("[mesh]\n", '[mesh]\nelement = "beam"\n'))
    assert main(["static", str(beam)]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "material.axial_strain" in err and "beam" in err
