"""Modes and the mapping factor K of the RANCF shell element, at the kernel level.

* The first frequencies of a simply supported square plate (1 m, 10 mm steel: E 2e11, ν 0.3,
  ρ 7850), the generalized eigenproblem ``K φ = ω² M φ`` of the kernel's stiffness and mass with
  the supports' rows ``C φ = 0`` (docs/derivations/shell.md sec. 9), against the Kirchhoff
  closed form ``f_mn = π/2 (m² + n²)/a² √(D/(ρ t))`` (``f_11`` = 47.986 Hz).
* The mapping factor K of the circular directions (sec. 3, eq. 3.7): one fixed K on every
  element of the Scordelis–Lo roof and the pinched hemisphere of benchmarks/shell_locking.py,
  from K = 0.01 to 0.99, against Kopt = 1/2: the spread of the nodal gradient scales, the
  condition numbers of ``M`` and of the supported ``K`` (on the null space of ``C``), also
  scaled by its diagonal, the highest frequency, and the displacement.

Prints the Markdown tables of docs/derivations/shell.md sec. 9; the cases are also the tests'
(tests/kernels/test_shell_studies.py), on coarse meshes.

    python benchmarks/shell_studies.py [--modes 2 4 8 16] [--kstudy 4 8]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray
from threadpoolctl import threadpool_limits

from rancf.bodies.shell import ShellBody, ShellSupport
from rancf.bodies.shell_supports import constraint_rows
from rancf.kernels.shell import ShellKernel
from rancf.mesh.surface_kinds import mesh_surface

sys.path.insert(0, str(Path(__file__).resolve().parent))
import shell_locking as cases  # noqa: E402

#: The plate: side, thickness, E, ν, ρ.
PLATE = (1.0, 0.01, 2e11, 0.3, 7850.0)
#: ``ω²`` below this fraction of ``max|K| / max|M|`` is a zero-energy mode (round-off leaves
#: the rigid modes of a free 2 × 2 plate at 1e-16 of it; its first pinned mode is at 2e-4).
ZERO_RTOL = 1e-10
#: The mapping factors of the K study (Kopt = 1/2 for every circular element, eq. 3.7).
K_VALUES = (0.01, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99)


def kirchhoff_frequency(m: int, n: int) -> float:
    """``f_mn = π/2 (m² + n²)/a² √(D/(ρ t))`` [Hz] of the simply supported square plate
    :data:`PLATE`, ``D = E t³ / (12 (1 − ν²))``."""
    a, t, e, nu, rho = PLATE
    d = e * t**3 / (12.0 * (1.0 - nu**2))
    return 0.5 * np.pi * (m * m + n * n) / a**2 * np.sqrt(d / (rho * t))


def constrained_modes(
    k: sp.spmatrix, m: sp.spmatrix, c: sp.spmatrix, count: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ``count`` lowest ``ω²`` of ``K φ = ω² M φ`` with ``C φ = 0`` and their modes
    ``(n, count)``: shift-invert Lanczos (ARPACK, σ = 0) on the saddle-point pencil
    ``([K, Cᵀ], [C, 0])``, ``([M, 0], [0, 0])`` with the rows scaled as in
    :func:`shell_locking.saddle_solve` (the multipliers' infinite eigenvalues map to 0 and are
    not found).  Raises ``RuntimeError`` if an ``ω²`` is below :data:`ZERO_RTOL` of
    ``max|K| / max|M|`` (a rigid or mechanism mode the supports leave free) or a mode breaks
    the rows by more than 1e-8 of its size."""
    n, nc = k.shape[0], c.shape[0]
    cs = c * float(abs(k).max())
    a = sp.bmat([[k, cs.T], [cs, None]], format="csc")
    b = sp.bmat([[m, None], [None, sp.csc_matrix((nc, nc))]], format="csc")
    lam, vec = spla.eigsh(a, k=count, M=b, sigma=0.0, which="LM")
    order = np.argsort(lam)
    lam, modes = lam[order], vec[:n, order]
    zero = ZERO_RTOL * float(abs(k).max()) / float(abs(m).max())
    if not np.all(lam > zero):
        raise RuntimeError(
            f"the supports leave a zero-energy mode (ω² = {lam.min():.3e}, below {zero:.1e})"
        )
    broken = np.abs(c @ modes).max(axis=0) / np.abs(modes).max(axis=0)
    if broken.max() > 1e-8:
        raise RuntimeError(f"a mode breaks the supports by {broken.max():.2e} of its size")
    return lam, modes


