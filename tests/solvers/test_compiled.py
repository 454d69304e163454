"""The compiled path gives the NumPy reference path's answers to round-off."""

import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from rancf.geometry.conic import conic_arc, conic_arc_through
from rancf.model.mesh import mesh_conic, mesh_line
from rancf.model.system import Material, Model, PointLoad, Section, Support
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.modal import natural_modes
from rancf.solvers.static import solve_static
from tests.conftest import EXAMPLE1, EXAMPLE2

SEC, MAT = Section.circular(0.02), Material(6000.0, 2e6)


def _models(kind):
    if kind == "rancf-2d":
        mesh, el = mesh_conic(conic_arc(*EXAMPLE1), 4, 0.3), "rancf"
    elif kind == "ancf-2d":
        mesh, el = mesh_conic(conic_arc(*EXAMPLE1), 4), "ancf"
    elif kind == "rancf-3d":
        chord, ang, pt = EXAMPLE2
        arc = conic_arc_through([0, 0, 0], [chord, 0, 0], ang, [pt[0], 0.0, pt[1]])
        mesh, el = mesh_conic(arc, 4), "rancf"
    elif kind == "line-3d":
        mesh, el = mesh_line([0, 0, 0], [0.5, 0.1, 0.0], 4), "rancf"
    else:
        mesh, el = mesh_conic(conic_arc(*EXAMPLE1), 4), "beam"
    dim = mesh.dim
    g = [0.0] * (dim - 1) + [-9.81]
    # in the plane of the curved spatial arc: out of it, statics has no equilibrium (the
    # magnitude curvature gives no linear out-of-plane stiffness, see test_static_modal)
    load = (0.05, 0.0, 0.05) if kind == "rancf-3d" else tuple([0.05] * dim)
    kw = dict(gravity=g, point_loads=[PointLoad(-1, load, 2.0)], damping=0.3)
    sup = [Support(0, "clamp")]
    return [Model(mesh, el, SEC, MAT, sup, backend=b, **kw) for b in ("numba", "numpy")]


KINDS = ["rancf-2d", "ancf-2d", "rancf-3d", "line-3d", "beam"]


@pytest.mark.parametrize("kind", KINDS)
def test_forces_tangent_energy_match(kind):
    fast, ref = _models(kind)
    rng = np.random.default_rng(5)
    y = fast.y0 + 0.02 * rng.normal(size=fast.n)
    f1, k1 = fast.internal_force_and_tangent(y)
    f2, k2 = ref.internal_force_and_tangent(y)
    assert np.abs(f1 - f2).max() <= 1e-12 * np.abs(f2).max()
    assert np.abs(k1 - k2).max() <= 1e-12 * np.abs(k2).max()
    assert np.abs(fast.internal_force(y) - f2).max() <= 1e-12 * np.abs(f2).max()
    assert fast.strain_energy(y) == pytest.approx(ref.strain_energy(y), rel=1e-12)


@pytest.mark.parametrize("kind", KINDS)
def test_dynamics_statics_modes_match(kind):
    fast, ref = _models(kind)
    opts = DynamicOptions(t_end=0.05, step=2e-3, rho_inf=0.8)
    r1, r2 = integrate(fast, opts), integrate(ref, opts)
    assert r1.n_newton == r2.n_newton
    assert np.abs(r1.q - r2.q).max() <= 1e-11 * np.abs(r2.q).max()
    assert np.allclose(r1.total_energy, r2.total_energy, rtol=1e-10, atol=1e-12)
    s1, s2 = solve_static(fast, 3), solve_static(ref, 3)
    assert np.abs(s1.q - s2.q).max() <= 1e-11 * np.abs(s2.q).max()
    m1, m2 = natural_modes(fast, count=3), natural_modes(ref, count=3)
    assert np.allclose(m1.frequencies_hz, m2.frequencies_hz, rtol=1e-10, atol=1e-9)


def test_modified_newton_gives_the_same_answer():
    m = Model(
        mesh_line([0, 0], [1.2, 0], 8),
        "ancf",
        Section(0.0018, 1.215e-8),
        Material(5540.0, 0.7e6),
        [Support(0, "pin")],
        gravity=[0, -9.81],
    )
    base = dict(t_end=0.3, step=1e-3, output_step=0.05)
    full = integrate(m, DynamicOptions(**base))
    mod = integrate(m, DynamicOptions(newton="modified", **base))
    assert mod.n_factorizations < 0.1 * full.n_factorizations
    assert mod.n_rejected == 0
    assert np.abs(mod.q - full.q).max() < 1e-8


def test_second_process_does_not_recompile(tmp_path):
    script = textwrap.dedent(
        """
        import json
        from rancf.model.mesh import mesh_line
        from rancf.model.system import Material, Model, Section, Support
        from rancf.solvers import compiled
        from rancf.solvers.dynamic import DynamicOptions, integrate
        m = Model(mesh_line([0, 0], [1, 0], 4), "ancf", Section(1e-3, 1e-8),
                  Material(5000.0, 1e7), [Support(0, "pin")], gravity=[0, -9.81])
        integrate(m, DynamicOptions(t_end=0.01, step=1e-3))
        fns = [compiled.run_steps, compiled.assemble]
        print(json.dumps({"misses": sum(sum(f.stats.cache_misses.values()) for f in fns),
                          "hits": sum(sum(f.stats.cache_hits.values()) for f in fns)}))
        """
    )
    f = tmp_path / "run.py"
    f.write_text(script)
    outs = []
    for _ in range(2):
        p = subprocess.run([sys.executable, str(f)], capture_output=True, text=True, check=True)
        outs.append(json.loads(p.stdout.strip().splitlines()[-1]))
    assert outs[1]["misses"] == 0
    assert outs[1]["hits"] >= 2
