"""Membrane locking of the RANCF shell element: linear solves at the element-kernel level.

The Scordelis–Lo roof and the pinched cylinder with rigid diaphragms, and a simply supported
square plate (no membrane–bending coupling: the treatment must not change it), each solved as
``K u = f`` at the reference with the supports as fixed coordinates (docs/derivations/shell.md
sec. 7), for 2, 4, 8, 16 elements per side, with the membrane strains as they are
(``"full"``), projected (eq. 5.1) and on a reduced 3 × 3 rule (``"reduced"``).  Prints the
Markdown table of docs/derivations/shell.md sec. 9.  The cases are also the tests'
(tests/kernels/test_shell_locking.py).

    python benchmarks/shell_locking.py [--sizes 2 4 8 16]
"""

from __future__ import annotations

import argparse

import numpy as np
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from rancf.kernels.shell import MEMBRANE, ShellKernel
from rancf.mesh.surface_kinds import mesh_surface
from rancf.mesh.surfaces import SurfaceMesh

#: Published values: Scordelis–Lo vertical displacement at the middle of the free edge, pinched
#: cylinder displacement under the load (MacNeal & Harder 1985; Belytschko et al. 1985), the
#: Navier series of a simply supported square plate, w = 0.00406235 q a^4 / D (nu = 0.3).
ROOF_REF = -0.3006
PINCHED_REF = -1.8248e-5
PLATE_COEF = 0.00406235


def _fix(mesh: SurfaceMesh, edge: str, vec: int, comps: list[int]) -> list[int]:
    """Coordinates ``comps`` of nodal vector ``vec`` (0 r, 1 r_x, 2 r_y, 3 r_xy) on an edge."""
    return [12 * int(nd) + 3 * vec + d for nd in mesh.edge_nodes(edge) for d in comps]


def _along(edge: str) -> tuple[int, int]:
    """The nodal gradient along an edge and across it."""
    return (2, 1) if edge in ("u0", "u1") else (1, 2)


def diaphragm(mesh: SurfaceMesh, edge: str, comps: list[int]) -> list[int]:
    """A rigid diaphragm: the components ``comps`` (the edge's plane) of ``r`` and ``r_along``
    fixed along the edge (sec. 7)."""
    return _fix(mesh, edge, 0, comps) + _fix(mesh, edge, _along(edge)[0], comps)


def symmetry(mesh: SurfaceMesh, edge: str, axis: int) -> list[int]:
    """A symmetry plane with normal ``e_axis``: ``r``, ``r_along`` do not cross it, ``r_cross``
    and ``r_xy`` stay normal to it (sec. 7)."""
    along, cross = _along(edge)
    other = [d for d in range(3) if d != axis]
    return (
        _fix(mesh, edge, 0, [axis])
        + _fix(mesh, edge, along, [axis])
        + _fix(mesh, edge, cross, other)
        + _fix(mesh, edge, 3, other)
    )


def linear_solve(
    kernel: ShellKernel, q0: NDArray, f: NDArray, fixed: list[int]
) -> NDArray[np.float64]:
    """Displacements ``u`` of ``K(q0) u = f`` with the coordinates ``fixed`` held at zero."""
    k = kernel.tangent(q0).tocsc()
    free = np.setdiff1d(np.arange(kernel.n), np.unique(fixed))
    u = np.zeros(kernel.n)
    u[free] = spla.spsolve(k[free][:, free], f[free])
    return u


def roof(n: int, membrane: str) -> float:
    """Scordelis–Lo roof (R 25, L 50, 80°, t 0.25, E 4.32e8, nu 0, 90 per area down), the
    quarter ``[50°, 90°] × [0, L/2]`` on ``n × n`` elements: the vertical displacement of the
    middle of the free edge."""
    geo = {"kind": "cylinder", "radius": 25.0, "length": 25.0, "angles_deg": [50.0, 90.0]}
    mesh = mesh_surface(geo, [n, n])
    k = ShellKernel.from_mesh(mesh, 0.25, 4.32e8, 0.0, 1.0, membrane=membrane)
    fixed = diaphragm(mesh, "v0", [0, 2]) + symmetry(mesh, "u1", 0) + symmetry(mesh, "v1", 1)
    u = linear_solve(k, mesh.q0, k.area_load([0.0, 0.0, -90.0]), fixed)
    return float(u[12 * int(mesh.edge_nodes("u0")[-1]) + 2])


def pinched(n: int, membrane: str) -> float:
    """Pinched cylinder (R 300, L 600, t 3, E 3e6, nu 0.3, P 1, rigid diaphragms), the eighth
    ``[0°, 90°] × [0, L/2]`` on ``n × n`` elements with P/4: the displacement under the load."""
    geo = {"kind": "cylinder", "radius": 300.0, "length": 300.0, "angles_deg": [0.0, 90.0]}
    mesh = mesh_surface(geo, [n, n])
    k = ShellKernel.from_mesh(mesh, 3.0, 3e6, 0.3, 1.0, membrane=membrane)
    fixed = (
        diaphragm(mesh, "v0", [0, 2])
        + symmetry(mesh, "u0", 2)
        + symmetry(mesh, "u1", 0)
        + symmetry(mesh, "v1", 1)
    )
    node = int(mesh.edge_nodes("u1")[-1])
    f = np.zeros(k.n)
    f[12 * node + 2] = -0.25
    return float(linear_solve(k, mesh.q0, f, fixed)[12 * node + 2])


def plate(n: int, membrane: str) -> float:
    """Simply supported square plate (a 1, t 0.01, E 2.1e11, nu 0.3, q 1000 down) on ``n × n``
    elements: the centre deflection over the Navier value ``-0.00406235 q a^4 / D``."""
    mesh = mesh_surface({"kind": "rectangle", "corner": [0.0, 0.0], "size": [1.0, 1.0]}, [n, n])
    t, e, nu, q = 0.01, 2.1e11, 0.3, 1000.0
    k = ShellKernel.from_mesh(mesh, t, e, nu, 1.0, membrane=membrane)
    fixed = [i for i in range(k.n) if i % 3 != 2]  # in-plane: decoupled in the linear plate
    for edge in ("u0", "u1", "v0", "v1"):
        fixed += diaphragm(mesh, edge, [2])
    u = linear_solve(k, mesh.q0, k.area_load([0.0, 0.0, -q]), fixed)
    w = mesh.point([0.5, 0.5], mesh.q0 + u)[2]
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


def main() -> None:
    """Print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2, 4, 8, 16])
    print(table(parser.parse_args().sizes))


if __name__ == "__main__":
    main()
