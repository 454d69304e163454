"""Modes and the mapping factor K of the shell element, at the kernel level
(benchmarks/shell_studies.py; docs/derivations/shell.md sec. 3, 9): the simply supported
plate's frequencies against the Kirchhoff closed form, the constrained eigensolver against a
dense null-space solve, and one fixed K against Kopt (gradient scales, conditioning, accuracy)
on coarse meshes, with the tables of the derivation reproduced."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla

ROOT = Path(__file__).resolve().parents[2]
SPEC = importlib.util.spec_from_file_location(
    "shell_studies", ROOT / "benchmarks" / "shell_studies.py"
)
assert SPEC is not None and SPEC.loader is not None
STUDY = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(STUDY)
DOC = (ROOT / "docs" / "derivations" / "shell.md").read_text(encoding="utf-8")


def test_kirchhoff_closed_form_of_the_plate():
    """f11 = π/a² √(D/(ρ t)) = 47.986 Hz for 1 m, 10 mm steel."""
    assert STUDY.kirchhoff_frequency(1, 1) == pytest.approx(47.986, abs=5e-4)


def test_simply_supported_plate_first_frequency_within_one_percent():
    """f1 within 1 % of 47.986 Hz on 2 × 2 elements already, within 2e-4 on 4 × 4, and the
    error falls by more than 10 from 2 to 4 to 8; the modes (1, 2) and (2, 1) have equal
    frequencies (1e-8) within 0.3 % of the closed form on 4 × 4."""
    ref = STUDY.kirchhoff_frequency(1, 1)
    err = {n: STUDY.plate_frequencies(n, 3)[0] / ref - 1.0 for n in (2, 4, 8)}
    assert abs(err[2]) < 0.01 and abs(err[4]) < 2e-4, err
    assert abs(err[4]) * 10 < abs(err[2]) and abs(err[8]) * 10 < abs(err[4]), err
    f = STUDY.plate_frequencies(4, 3)
    assert f[1] == pytest.approx(f[2], rel=1e-8)
    assert f[1] == pytest.approx(STUDY.kirchhoff_frequency(1, 2), rel=3e-3)


def test_constrained_modes_match_a_dense_null_space_solve():
    """The shift-invert saddle-point eigensolver gives the eigenvalues of ``Zᵀ K Z`` over
    ``Zᵀ M Z`` (``Z`` the null space of the rows) to 1e-9, on the pinned plate of 3 × 3."""
    mesh = STUDY.mesh_surface(STUDY.cases.SQUARE, [3, 3])
    a, t, e, nu, rho = STUDY.PLATE
    pins = [STUDY.ShellSupport("pin", s) for s in STUDY.cases.EDGES]
    body = STUDY.ShellBody(mesh, t, e, nu, rho, supports=pins)
    kernel = STUDY.ShellKernel.from_mesh(mesh, t, e, nu, rho)
    k, m = kernel.tangent(mesh.q0), kernel.mass()
    c, _ = STUDY.constraint_rows(body)
    lam, modes = STUDY.constrained_modes(k, m, c, 5)
    z = sla.null_space(c.toarray())
    ref = sla.eigh(z.T @ k.toarray() @ z, z.T @ m.toarray() @ z, eigvals_only=True)[:5]
    assert np.allclose(lam, ref, rtol=1e-9, atol=0.0)
    assert np.abs(c @ modes).max() < 1e-10 * np.abs(modes).max()


def test_constrained_modes_refuse_an_unsupported_body():
    """Without supports the free plate's rigid motions have ω² = 0 to round-off: refused, not
    returned as frequencies."""
    mesh = STUDY.mesh_surface(STUDY.cases.SQUARE, [2, 2])
    a, t, e, nu, rho = STUDY.PLATE
    kernel = STUDY.ShellKernel.from_mesh(mesh, t, e, nu, rho)
    c = STUDY.sp.csr_matrix((0, kernel.n))
    with pytest.raises(RuntimeError, match="zero-energy mode"):
        STUDY.constrained_modes(kernel.tangent(mesh.q0), kernel.mass(), c, 3)


@pytest.mark.parametrize("k", [0.1, 0.3, 0.7, 0.9])
def test_a_fixed_k_spreads_the_gradient_scales_geometrically(k):
    """With one K on n equal circular elements the scales grow (or shrink) by ((1 − K)/K)^(2/3)
    per element (1e-9): the spread over the roof's 4 elements is that to the power 3."""
    row = STUDY.k_row("roof", 4, k)
    ratio = ((1.0 - k) / k) ** 2.0
    assert row["spread"] == pytest.approx(max(ratio, 1.0 / ratio), rel=1e-9)


def test_kopt_is_best_conditioned_and_most_accurate_on_the_roof():
    """On the roof with 4 × 4 elements, K = 1/2 (Kopt) gives the smallest condition numbers of
    M and of the supported K and the smallest error; each grows as K moves away from 1/2."""
    rows = {k: STUDY.k_row("roof", 4, k) for k in (0.1, 0.3, 0.5, 0.7, 0.9)}
    ref = -STUDY.cases.ROOF_REF
    err = {k: abs(r["w"] / ref - 1.0) for k, r in rows.items()}
    for key in ("cond_m", "cond_k"):
        assert rows[0.5][key] < rows[0.3][key] < rows[0.1][key], key
        assert rows[0.5][key] < rows[0.7][key] < rows[0.9][key], key
    assert err[0.5] < err[0.3] < err[0.1] and err[0.5] < err[0.7] < err[0.9], err


def test_the_ill_conditioning_of_a_fixed_k_is_the_gradient_scaling():
    """At K = 0.1 and 0.9 on the roof (4 × 4) the supported stiffness is more than 50 times
    worse conditioned than at Kopt, but scaled by its diagonal (Jacobi) it is within a factor 2
    of Kopt's: the spread of the nodal gradient scales, not the element, makes it ill
    conditioned.  The highest frequency grows by more than 1.4 (a smaller explicit step)."""
    rows = {k: STUDY.k_row("roof", 4, k) for k in (0.1, 0.5, 0.9)}
    for k in (0.1, 0.9):
        assert rows[k]["cond_k"] > 50.0 * rows[0.5]["cond_k"], k
        assert rows[k]["cond_kj"] < 2.0 * rows[0.5]["cond_kj"], k
        assert rows[k]["omega_max"] > 1.4 * rows[0.5]["omega_max"], k


def test_the_derivation_holds_the_modes_and_k_tables():
    section = DOC[DOC.index("## 9.") :]
    for line in STUDY.modes_table([2, 4, 8]).splitlines()[2:-1]:
        assert line in section, line
    for line in STUDY.k_table("roof", [4]).splitlines():
        assert line in section, line


def test_the_surface_mesher_warns_of_a_far_fixed_k(caplog):
    """One K = 0.01 on 8 circular elements spreads the nodal gradients by 2e9: the mesher logs
    the cable's warning; Kopt logs nothing."""
    geo = {"kind": "cylinder", "radius": 25.0, "length": 25.0, "angles_deg": [50.0, 90.0]}
    with caplog.at_level("WARNING", logger="rancf.mesh.surfaces"):
        STUDY.mesh_surface(geo, [8, 8])
        assert not caplog.records
        STUDY.mesh_surface(geo, [8, 8], k=0.01)
    assert "span a factor 2.06e+09 over 8 elements" in caplog.text