def plate_frequencies(n: int, count: int = 6, membrane: str = "projected") -> NDArray:
    """The ``count`` lowest frequencies [Hz] of :data:`PLATE` on ``n × n`` elements, pinned
    on its four edges (docs/derivations/shell.md sec. 7)."""
    a, t, e, nu, rho = PLATE
    mesh = mesh_surface({**cases.SQUARE, "size": [a, a]}, [n, n])
    body = ShellBody(mesh, t, e, nu, rho, supports=[ShellSupport("pin", s) for s in cases.EDGES])
    kernel = ShellKernel.from_mesh(mesh, t, e, nu, rho, membrane=membrane)
    c, _ = constraint_rows(body)
    lam, _ = constrained_modes(kernel.tangent(mesh.q0), kernel.mass(), c, count)
    return np.sqrt(lam) / (2.0 * np.pi)


#: The plate's first six Kirchhoff modes ``(m, n)`` (the second and third, fifth and sixth
#: are pairs of equal frequency).
PLATE_MODES = ((1, 1), (1, 2), (2, 1), (2, 2), (1, 3), (3, 1))


def modes_table(sizes: list[int]) -> str:
    """Markdown: the first six frequencies on each mesh, the Kirchhoff values and f1's error."""
    ref = [kirchhoff_frequency(m, n) for m, n in PLATE_MODES]
    head = " | ".join(f"f{i + 1} ({m},{n})" for i, (m, n) in enumerate(PLATE_MODES))
    out = [f"| n × n | {head} | f1 error |", "| ---: |" + " ---: |" * (len(ref) + 1)]
    for n in sizes:
        f = plate_frequencies(n)
        cells = " | ".join(f"{x:.3f}" for x in f)
        out.append(f"| {n} | {cells} | {f[0] / ref[0] - 1.0:+.2e} |")
    out.append("| Kirchhoff | " + " | ".join(f"{x:.3f}" for x in ref) + " | |")
    return "\n".join(out)


def _roof(n: int, k: float | str) -> tuple[ShellBody, ShellKernel, NDArray, float]:
    body = cases.roof_body(n, k)
    kernel = cases.kernel_of(body, "projected")
    return body, kernel, kernel.area_load([0.0, 0.0, -90.0]), -cases.ROOF_REF


def _hemisphere(n: int, k: float | str) -> tuple[ShellBody, ShellKernel, NDArray, float]:
    body = cases.hemisphere_body(n, k)
    kernel = cases.kernel_of(body, "projected")
    return body, kernel, cases.hemisphere_load(body), cases.HEMISPHERE_REF


#: ``case: (n, K) -> (body, kernel, load, reference)``: the roof and the hemisphere of
#: benchmarks/shell_locking.py with one mapping factor K on every circular element.
K_CASES = {"roof": _roof, "hemisphere": _hemisphere}
#: Where each case's displacement is read: the surface point and the component (signed so that
#: the reference is positive).
K_READ = {"roof": ((0.0, 1.0), 2, -1.0), "hemisphere": ((0.0, 1.0), 0, 1.0)}


#: Condition numbers above this are singular to round-off (their smallest eigenvalue is lost).
COND_LOST = 1e15


