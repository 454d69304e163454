"""A shell body as a flexible body of the System: the core's ``Model`` of the shell family.

The System holds a flexible body as a :class:`rancf.bodies.flexible.Model`; :class:`ShellModel`
is that model for a :class:`~rancf.bodies.shell.ShellBody` (docs/derivations/shell.md sec. 8,
"What the System needs to hold a shell"):

* **Elements.** The core gathers an element's 48 coordinates through the connectivity of the
  body's :class:`~rancf.kernels.shell.ShellKernel` (``Connectivity``, ``src/cpp/bodies/model.hpp``)
  and calls the shell family's kernel of the registry, which is ``ShellElements``: one
  implementation of the shell's energy, forces and tangent.  The half bandwidth follows from the
  connectivity: ``12 (largest node span of an element + 1) - 1``, ``12 (min(nu, nv) + 3) - 1``
  with the nodes numbered along the shorter direction first (:func:`short_first`).
* **Supports** (sec. 7) fix components of nodal vectors.  Each support's rows
  (:func:`rancf.bodies.shell_supports.support_rows`) are grouped by node and nodal vector; a
  vector whose held directions are coordinate axes holds those coordinates, any other is
  turned into an orthonormal basis whose first rows span the held directions
  (``y_k = B q_k`` per node, :attr:`rotations` as for a line's clamp, held rows in
  :attr:`fixed`).  Rows over several nodes (a support at a point between nodes, the seam of a
  closed direction) are refused in one line: the System does not hold them yet.
* **Loads** are one constant vector (point, edge and area loads, gravity:
  :func:`rancf.scenario.shell_build.shell_load`), scaled by the load factor in statics and
  constant in time in dynamics (the model's ``f_gravity``).
* **Mass**: the consistent ``ShellKernel.mass()`` in model coordinates, band storage.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.bodies.families import SHELL
from rancf.bodies.flexible import Model
from rancf.bodies.flexible_core import no_reduction
from rancf.bodies.properties import StrainRateDamping
from rancf.errors import InputError
from rancf.kernels import _core
from rancf.kernels.cable import CableProperties

if TYPE_CHECKING:  # SciPy and the shell's modules load with a shell, not with every system
    from rancf.bodies.shell import ShellBody

__all__ = [
    "ShellModel",
    "node_bases",
    "shell_point",
    "shell_reader",
    "short_first",
    "unstable_shells",
]

#: Coordinates per node: ``r, r_x, r_y, r_xy`` (:data:`rancf.bodies.shell.NODE_DOFS`).
NODE_DOFS = 12

#: Entries of a support row below this fraction of its largest are zero (shape factors at a
#: node that vanish to round-off).
ROW_ZERO = 1e-13


def node_bases(
    body: ShellBody, keys: Sequence[str] | None = None
) -> tuple[NDArray[np.bool_], list[tuple[int, NDArray]]]:
    """The held coordinates and the rotated blocks of the body's supports (module docstring):
    ``(fixed (n,), [(first index, basis (3, 3)), ...])`` with ``q_block = basis @ y_block``
    (:class:`rancf.mesh.coordinates.Coordinates`).  ``keys``: each support's key in errors
    (default ``supports[K]``)."""
    import scipy.sparse as sp

    from rancf.bodies.shell_supports import support_rows

    closed = [d for d, axis in (("u", body.mesh.u), ("v", body.mesh.v)) if axis.closed]
    if closed:  # its seam is rows over two nodes, which the System does not hold yet
        raise InputError(
            "geometry",
            f"closed in {closed[0]} (a 360 deg seam)",
            "an open surface: the seam of a closed surface is not held by the System yet "
            "(model a half or a quarter with symmetry supports)",
        )
    held: dict[int, list[NDArray]] = {}  # first index of a nodal vector -> its held directions
    for k, s in enumerate(body.supports):
        key = keys[k] if keys is not None else f"supports[{k}]"
        try:
            c = sp.csr_matrix(support_rows(body, s))
        except InputError as exc:
            raise InputError(f"{key}.{exc.parameter}", exc.value, exc.allowed) from None
        for i in range(c.shape[0]):
            cols = c.indices[c.indptr[i] : c.indptr[i + 1]]
            vals = c.data[c.indptr[i] : c.indptr[i + 1]]
            keep = np.abs(vals) > ROW_ZERO * np.abs(vals).max()
            cols, vals = cols[keep], vals[keep]
            first = np.unique(cols // 3)
            if first.size != 1:
                raise InputError(
                    f"{key}.at",
                    s.at if isinstance(s.at, str) else list(s.at),
                    "an edge, or a point at a node (a support between nodes or across nodes "
                    "is not held by the System yet)",
                )
            d = np.zeros(3)
            d[cols % 3] = vals
            held.setdefault(3 * int(first[0]), []).append(d)
    fixed = np.zeros(body.n_dofs, dtype=bool)
    rotations: list[tuple[int, NDArray]] = []
    for off, dirs in sorted(held.items()):
        _, sv, vt = np.linalg.svd(np.array(dirs), full_matrices=True)
        rank = int(np.sum(sv > 1e-10 * sv[0]))
        proj = vt[:rank].T @ vt[:rank]
        diag = np.diag(proj)
        if np.allclose(proj, np.diag(np.round(diag)), rtol=0.0, atol=1e-12):
            fixed[off + np.flatnonzero(np.round(diag) == 1.0)] = True  # coordinate axes
            continue
        fixed[off : off + rank] = True  # y_block = vt q_block: its first `rank` entries held
        rotations.append((off, vt.T.copy()))
    return fixed, rotations


def short_first(body: ShellBody) -> NDArray[np.int64]:
    """Each of the body's coordinates' index in a numbering of the nodes along the shorter
    direction first (docs/derivations/shell.md sec. 8: the half bandwidth ``12 (min(nu, nv) +
    3) - 1``): the body's own (``u`` first) unless ``v`` has fewer elements, then node
    ``j (nu + 1) + i`` becomes ``i (nv + 1) + j``."""
    nv1, nu1 = body.mesh.nodes.shape[:2]
    j, i = np.divmod(np.arange(body.n_nodes), nu1)
    node = i * nv1 + j if nv1 < nu1 else np.arange(body.n_nodes)
    return (node[:, None] * NODE_DOFS + np.arange(NODE_DOFS)).ravel()


class ShellModel(Model):
    """A shell body as a flexible body of a System (module docstring).

    Parameters
    ----------
    body : ShellBody
        The shell, its supports included.
    load : array_like, shape ``(12 n_nodes,)``, optional
        The constant load vector on the nodal coordinates (default none).
    gravity : array_like, optional
        The gravity ``load`` holds the weight of (kept for the System's check that a flexible
        body's weight is its own); None: none.
    damping : float
        Mass-proportional damping [1/s].
    gauss : int
        Gauss points per direction.
    membrane : str
        The treatment of the membrane strains (:data:`rancf.kernels.shell.MEMBRANE`).
    support_keys : sequence of str, optional
        Each support's key in errors (a scenario's ``supports[K]``).
    """

    def __init__(
        self,
        body: ShellBody,
        load: ArrayLike | None = None,
        gravity: ArrayLike | None = None,
        damping: float = 0.0,
        gauss: int = 5,
        membrane: str = "projected",
        support_keys: Sequence[str] | None = None,
    ) -> None:
        # the chain's set-up (Model.__init__) does not apply: the shell's own, field by field
        self.body, self.stress_free = body, "reference"
        self.element = cast(Any, SHELL.name)  # not a line's mesh.element
        self.family = SHELL
        self.section: Any = None
        self.material: Any = None
        self.dim, self.closed, self.reduction, self.notes = 3, False, None, ()
        self.n_nodes = body.n_nodes
        #: Each body coordinate's index in the model's (nodes numbered along the shorter
        #: direction first: :func:`short_first`).
        self.dof_perm = short_first(body)
        from rancf.kernels.shell import ShellKernel

        kernel = ShellKernel.from_mesh(
            body.mesh,
            body.thickness,
            body.youngs_modulus,
            body.poisson_ratio,
            body.density,
            gauss,
            membrane,
        )
        node_perm = self.dof_perm[::NODE_DOFS] // NODE_DOFS
        record = replace(
            kernel.record,
            connectivity=np.ascontiguousarray(node_perm[kernel.record.connectivity]),
            q0=self.to_model(kernel.record.q0),
        )
        self.kernel: Any = ShellKernel(record)
        conn = record.connectivity
        self.n_el = int(conn.shape[0])
        self.dpn, self.nde = NODE_DOFS, 4 * NODE_DOFS
        self.n = NODE_DOFS * self.n_nodes
        self.ku = NODE_DOFS * (int((conn.max(axis=1) - conn.min(axis=1)).max()) + 1) - 1
        self.element_dofs = (conn[:, :, None] * NODE_DOFS + np.arange(NODE_DOFS)).reshape(
            self.n_el, self.nde
        )
        fixed, rotations = node_bases(body, support_keys)
        self.fixed = self.to_model(fixed)
        self.rotations = [(int(self.dof_perm[off]), basis) for off, basis in rotations]
        ell = float(np.ptp(body.q0.reshape(-1, NODE_DOFS)[:, :3], axis=0).max())
        t, e_mod = body.thickness, body.youngs_modulus
        #: The force scales of a strip of the shell as wide as its largest extent ``ℓ``:
        #: ``E t ℓ``, ``E t³ ℓ / 12``, ``ρ t ℓ`` (tolerances and round-off floors, as a
        #: line's ``EA``, ``EI``, ``ρA``).
        self.props = CableProperties(
            e_mod * t * ell, e_mod * t**3 / 12.0 * ell, body.density * t * ell
        )
        self.supports = ()
        self.mesh: Any = body.mesh
        self.q0 = np.ascontiguousarray(record.q0, dtype=float)
        self.y0 = self.y_from_q(self.q0)
        self.y_installed = self.y0.copy()
        self.v0 = np.zeros(self.n)
        t = self._turn()
        self.mass_band = self._band(t @ self.kernel.mass() @ t.T)
        self.gravity = None if gravity is None else np.asarray(gravity, dtype=float)
        f = np.zeros(self.n) if load is None else np.asarray(load, dtype=float)
        if f.shape != (self.n,):
            raise InputError("load", list(f.shape), f"{self.n} values (12 a node)")
        self.f_gravity = np.ascontiguousarray(self.to_y(self.to_model(f)))
        self.point_loads = ()
        if not (np.isfinite(damping) and damping >= 0):
            raise InputError("damping.mass_proportional", damping, "a finite number >= 0")
        self.damping = float(damping)
        self.strain_rate_damping = StrainRateDamping()
        self.core = self._core()

    def _turn(self) -> Any:
        """``T`` with ``y = T q`` (SciPy sparse): the rotated blocks' ``basisᵀ``, the identity
        elsewhere."""
        import scipy.sparse as sp

        t = sp.lil_matrix((self.n, self.n))
        t.setdiag(1.0)
        for off, basis in self.rotations:
            t[off : off + 3, off : off + 3] = basis.T
        return sp.csr_matrix(t)

    def _band(self, a: Any) -> NDArray[np.float64]:
        """A SciPy sparse matrix in general band storage ``(2 ku + 1, n)``."""
        c = a.tocoo()
        ab = np.zeros((2 * self.ku + 1, self.n))
        np.add.at(ab, (self.ku + c.row - c.col, c.col), c.data)
        return ab

    def _core(self) -> Any:
        """The core's model of the shell family (``src/cpp/bodies/model.hpp``)."""
        z, zi = np.zeros(0), np.zeros(0, dtype=np.int64)
        node_rot = np.full(self.n_nodes, -1, dtype=np.int64)
        bases: list[NDArray] = []
        for off, basis in self.rotations:  # each node's 12 x 12 B (y_k = B q_k)
            node = off // NODE_DOFS
            if node_rot[node] < 0:
                node_rot[node] = len(bases)
                bases.append(np.eye(NODE_DOFS))
            o = off % NODE_DOFS
            bases[int(node_rot[node])][o : o + 3, o : o + 3] = basis.T
        basis_arr = np.ascontiguousarray(np.array(bases).reshape(-1, NODE_DOFS, NODE_DOFS))
        return _core.Model(
            kind=self.family.core_kind,
            dim=3,
            dpn=NODE_DOFS,
            n_el=self.n_el,
            stiffness=_core.Stiffness(ea=0.0),
            cable=_core.CableData(n1=z, n2=z, gw=z, s0=z, k0=z, j0=z, qr=z),
            beam=_core.BeamData(l0=z, d0=z),
            rod=_core.RodData(n1=z, n2=z, xi=z, gw=z, j0=z, kref=z, tref=z.copy(), m1ref=z.copy()),
            supports=_core.Supports(
                fixed=self.fixed.astype(np.uint8),
                rot_of_node=np.full((self.n_nodes, 2), -1, dtype=np.int64),
                rot=np.zeros((1, 3, 3)),
            ),
            loads=_core.Loads(
                f_gravity=self.f_gravity,
                base=zi,
                f0=np.zeros((0, 3)),
                freq=z,
                moment_node=zi,
                moment=np.zeros((0, 3)),
                moment_freq=z,
            ),
            mass_band=np.ascontiguousarray(self.mass_band),
            y_ref=np.ascontiguousarray(self.y0),
            reduction=no_reduction(),
            shell=_core.ShellData(
                elements=self.kernel.core, node_rot=node_rot, node_basis=basis_arr
            ),
        )

    def check_node(self, node: int, key: str) -> int:
        """A shell's places are its edges and surface points, not node indices: refused in one
        line naming ``key``."""
        raise InputError(
            key,
            node,
            f'a place on a line body (the shell {self.body.name!r} has edges "u0", "u1", "v0", '
            '"v1" and points [u, v]; joints, springs and loads at places on a shell are not '
            "held by the System yet)",
        )

    def reset_triads(self) -> None:
        """No nodal frames: nothing to reset."""

    def to_model(self, x: ArrayLike) -> NDArray:
        """A vector on the body's coordinates (:class:`~rancf.bodies.shell.ShellBody`'s
        numbering) in the model's numbering."""
        x = np.asarray(x)
        out = np.empty_like(x)
        out[self.dof_perm] = x
        return out

    def to_body(self, q: ArrayLike) -> NDArray[np.float64]:
        """Full coordinates ``(..., n)`` in the model's numbering in the body's."""
        return np.asarray(q, dtype=float)[..., self.dof_perm]

    def shape_row(self, at: ArrayLike) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """:meth:`ShellBody.shape_row <rancf.bodies.shell.ShellBody.shape_row>` of the point
        ``at`` with the model's coordinate indices."""
        idx, f = self.body.shape_row(at)
        return self.dof_perm[idx], f

    def positions(self, y: ArrayLike, at: ArrayLike) -> NDArray[np.float64]:
        """The point ``at = [u, v]`` at model coordinates ``y`` (a ``position`` sensor)."""
        return self.body.position(at, self.to_body(self.q_from_y(np.asarray(y, dtype=float))))


