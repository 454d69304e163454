"""Membrane locking of the RANCF shell element: linear solves at the element-kernel level.

The Scordelis–Lo roof and the pinched cylinder with rigid diaphragms, the pinched hemisphere
with an 18° hole, and a simply supported square plate (no membrane–bending coupling: the
treatment must not change it), each solved as ``K u = f`` at the reference with the supports
of :class:`rancf.bodies.shell.ShellSupport` as the rows ``C u = 0`` of
:func:`rancf.bodies.shell_supports.constraint_rows` (docs/derivations/shell.md sec. 7; one
saddle-point system, :func:`saddle_solve`), for 2 to 32 elements per side, with the membrane
strains as they are (``"full"``), projected (eq. 5.1) and on a reduced 3 × 3 rule
(``"reduced"``).  Prints the Markdown tables of docs/derivations/shell.md sec. 9.  The cases are
also the tests' (tests/kernels/test_shell_locking.py).

    python benchmarks/shell_locking.py [--sizes 2 4 8 16] [--hemisphere 2 4 8 16 24 32]
        [--normalized 2 4 8 16 32]
"""

from __future__ import annotations

import argparse

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from rancf.bodies.shell import ShellBody, ShellSupport
from rancf.bodies.shell_loads import point_load
from rancf.bodies.shell_supports import constraint_rows
from rancf.kernels.shell import MEMBRANE, ShellKernel
from rancf.mesh.surface_kinds import mesh_surface

#: Published values: Scordelis–Lo vertical displacement at the middle of the free edge, pinched
#: cylinder displacement under the load (MacNeal & Harder 1985; Belytschko et al. 1985), the
#: Navier series of a simply supported square plate, w = 0.00406235 q a^4 / D (nu = 0.3).
ROOF_REF = -0.3006
PINCHED_REF = -1.8248e-5
PLATE_COEF = 0.00406235
#: Pinched hemisphere with an 18° hole: the radial displacement under a load (MacNeal & Harder
#: 1985 give 0.094; 0.0924 is the value of Belytschko et al. 1985 that the Kirchhoff–Love IGA
#: papers, Kiendl et al. 2009 among them, compare with).
HEMISPHERE_REF = 0.0924
#: The unit square plate and its four edges.
SQUARE = {"kind": "rectangle", "corner": [0.0, 0.0], "size": [1.0, 1.0]}
EDGES = ("u0", "u1", "v0", "v1")


def saddle_solve(k: sp.spmatrix, c: sp.spmatrix, rhs: NDArray) -> NDArray[np.float64]:
    """``x`` of ``K x + Cᵀ μ = rhs``, ``C x = 0``: the saddle-point system of a solve with the
    supports' rows ``C`` held by multipliers ``μ`` (docs/derivations/shell.md sec. 7), by
    SciPy's sparse LU; the rows are scaled by the largest entry of ``K`` so that both blocks
    are of one size (unscaled, the rows of a stiff shell hold to only 1e-8 of ``|x|``)."""
    n, nc = k.shape[0], c.shape[0]
    cs = c * float(abs(k).max())
    a = sp.bmat([[k, cs.T], [cs, None]], format="csc")
    return np.asarray(spla.spsolve(a, np.concatenate([rhs, np.zeros(nc)]))[:n])


def linear_solve(kernel: ShellKernel, body: ShellBody, f: NDArray) -> NDArray[np.float64]:
    """Displacements ``u`` of ``K(q0) u = f`` with the supports of ``body`` held,
    ``C u = 0`` (:func:`rancf.bodies.shell_supports.constraint_rows`); the rows are checked
    to hold to 1e-10 of ``|u|``."""
    c, _ = constraint_rows(body)
    u = saddle_solve(kernel.tangent(body.q0), c, f)
    if c.shape[0] and np.abs(c @ u).max() > 1e-10 * max(float(np.abs(u).max()), 1e-300):
        raise RuntimeError("the supports do not hold in the linear solve (singular system?)")
    return u


