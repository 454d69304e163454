"""The shell body with the shell element kernel: the Scordelis-Lo roof, linear, from its
scenario file (supports as constraint rows, the load vector, the position sensor)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spl

from rancf.bodies.shell_supports import constraint_rows
from rancf.kernels.shell import ShellKernel
from rancf.scenario import Scenario
from rancf.scenario.shell_build import shell_body, shell_load, shell_sensor_values

ROOF = Path(__file__).parents[1] / "scenario" / "data" / "scordelis_lo.toml"
#: The vertical displacement of the middle of the free edge (MacNeal & Harder 1985).
REFERENCE = 0.3006


def _deflection(n: int, membrane: str) -> float:
    raw = tomllib.loads(ROOF.read_text())
    raw["mesh"]["elements"] = [n, n]
    sc = Scenario.from_dict(raw, str(ROOF))
    body = shell_body(sc, 0)
    kernel = ShellKernel.from_mesh(
        body.mesh,
        body.thickness,
        body.youngs_modulus,
        body.poisson_ratio,
        body.density,
        membrane=membrane,
    )
    f = shell_load(sc, body)
    np.testing.assert_allclose(kernel.area_load([0.0, 0.0, -90.0]), f, atol=1e-12 * abs(f).max())
    c, _ = constraint_rows(body)
    a = sp.bmat([[kernel.tangent(body.q0), c.T], [c, None]], format="csc")
    x = spl.spsolve(a, np.concatenate([f, np.zeros(c.shape[0])]))
    u = x[: body.n_dofs]
    assert np.abs(c @ u).max() < 1e-8 * np.abs(u).max()  # the supports hold
    before = shell_sensor_values(sc, body, body.q0)["free_mid_z"]
    return before - shell_sensor_values(sc, body, body.q0 + u)["free_mid_z"]


@pytest.mark.parametrize("membrane", ["full", "projected"])
def test_scordelis_lo_roof_free_edge_deflection(membrane):
    w = _deflection(4, membrane)
    assert abs(w - REFERENCE) < 0.015 * REFERENCE, w
