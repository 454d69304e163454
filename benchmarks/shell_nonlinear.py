"""Geometrically nonlinear checks of the RANCF shell element: Newton solves at the kernel level.

Load steps, each solved by Newton's method on ``f_int(q) = λ f_ext(q)`` with the supports held
as Lagrange multipliers (``C q = C q0``, :func:`rancf.bodies.shell_supports.constraint_rows`),
the loads as consistent nodal vectors (:mod:`rancf.bodies.shell_loads`) and a follower end
moment (docs/derivations/shell.md sec. 6, eq. 6.1).  Cases (sec. 9):

* the plate strip rolled into a full circle by ``M = 2π EI / L`` (L 12, b 1, t 0.1, E 1.2e6,
  ν 0, clamped at one end): the free edge returns to the clamp;
* the slit annular plate of Sze, Liu & Lo (2004) (R 6..10, t 0.03, E 21e6, ν 0, one slit edge
  clamped, a line force up to 0.8 per length on the other): the vertical deflections of the
  loaded edge's inner (A) and outer (B) corners against their load-deflection table;
* their pull-out of an open-ended cylinder (R 4.953, L 10.35, t 0.094, E 10.5e6, ν 0.3125, two
  opposite radial forces up to 40000): the radial displacements at A, B and C likewise.

The cases are also the tests' (tests/kernels/test_shell_nonlinear.py), on coarse meshes.

    python benchmarks/shell_nonlinear.py [--case rollup annular pullout] [--sizes 4 8 16]
        [--annular 16 2 32 4] [--pullout 8 8 16 16]
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from rancf.bodies.shell import ShellBody, ShellSupport
from rancf.bodies.shell_loads import edge_frames, edge_load, point_load
from rancf.bodies.shell_supports import constraint_rows
from rancf.kernels.shell import ShellKernel
from rancf.mesh.surface_kinds import (
    circle_pieces,
    line_pieces,
    mesh_surface,
    surface_of_revolution,
)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from shell_locking import saddle_solve  # noqa: E402

#: Sze, Liu & Lo (2004), slit annular plate, their 10 × 80 S4R table: ``P / Pmax``, ``w_A``,
#: ``w_B`` (as transcribed in MBDyn's tests/plates/sze2004/sze33/sze33_ref.dat).
SZE_ANNULAR = np.array(
    [
        [0.025, 1.305, 1.789],
        [0.05, 2.455, 3.370],
        [0.075, 3.435, 4.720],
        [0.10, 4.277, 5.876],
        [0.125, 5.007, 6.872],
        [0.15, 5.649, 7.736],
        [0.20, 6.725, 9.160],
        [0.25, 7.602, 10.288],
        [0.30, 8.340, 11.213],
        [0.35, 8.974, 11.992],
        [0.40, 9.529, 12.661],
        [0.45, 10.023, 13.247],
        [0.50, 10.468, 13.768],
        [0.55, 10.876, 14.240],
        [0.60, 11.257, 14.674],
        [0.65, 11.620, 15.081],
        [0.70, 11.970, 15.469],
        [0.75, 12.310, 15.842],
        [0.80, 12.642, 16.202],
        [0.85, 12.966, 16.550],
        [0.90, 13.282, 16.886],
        [0.95, 13.590, 17.212],
        [1.00, 13.891, 17.528],
    ]
)

#: Sze, Liu & Lo (2004), pull-out of an open-ended cylinder, their 16 × 24 S4R table on the
#: octant: ``P / Pmax``, ``w_A`` (outward, under the load), ``−u_B``, ``−u_C`` (inward, 90° from
#: the load at mid-length and at the free end) (as transcribed in MBDyn's
#: tests/plates/sze2004/sze35/sze35_ref.dat).
SZE_PULLOUT = np.array(
    [
        [0.025, 0.819, 0.864, 0.872],
        [0.05, 1.260, 1.471, 1.493],
        [0.075, 1.527, 1.901, 1.946],
        [0.10, 1.707, 2.217, 2.293],
        [0.15, 1.936, 2.641, 2.792],
        [0.20, 2.079, 2.904, 3.106],
        [0.25, 2.180, 3.087, 3.310],
        [0.30, 2.257, 3.227, 3.452],
        [0.35, 2.321, 3.342, 3.556],
        [0.40, 2.376, 3.443, 3.632],
        [0.45, 2.425, 3.539, 3.688],
        [0.50, 2.473, 3.653, 3.718],
        [0.525, 2.543, 4.061, 3.580],
        [0.55, 2.577, 4.171, 3.518],
        [0.60, 2.618, 4.274, 3.452],
        [0.65, 2.648, 4.338, 3.410],
        [0.70, 2.672, 4.385, 3.378],
        [0.75, 2.692, 4.423, 3.353],
        [0.80, 2.710, 4.455, 3.332],
        [0.85, 2.726, 4.483, 3.313],
        [0.90, 2.741, 4.508, 3.297],
        [0.95, 2.755, 4.530, 3.283],
        [1.00, 2.768, 4.551, 3.269],
    ]
)

#: Newton: the norm of the free residual over that of the full external load that converges
#: (round-off holds it near 1e-9 in the annular plate).
NEWTON_RTOL = 1e-7
NEWTON_MAX = 40
#: Halvings of a load step that does not converge before a solve gives up.
CUTS = 6

#: ``(Q, dQ/dq)`` of the external load at load factor ``λ`` and coordinates ``q``.
Load = Callable[[NDArray[np.float64], float], tuple[NDArray[np.float64], sp.spmatrix | None]]


def follower_moment(
    body: ShellBody, edge: str, moment: float, axis: NDArray, q: NDArray, points: int = 8
) -> tuple[NDArray[np.float64], sp.csr_matrix]:
    """A total bending moment ``moment`` about the fixed ``axis`` spread along ``edge`` as a
    follower couple: ``m = moment / L`` per reference length on the rotation ``θ`` of the
    current cross tangent ``a`` about ``axis`` (eq. 6.1), ``Q = ∫ m S_νᵀ g ds`` with
    ``g = axis × a / |a_p|²`` (``a_p`` the part of ``a`` normal to ``axis``), and its
    (symmetric) derivative ``∫ m S_νᵀ ∂g/∂a S_ν ds``."""
    t = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    frames = edge_frames(body, edge, points)
    m = moment / float(sum(f[5].sum() for f in frames))
    out = np.zeros(body.n_dofs)
    rows_i, cols_i, vals = [], [], []
    skew = np.cross(np.eye(3), t)  # skew[c, f] = (e_c × t)_f = ∂(t × a)_c / ∂a_f
    for dofs, rows, _, _, _, ds in frames:
        a = np.einsum("pab,abc->pc", rows[2], q[dofs])
        ap = a - np.outer(a @ t, t)
        n2 = np.einsum("pc,pc->p", ap, ap)
        g = np.cross(t, a) / n2[:, None]
        np.add.at(out, dofs, m * np.einsum("pab,p,pc->abc", rows[2], ds, g))
        h = skew[None] / n2[:, None, None] - 2.0 * np.einsum("pc,pd->pcd", g, ap / n2[:, None])
        ke = m * np.einsum("pab,pde,p,pcf->abcdef", rows[2], rows[2], ds, h).reshape(48, 48)
        flat = dofs.reshape(48)
        rows_i.append(np.repeat(flat, 48))
        cols_i.append(np.tile(flat, 48))
        vals.append(ke.ravel())
    k = sp.coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows_i), np.concatenate(cols_i))),
        shape=(body.n_dofs, body.n_dofs),
    )
    return out, k.tocsr()


def _newton(
    kernel: ShellKernel, c: sp.csr_matrix, load: Load, q: NDArray, lam: float, scale: float
) -> NDArray[np.float64] | None:
    """Newton from ``q`` at load factor ``lam``: the converged coordinates, or None."""
    cct = spla.splu(sp.csc_matrix(c @ c.T))
    for _ in range(NEWTON_MAX):
        f, k_ext = load(q, lam)
        r = kernel.forces(q) - f
        free = r - c.T @ cct.solve(c @ r)
        if not np.all(np.isfinite(free)):
            return None
        if np.linalg.norm(free) <= NEWTON_RTOL * scale:
            return q
        k = kernel.tangent(q) if k_ext is None else kernel.tangent(q) - k_ext
        q = q + saddle_solve(k, c, -r)
    return None


def newton_path(
    kernel: ShellKernel, body: ShellBody, load: Load, factors: NDArray
) -> list[NDArray[np.float64]]:
    """Coordinates at each load factor of ``factors`` (increasing from 0): Newton on
    ``f_int(q) − Q(q, λ) + Cᵀ μ = 0``, ``C q = C q0``.  A step that does not converge in
    :data:`NEWTON_MAX` iterations is halved, up to :data:`CUTS` times; then ``RuntimeError``."""
    c, _ = constraint_rows(body)
    q, lam0 = body.q0.copy(), 0.0
    scale = max(float(np.linalg.norm(load(q, float(factors[-1]))[0])), 1e-300)
    out = []
    for target in factors:
        step, cuts = float(target) - lam0, 0
        while lam0 < target:
            lam = min(lam0 + step, float(target))
            new = _newton(kernel, c, load, q, lam, scale)
            if new is None:
                cuts += 1
                if cuts > CUTS:
                    raise RuntimeError(
                        f"Newton did not converge at load factor {lam:g} (from {lam0:g}, "
                        f"after {CUTS} halvings of the step, {NEWTON_MAX} iterations each)"
                    )
                step *= 0.5
                continue
            q, lam0 = new, lam
        out.append(q.copy())
    return out


def rollup(n: int, steps: int) -> tuple[float, NDArray[np.float64]]:
    """The plate strip (L 12, b 1, t 0.1, E 1.2e6, ν 0) on ``n × 1`` elements, clamped at
    ``u0``, rolled by the follower end moment ``M = 2π EI / L`` in ``steps`` equal steps: the
    largest distance of the free edge's points from the clamp over ``L``, and the mid-point of
    the free edge at each step."""
    length, width, t, e = 12.0, 1.0, 0.1, 1.2e6
    mesh = mesh_surface(
        {"kind": "rectangle", "corner": [0.0, 0.0], "size": [length, width]}, [n, 1]
    )
    body = ShellBody(mesh, t, e, 0.0, 1.0, supports=[ShellSupport("clamp", "u0")])
    kernel = ShellKernel.from_mesh(mesh, t, e, 0.0, 1.0)
    moment = 2.0 * np.pi * e * width * t**3 / 12.0 / length
    axis = np.array([0.0, 1.0, 0.0])

    def load(q: NDArray, lam: float) -> tuple[NDArray, sp.spmatrix]:
        return follower_moment(body, "u1", -lam * moment, axis, q)

    path = newton_path(kernel, body, load, np.linspace(0.0, 1.0, steps + 1)[1:])
    tips = np.array([body.position([1.0, 0.5], q) for q in path])
    gap = max(
        float(np.linalg.norm(body.position([1.0, s], path[-1]) - body.position([0.0, s])))
        for s in np.linspace(0.0, 1.0, 5)
    )
    return gap / length, tips


def annular(nu: int, nv: int, factors: NDArray) -> NDArray[np.float64]:
    """Slit annular plate (R 6..10, t 0.03, E 21e6, ν 0) on ``nu × nv`` elements (u around,
    v across): clamped at ``u0``, a vertical line force ``0.8 λ`` per length on ``u1``.
    Rows ``[λ, w_A, w_B]`` with A the inner and B the outer corner of the loaded edge."""
    pts, w, pu = circle_pieces(0.0, 2.0 * np.pi, nu, "opt")
    tv, pv = line_pieces(nv)
    profile = np.stack([6.0 + 4.0 * tv, 0.0 * tv], axis=-1)
    mesh = surface_of_revolution((pts, w, replace(pu, closed=False)), profile, pv, "xy", "annulus")
    body = ShellBody(mesh, 0.03, 21e6, 0.0, 1.0, supports=[ShellSupport("clamp", "u0")])
    kernel = ShellKernel.from_mesh(mesh, 0.03, 21e6, 0.0, 1.0)
    f = edge_load(body, "u1", force=[0.0, 0.0, 0.8 * 4.0])
    path = newton_path(kernel, body, lambda q, lam: (lam * f, None), factors)
    a0, b0 = body.position([1.0, 0.0]), body.position([1.0, 1.0])
    return np.array(
        [
            [lam, body.position([1.0, 0.0], q)[2] - a0[2], body.position([1.0, 1.0], q)[2] - b0[2]]
            for lam, q in zip(factors, path, strict=True)
        ]
    )


def pullout(nu: int, nv: int, factors: NDArray) -> NDArray[np.float64]:
    """Pull-out of an open-ended cylinder (R 4.953, L 10.35, t 0.094, E 10.5e6, ν 0.3125, two
    opposite radial forces P up to 40000 at mid-length), the octant ``[0°, 90°] × [0, L/2]`` on
    ``nu × nv`` elements with symmetry planes at 0°, 90° and ``y = L/2`` and ``P/4`` outward at
    A ``[1, 1]``.  Rows ``[λ, w_A, −u_B, −u_C]``: B ``[0, 1]`` and C ``[0, 0]`` (the free end)."""
    geo = {"kind": "cylinder", "radius": 4.953, "length": 10.35 / 2, "angles_deg": [0.0, 90.0]}
    mesh = mesh_surface(geo, [nu, nv])
    planes = (("u0", (0.0, 0.0, 1.0)), ("u1", (1.0, 0.0, 0.0)), ("v1", (0.0, 1.0, 0.0)))
    supports = [ShellSupport("symmetry", e, normal=n) for e, n in planes]
    body = ShellBody(mesh, 0.094, 10.5e6, 0.3125, 1.0, supports=supports)
    kernel = ShellKernel.from_mesh(mesh, 0.094, 10.5e6, 0.3125, 1.0)
    f = point_load(body, [1.0, 1.0], [0.0, 0.0, 40000.0 / 4.0])
    path = newton_path(kernel, body, lambda q, lam: (lam * f, None), factors)
    d = [lambda q, p=p: body.position(p, q) - body.position(p) for p in ([1, 1], [0, 1], [0, 0])]
    return np.array(
        [[lam, d[0](q)[2], -d[1](q)[0], -d[2](q)[0]] for lam, q in zip(factors, path, strict=True)]
    )


#: The loads the tables show (every load of the reference table is solved).
SHOWN = (0.05, 0.1, 0.2, 0.3, 0.5, 0.525, 0.6, 0.8, 1.0)
#: ``case: (solver, reference table, column names)``.
SZE_CASES = {
    "annular": (annular, SZE_ANNULAR, ("w_A", "w_B")),
    "pullout": (pullout, SZE_PULLOUT, ("w_A", "−u_B", "−u_C")),
}


def sze_table(case: str, meshes: list[tuple[int, int]]) -> str:
    """Markdown: a Sze et al. case on each mesh beside their table, at the loads
    :data:`SHOWN` (each solve runs through every load of their table)."""
    solve, ref, names = SZE_CASES[case]
    runs = [solve(nu, nv, ref[:, 0]) for nu, nv in meshes]
    head = [f"{q} {m[0]} × {m[1]}" if m else f"{q} Sze" for q in names for m in [*meshes, None]]
    out = ["| P/Pmax | " + " | ".join(head) + " |", "| ---: |" + " ---: |" * len(head)]
    for r, lam in enumerate(ref[:, 0]):
        if not np.any(np.isclose(lam, SHOWN)):
            continue
        values = [x[r, 1 + k] for k in range(len(names)) for x in [*runs, ref]]
        out.append(f"| {lam:g} | " + " | ".join(f"{v:.3f}" for v in values) + " |")
    return "\n".join(out)


def rollup_table(sizes: list[int], steps: int) -> str:
    """Markdown: the free edge's distance from the clamp after the full moment."""
    out = ["| elements | gap / L |", "| ---: | ---: |"]
    for n in sizes:
        out.append(f"| {n} × 1 | {rollup(n, steps)[0]:.2e} |")
    return "\n".join(out)


def main() -> None:
    """Print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", nargs="+", default=["rollup", "annular", "pullout"])
    parser.add_argument("--sizes", type=int, nargs="+", default=[4, 8, 16])
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--annular", type=int, nargs="+", default=[16, 2, 32, 4, 48, 6])
    parser.add_argument("--pullout", type=int, nargs="+", default=[8, 8, 16, 16])
    args = parser.parse_args()
    if "rollup" in args.case:
        print(rollup_table(args.sizes, args.steps))
    for case in ("annular", "pullout"):
        if case in args.case:
            n = getattr(args, case)
            print(sze_table(case, list(zip(n[::2], n[1::2], strict=True))))


if __name__ == "__main__":
    main()