def kernel_of(body: ShellBody, membrane: str) -> ShellKernel:
    """The element kernel of ``body`` with the membrane treatment ``membrane``."""
    return ShellKernel.from_mesh(
        body.mesh,
        body.thickness,
        body.youngs_modulus,
        body.poisson_ratio,
        body.density,
        membrane=membrane,
    )


def sym(edge: str, axis: int) -> ShellSupport:
    """A symmetry plane with normal ``e_axis`` on ``edge``."""
    return ShellSupport("symmetry", edge, normal=tuple(float(a == axis) for a in range(3)))


def roof_body(n: int, k: float | str = "opt") -> ShellBody:
    """Scordelis–Lo roof (R 25, L 50, 80°, t 0.25, E 4.32e8, nu 0), the quarter
    ``[50°, 90°] × [0, L/2]`` on ``n × n`` elements with mapping factor ``k`` along the
    circle: a diaphragm at ``y = 0``, symmetry at 90° and at ``y = L/2``."""
    geo = {"kind": "cylinder", "radius": 25.0, "length": 25.0, "angles_deg": [50.0, 90.0]}
    supports = [ShellSupport("diaphragm", "v0"), sym("u1", 0), sym("v1", 1)]
    return ShellBody(mesh_surface(geo, [n, n], k=k), 0.25, 4.32e8, 0.0, 1.0, supports=supports)


def roof(n: int, membrane: str) -> float:
    """:func:`roof_body` under 90 per area down: the vertical displacement of the middle of the
    free edge."""
    body = roof_body(n)
    k = kernel_of(body, membrane)
    u = linear_solve(k, body, k.area_load([0.0, 0.0, -90.0]))
    return float(u[12 * int(body.mesh.edge_nodes("u0")[-1]) + 2])


def pinched(n: int, membrane: str) -> float:
    """Pinched cylinder (R 300, L 600, t 3, E 3e6, nu 0.3, P 1, rigid diaphragms), the eighth
    ``[0°, 90°] × [0, L/2]`` on ``n × n`` elements with P/4: the displacement under the load."""
    geo = {"kind": "cylinder", "radius": 300.0, "length": 300.0, "angles_deg": [0.0, 90.0]}
    supports = [ShellSupport("diaphragm", "v0"), sym("u0", 2), sym("u1", 0), sym("v1", 1)]
    body = ShellBody(mesh_surface(geo, [n, n]), 3.0, 3e6, 0.3, 1.0, supports=supports)
    k = kernel_of(body, membrane)
    node = int(body.mesh.edge_nodes("u1")[-1])
    f = np.zeros(k.n)
    f[12 * node + 2] = -0.25
    return float(linear_solve(k, body, f)[12 * node + 2])


def hemisphere_body(n: int, k: float | str | list = "opt") -> ShellBody:
    """Pinched hemisphere with an 18° hole (R 10, t 0.04, E 6.825e7, nu 0.3), the quarter
    ``azimuth [0°, 90°] × polar [18°, 90°]`` on ``n × n`` elements with mapping factor(s)
    ``k``: symmetry planes ``y = 0`` (``u0``) and ``x = 0`` (``u1``), the point ``[0, 1]`` on
    the equator held along ``z`` (a roller along ``x``; the loads have no resultant along
    ``z``)."""
    geo = {"kind": "sphere", "radius": 10.0, "azimuth_deg": [0.0, 90.0], "polar_deg": [18.0, 90.0]}
    hold_z = ShellSupport("roller", (0.0, 1.0), axis=(1.0, 0.0, 0.0))
    supports = [sym("u0", 1), sym("u1", 0), hold_z]
    return ShellBody(mesh_surface(geo, [n, n], k=k), 0.04, 6.825e7, 0.3, 1.0, supports=supports)


def hemisphere_load(body: ShellBody) -> NDArray[np.float64]:
    """The hemisphere's forces: ``+1 e_x`` at ``[0, 1]`` and ``−1 e_y`` at ``[1, 1]``."""
    return point_load(body, [0.0, 1.0], [1.0, 0.0, 0.0]) + point_load(body, [1.0, 1.0], [0, -1, 0])