def shell_point(system: Any, spec: Any) -> tuple[str, tuple[float, float]] | None:
    """The shell body and surface point ``(u, v)`` of a place ``spec`` of ``system``: ``[u, v]``
    (the system's only body a shell) or ``"BODY:u,v"`` (``BODY`` a shell); None for any other
    place (a node, a rigid body's point, the ground)."""
    shells = [n for n, b in zip(system.names, system.flex, strict=False) if b.family.surface]
    if not shells:
        return None
    name, at = (system.single, spec) if not isinstance(spec, str) else (None, spec)
    if isinstance(at, str):
        name, _, at = at.rpartition(":")
        name = name or system.single
        try:
            at = [float(x) for x in at.split(",")]
        except ValueError:
            return None
    if not isinstance(name, str) or name not in shells:
        return None
    if not isinstance(at, list | tuple) or len(at) != 2:
        return None
    u, v = (float(x) for x in at)
    if not (0.0 <= u <= 1.0 and 0.0 <= v <= 1.0):
        raise InputError("at", list(at), "a surface point [u, v] with 0 <= u, v <= 1")
    return name, (u, v)


def shell_reader(system: Any, spec: Any) -> Callable[[Any], NDArray] | None:
    """The ``position`` sensor of a shell's point ``spec`` (:func:`shell_point`) as a reader
    of blocks of rows (``blk[1]``: full coordinates ``(k, n)``, :mod:`rancf.system.sensors`):
    the point's shape-function row applied to its coordinates; None for any other place."""
    on_shell = shell_point(system, spec)
    if on_shell is None:
        return None
    name, uv = on_shell
    idx, f = system.bodies[name].shape_row(uv)
    cols = system.offsets[name] + idx
    return lambda blk: np.einsum("k,rkc->rc", f, blk[1][:, cols])


def unstable_shells(shells: Sequence[str], count: int, low: complex) -> str:
    """The line of :func:`rancf.solvers.static_checks.instability` for a system with the shells
    ``shells`` whose tangent has ``count`` negative eigenvalues, the lowest ``low``."""
    return (
        f"unstable equilibrium: the tangent stiffness has {count} negative eigenvalue(s) on the "
        f"constraints' null space (lowest λ = ω² = {low.real:.4g} 1/s²), with the shell(s) "
        f"{', '.join(map(repr, shells))}: the state is past a buckling load; try more load "
        'steps or solver.static_method = "arc_length"'
    )