def _cond(ev: NDArray) -> float:
    """``λ_max / λ_min`` of a symmetric positive definite matrix's eigenvalues, ``inf`` when
    ``λ_min`` is below :data:`COND_LOST` of ``λ_max`` (lost to round-off)."""
    return float(ev[-1] / ev[0]) if ev[0] > ev[-1] / COND_LOST else float("inf")


def _omega_max(k: NDArray, m: NDArray) -> float:
    """The highest ``ω`` of ``(k, m)``, NaN where ``m`` is not positive definite to
    round-off (its Cholesky factor fails)."""
    try:
        return float(np.sqrt(sla.eigh(k, m, eigvals_only=True)[-1]))
    except np.linalg.LinAlgError:
        return float("nan")


def k_row(case: str, n: int, k: float | str) -> dict[str, float]:
    """One mesh of the K study: the spread of the nodal gradient scales (largest over smallest,
    over both directions), the 2-norm condition numbers of ``M``, of ``K_Z = Zᵀ K Z`` (``Z``
    an orthonormal basis of the null space of the supports' rows; dense, small meshes; ``inf``
    when singular to round-off) and of ``K_Z`` scaled by its diagonal (Jacobi), the highest
    circular frequency ``ω_max`` of ``(K_Z, M_Z)`` (independent of any scaling of the
    coordinates: it sets an explicit time step) and the displacement."""
    body, kernel, f, _ = K_CASES[case](n, k)
    mesh = body.mesh
    spread = max(float(d.scales.max() / d.scales.min()) for d in (mesh.u, mesh.v))
    c, _ = constraint_rows(body)
    kk = kernel.tangent(body.q0)
    u = cases.saddle_solve(kk, c, f)
    at, comp, sign = K_READ[case]
    w = sign * float(body.position(at, body.q0 + u)[comp] - body.position(at)[comp])
    with threadpool_limits(1):  # small dense problems: threads only contend on a shared machine
        z = sla.null_space(c.toarray())
        kz = z.T @ kk.toarray() @ z
        mz = z.T @ kernel.mass().toarray() @ z
        jacobi = 1.0 / np.sqrt(np.diag(kz))
        return {
            "spread": spread,
            "cond_m": _cond(np.linalg.eigvalsh(kernel.mass().toarray())),
            "cond_k": _cond(np.linalg.eigvalsh(kz)),
            "cond_kj": _cond(np.linalg.eigvalsh(jacobi[:, None] * kz * jacobi[None, :])),
            "omega_max": _omega_max(kz, mz),
            "w": w,
        }


def _fmt(x: float) -> str:
    return f"{x:.2e}" if np.isfinite(x) else f"> {COND_LOST:.0e}"


def k_table(case: str, sizes: list[int]) -> str:
    """Markdown: the K study of one case (:func:`k_row`), a row per mesh and K, with the
    displacement's error against the published reference."""
    ref = K_CASES[case](1, "opt")[3]
    out = [
        "| n × n | K | scale spread | cond M | cond K | cond K Jacobi | ω_max / Kopt's "
        "| w / ref − 1 |",
        "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    for n in sizes:
        rows = {k: k_row(case, n, k) for k in K_VALUES}
        for k, r in rows.items():
            cells = [f"{n}", f"{k:g}", f"{r['spread']:.3g}", _fmt(r["cond_m"]), _fmt(r["cond_k"])]
            cells += [_fmt(r["cond_kj"]), f"{r['omega_max'] / rows[0.5]['omega_max']:.3g}"]
            out.append("| " + " | ".join([*cells, f"{r['w'] / ref - 1.0:+.2e}"]) + " |")
    return "\n".join(out)


def main() -> None:
    """Print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--modes", type=int, nargs="+", default=[2, 4, 8, 16])
    parser.add_argument("--kstudy", type=int, nargs="+", default=[4, 8])
    args = parser.parse_args()
    print(modes_table(args.modes))
    for case in K_CASES:
        print(f"\n{case}\n")
        print(k_table(case, args.kstudy))


if __name__ == "__main__":
    main()