def hemisphere(n: int, membrane: str) -> float:
    """:func:`hemisphere_body` under :func:`hemisphere_load` (on the equator): the radial
    (outward) displacement under the first force."""
    body = hemisphere_body(n)
    u = linear_solve(kernel_of(body, membrane), body, hemisphere_load(body))
    return float(body.position([0.0, 1.0], body.q0 + u)[0] - 10.0)


def plate(n: int, membrane: str) -> float:
    """Simply supported square plate (a 1, t 0.01, E 2.1e11, nu 0.3, q 1000 down) on ``n × n``
    elements, pinned on its four edges (the in-plane motion is decoupled in the linear plate):
    the centre deflection over the Navier value ``-0.00406235 q a^4 / D``."""
    t, e, nu, q = 0.01, 2.1e11, 0.3, 1000.0
    pins = [ShellSupport("pin", s) for s in EDGES]
    body = ShellBody(mesh_surface(SQUARE, [n, n]), t, e, nu, 1.0, supports=pins)
    k = kernel_of(body, membrane)
    u = linear_solve(k, body, k.area_load([0.0, 0.0, -q]))
    w = body.position([0.5, 0.5], body.q0 + u)[2]
    d = e * t**3 / (12.0 * (1.0 - nu**2))
    return float(w / (-PLATE_COEF * q / d))


def table(sizes: list[int]) -> str:
    """The Markdown convergence table (displacement against elements per side): each case with
    the membrane strains full, projected (eq. 5.1) and reduced (3 × 3)."""
    head = " | ".join(f"{c} {m}" for c in ("roof", "pinched", "plate") for m in MEMBRANE)
    out = [f"| n × n | {head} |", "| ---: |" + " ---: |" * 3 * len(MEMBRANE)]
    for n in sizes:
        cells = [f"{roof(n, m):.5f}" for m in MEMBRANE]
        cells += [f"{pinched(n, m):.4e}" for m in MEMBRANE]
        cells += [f"{plate(n, m):.5f}" for m in MEMBRANE]
        out.append(f"| {n} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def hemisphere_table(sizes: list[int]) -> str:
    """Markdown: the pinched hemisphere's radial displacement with each membrane treatment and
    the projected one over :data:`HEMISPHERE_REF`."""
    head = " | ".join(f"hemisphere {m}" for m in MEMBRANE)
    out = [f"| n × n | {head} | projected / 0.0924 |", "| ---: |" + " ---: |" * 4]
    for n in sizes:
        w = {m: hemisphere(n, m) for m in MEMBRANE}
        cells = [f"{w[m]:.5f}" for m in MEMBRANE] + [f"{w['projected'] / HEMISPHERE_REF:.4f}"]
        out.append(f"| {n} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def normalized_table(sizes: list[int]) -> str:
    """Markdown: the three obstacle-course displacements with the projected membrane strains
    (the kernel's default) over their references, against elements per side."""
    out = [
        "| n × n | roof / 0.3006 | pinched cylinder / 1.8248e-5 | hemisphere / 0.0924 |",
        "| ---: | ---: | ---: | ---: |",
    ]
    for n in sizes:
        w = (
            roof(n, "projected") / ROOF_REF,
            pinched(n, "projected") / PINCHED_REF,
            hemisphere(n, "projected") / HEMISPHERE_REF,
        )
        out.append(f"| {n} | " + " | ".join(f"{x:.4f}" for x in w) + " |")
    return "\n".join(out)


def main() -> None:
    """Print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2, 4, 8, 16])
    parser.add_argument("--hemisphere", type=int, nargs="+", default=[2, 4, 8, 16, 24, 32])
    parser.add_argument("--normalized", type=int, nargs="+", default=[2, 4, 8, 16, 32])
    args = parser.parse_args()
    print(table(args.sizes))
    print()
    print(hemisphere_table(args.hemisphere))
    print()
    print(normalized_table(args.normalized))


if __name__ == "__main__":
    main()
