"""Quantities derived from a system's stored states: accelerations, multipliers, reactions of
supports and joints, section values and sensors.

A run stores its states ``(t, q, v)`` (rods also the nodal directors ``m1``, which the
coordinates alone do not fix).  :class:`SystemOutputs` turns rows of them into

* the consistent accelerations and multipliers, the solution of
  ``[M Gᵀ; G 0] [a; λ] = [f_ext - f_int - g - c M v; -γ]`` with the prescribed coordinates'
  accelerations given (the compiled core's ``initial_acceleration``: the same assembly the
  integrator uses, so supports moving by a time function are included);
* the reactions of the supports (:mod:`rancf.bodies.reactions`): the held rows of the residual
  ``M a + g + c M v + f_int - f_ext + Gᵀ λ``;
* the reactions of the joints: the resultant force and moment the joint exerts on its first
  place, the least-squares resultant of the generalized forces ``-G_Aᵀ λ`` on that place's
  coordinates (``src/cpp/system/system_outputs.cpp``);
* the section values of every flexible body (:mod:`rancf.bodies.section_outputs`);
* the sensors (:mod:`rancf.system.sensors`).

Static rows (a load path, ``t`` the path parameter) have ``a = v = 0``, the residual
``f_int - p f_ext + Gᵀ λ`` at the load factor ``p = min(t, 1)`` (loads at their amplitude, as
:func:`rancf.solvers.static.solve_static` takes them) and the solver's multipliers.

Why not the integrator's own accelerations: its algorithmic ``w_{n+1}`` approximates the
acceleration at ``t_{n+1} + (α_m - α_f) h`` (Arnold & Brüls 2007), a first-order shift for
``ρ∞ < 1``; its ``a_{n+1}`` satisfies the balance at ``t_{n+1}`` to the Newton tolerance only,
and a row needs the force pass at its ``(y, v)`` anyway (the reactions, the nodal axial
forces), after which the consistent acceleration costs one band solve more (a fraction of a
row's time: ``docs/guide/performance.md``).

Contact is the exception: a penalty vibrates far faster than any step resolves, the integrator
damps that vibration, and the state at a step's end samples it (the unbraked belt drive's pulley,
pushed by 20 N, read 16.4 to 18.5 N there).  A dynamic row's contact forces are therefore those
of the step that ended at it, as the dynamics applied them: at the step's generalized-α point
``(y_f, v_f)`` with the step's mean pressure (``alpha`` of :meth:`SystemOutputs.rows`, the
stream the integrator stores), and the row's accelerations, multipliers and reactions are the
consistent ones with those contact forces, so every body's forces balance ``M a``.  Contact
between flexible bodies is reported at ``y_f`` with the pressure there.

Column names: each Part names its own (:meth:`rancf.system.part.Part.sensors`), in the order of
:attr:`rancf.system.system.System.parts`: a support's ``LABEL_fx, LABEL_fy[, LABEL_fz]`` then
its moment (``LABEL_mz`` or ``LABEL_mx, _my, _mz``; the label is the support's place as the
caller wrote it, else ``BODY:AT``); a joint's ``NAME_fx ...`` and, for joints that transmit a
moment (``fixed``, a 3D ``revolute``, a driven joint), ``NAME_mz`` or ``NAME_mx, _my, _mz``,
and for a ``sliding`` joint the arc length ``NAME_s`` [m] of the body's point at its place
(:mod:`rancf.system.sliding`); then every obstacle's
(:func:`rancf.system.contact_states.contact_outputs`): the force it exerts on the bodies,
``NAME_normal_x, _y[, _z]`` and ``NAME_friction_x, _y[, _z]`` [N], their moment, the contact
length ``NAME_length`` [m] and the largest penetration ``NAME_penetration`` [m]; then every
pair of flexible bodies in contact (``body_contacts``, ``A_B_...``; ``A_A_...``
self-contact): the total contact force ``A_B_contact_force`` [N] (the sum of the pressures'
magnitudes) and the largest penetration ``A_B_penetration`` [m].
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.nodal_forces import recovers_axial_force
from rancf.bodies.reactions import Reaction, reaction_row, support_reactions
from rancf.bodies.section_outputs import SectionSampler, section_names
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, evaluator
from rancf.system.energy_track import EnergyTrack
from rancf.system.output_block import (
    block_derived,
    block_sections,
    contact_row,
    rod_triads,
    takes_block,
)
from rancf.system.output_columns import part_columns, support_labels
from rancf.system.parts.flexible import FlexibleBody
from rancf.system.seabed_friction import static_friction_load
from rancf.system.sensors import SensorReader
from rancf.system.sliding import sliding_slots
from rancf.system.static_residual import static_residual
from rancf.system.system import System

__all__ = ["SystemOutputs"]


class SystemOutputs:
    """Accelerations, multipliers, reactions, section values and sensors of rows of states.

    Parameters
    ----------
    system : System
    sensors : sequence of sensor records
        Each with ``name``, ``kind``, ``places``, ``joint``, ``body``, ``about`` and
        ``columns(dim)`` (:mod:`rancf.system.sensors`).
    labels : mapping body name -> list, optional
        The supports' ``at`` as the user wrote it, per flexible body.
    per_element : int
        Section sample points per element.
    """

    def __init__(
        self,
        system: System,
        sensors: Sequence[Any] = (),
        labels: Mapping[str, Sequence[int | str]] | None = None,
        per_element: int = 4,
    ) -> None:
        self.system = s = system
        bodies = list(zip(s.names, s.flex, strict=False))
        #: The line bodies (section values along them) and the shells (sensors, surfaces).
        self.flex = [(name, b) for name, b in bodies if not b.family.surface]
        self.shells = [(name, b) for name, b in bodies if b.family.surface]
        self.labels = support_labels(s, labels)
        self.samplers = {name: SectionSampler(b, per_element) for name, b in self.flex}
        winched = set()
        if getattr(s, "winches", ()):
            from rancf.system.winches import winch_node

            winched = {winch_node(s, w)[0] for w in s.winches}
        #: The flexible bodies whose axial force is read from their nodal forces.
        self.recovered = {
            name for name, b in self.flex if recovers_axial_force(b) and name not in winched
        }
        self.section_names = {name: section_names(b) for name, b in self.flex}
        #: Every part with output columns and its columns (its :meth:`~rancf.system.part.
        #: Part.sensors`), in order: the reaction columns are theirs.
        self.part_columns = part_columns(s, self.labels)
        cols = {id(p): c for p, c in self.part_columns}
        self.support_names = {
            p.name: [c for sup in p.supports(self.labels[p.name]) for c in sup.sensors(s)]
            for p in s.body_parts
            if isinstance(p, FlexibleBody)
        }
        self.joint_names = [cols[id(j)] for j in s.joints]
        self.reaction_names = [x for _, c in self.part_columns for x in c]
        self.contact_start = sum(len(c) for c in self.support_names.values())
        self.contact_start += sum(len(c) for c in self.joint_names)
        self.along_widths = {
            n: sp.n_points * len(self.section_names[n]) for n, sp in self.samplers.items()
        }
        self.sensors = SensorReader(self, sensors)
        self.sensor_names = self.sensors.names
        #: The core's integrator of the system, for the rows' consistent accelerations.
        self.integrator = evaluator(s.core, s.damping)
        #: The largest |axial strain| of the rows seen so far, and the ``t`` of its row.
        self.largest_strain: tuple[float, float] = (0.0, 0.0)
        #: Every flexible body's largest axial strain (signed: the most stretched) so far.
        self.largest_by_body: dict[str, float] = {}
        self.energy = EnergyTrack()  #: the stored rows' energies (fed by the run's sink)
        #: One flexible body, nothing else with energy: its energies are the system's (stored).
        others = s.rigid or s.springs or s.has_contact or getattr(s, "winches", ())
        self._body_is_system = len(s.flex) == 1 and not others

    # ------------------------------------------------------------------ sizes
    @property
    def n_q(self) -> int:
        """Coordinates of a state."""
        return self.system.n

    @property
    def n_directors(self) -> int:
        """Numbers of a row's rod directors (3 a rod node)."""
        return 3 * sum(b.n_nodes for _, b in self.flex if b.family.has_triads)

    @property
    def n_along(self) -> int:
        """Section values of a row (every flexible body's, flattened)."""
        return sum(self.along_widths.values())

    def joint_columns(self, name: str) -> slice:
        """The reaction columns of the joint called ``name``."""
        start = sum(len(c) for c in self.support_names.values())
        for j, cols in zip(self.system.joints, self.joint_names, strict=True):
            if j.label(self.system) == name:
                return slice(start, start + len(cols))
            start += len(cols)
        raise KeyError(name)

    # ------------------------------------------------------------------ rows
    def rows(
        self,
        t: NDArray,
        q: NDArray,
        v: NDArray | None = None,
        directors: NDArray | None = None,
        energy: NDArray | None = None,
        lam: NDArray | None = None,
        static: bool = False,
        per_body: bool = False,
        alpha: NDArray | None = None,
    ) -> dict[str, NDArray[np.float64]]:
        """Derived values of ``k`` rows: ``"a"`` ``(k, n_q)`` (full coordinates), ``"lam"``
        ``(k, m)``, ``"r"`` reactions ``(k, n_reaction_columns)``, ``"s"`` section values
        ``(k, n_along)`` and ``"c"`` sensors ``(k, n_sensor_columns)``.  ``directors``: rods'
        nodal ``m1`` ``(k, n_directors)``; ``energy`` ``(k, 3)`` (for ``energy`` sensors);
        ``lam``: the multipliers of static rows (their solver's); ``per_body``: also ``"eb"``,
        every flexible body's kinetic, strain and gravitational energy ``(k, 3 n_flexible)``;
        ``alpha``: the generalized-α point ``(y_f, v_f)`` of the step that ended at each
        dynamic row ``(k, 2 n)`` (:data:`rancf.solvers.output.STREAMS`): the contact forces are
        then that step's (module docstring)."""
        s = self.system
        t = np.atleast_1d(np.asarray(t, dtype=float))
        k = t.size
        q = np.asarray(q, dtype=float).reshape(k, -1)
        out = {
            "a": np.zeros((k, s.n)),
            "lam": np.zeros((k, s.m)),
            "r": np.empty((k, len(self.reaction_names))),
            "s": np.empty((k, self.n_along)),
            "eb": np.empty((k, 3 * len(s.flex) if per_body else 0)),
        }
        res, res0, no_lam = np.empty(s.n + s.m), np.empty(s.n + s.m), np.zeros(s.m)
        raws: dict[str, list[NDArray]] = {name: [] for name, _ in self.flex}
        nodal: dict[str, list[NDArray]] = {name: [] for name, _ in self.flex}
        factors: dict[str, list[float]] = {name: [] for name, _ in self.flex}
        # without rods' triads or sliding joints a block's dynamic rows go through the core
        ys = s.y_from_q(q) if takes_block(s, static, directors, k) else None
        if ys is not None:
            vs = np.zeros_like(ys) if v is None else s.y_from_q(np.reshape(v, (k, -1)))
            own, internal = block_derived(self, t, ys, vs, out, alpha)
            block_sections(self, raws, factors, ys, t, nodal, own, internal)
        if per_body and energy is not None and self._body_is_system and not static:
            out["eb"], per_body = np.array(energy, dtype=float).reshape(k, 3), False
        elif per_body and ys is not None:  # the block's bodies' energies in one call
            s.core.body_energies_rows(
                np.ascontiguousarray(t),
                np.ascontiguousarray(ys),
                np.ascontiguousarray(vs),
                out["eb"],
            )
            per_body = False
        with rod_triads(s, self.flex) as set_row:
            for i in range(k if ys is None else 0):
                y = s.y_from_q(q[i])
                if directors is not None:
                    set_row(y, np.asarray(directors[i]).ravel())
                vy = np.zeros(s.n) if v is None or static else s.y_from_q(v[i])
                a, li = np.zeros(s.n), sliding_slots(s, y, None if lam is None else lam[i])
                if static:
                    if lam is not None:
                        li[:] = lam[i]
                    at = ResidualOptions(0.0, min(float(t[i]), 1.0), True, dynamic=False)
                    static_residual(s, y, li, res, at)
                    s.core.residual(
                        ResidualPoint(y, no_lam, res0), replace(at, distributed_only=True)
                    )
                    if (fr := static_friction_load(s, y)) is not None:  # the seabeds' friction
                        res[: s.n] -= fr
                        res0[: s.n] -= fr
                    step: tuple[NDArray, ...] = ()
                else:
                    step = self._step(alpha, i, y, vy)
                    self.integrator.initial_acceleration(y, vy, float(t[i]), a, li, *step)
                    at = ResidualOptions(float(t[i]))
                    s.core.residual(ResidualPoint(y, li, res, vy, a, *step), at)
                    s.core.residual(
                        ResidualPoint(y, no_lam, res0, vy, a, *step),
                        replace(at, distributed_only=True),
                    )
                out["a"][i], out["lam"][i] = s.q_from_y(a), li
                vc = None if static else vy  # friction from the velocities
                out["r"][i] = self._reactions(y, res[: s.n], float(t[i]), li, vc, step)
                block_sections(self, raws, factors, y[None], t[i : i + 1], nodal, res0[None])
                if per_body:
                    out["eb"][i] = self._body_energies(y, vy, float(t[i]))
        if k:
            out["s"] = self._along(raws, factors, t, nodal)
        out["c"] = self.sensors.values(t, q, v, out, energy)
        return out

    def contact_columns(self, name: str) -> slice:
        """The columns of the obstacle called ``name`` (normal, friction, moment, length,
        penetration)."""
        start = self.contact_start
        for ob, oname in zip(self.system.obstacles, self.system.obstacle_names, strict=True):
            w = len(ob.sensors(self.system))
            if oname == name:
                return slice(start, start + w)
            start += w
        raise ValueError(name)

    def static_reactions(
        self, y: NDArray, lam: NDArray, load_factor: float = 1.0
    ) -> list[Reaction]:
        """The reactions of every support and joint at a static state (model coordinates ``y``,
        the solver's multipliers ``lam``, the loads at ``load_factor`` times their amplitude):
        the supports of each flexible body in file order, then the joints (``at`` their name);
        a moment where the support or joint transmits one."""
        s = self.system
        y = np.asarray(y, dtype=float)
        lam = np.asarray(lam, dtype=float)
        res = np.empty(s.n + s.m)
        at = ResidualOptions(0.0, float(load_factor), amplitude=True, dynamic=False)
        static_residual(s, y, lam, res, at)
        if (fr := static_friction_load(s, y)) is not None:
            res[: s.n] -= fr
        return self.reactions(y, res[: s.n], 0.0, lam)

    def reactions(self, y: NDArray, res: NDArray, t: float, lam: NDArray) -> list[Reaction]:
        """The reactions of the supports (the held rows of the balance residual ``res``) and of
        the joints (their multipliers ``lam``) at ``y``, ``t``: :meth:`static_reactions`."""
        s = self.system
        out: list[Reaction] = []
        for name, b in self.flex:
            sl = s.body_slice(name)
            out += support_reactions(b, y[sl], res[sl], self.labels[name])
        for k, j in enumerate(s.joints):
            force, moment = s.core.joint_reaction(k, y, t, lam)
            mom, extra = None, None
            if j.transmits_moment(s.dim):
                mom = np.asarray(moment)[2:] if s.dim == 2 else np.asarray(moment)
            if more := j.entry.values(s, k, y, lam):
                extra = np.array(more)
            out.append(Reaction(j.name or f"joint{k}", np.asarray(force)[: s.dim], mom, extra))
        return out

    def _step(self, alpha: NDArray | None, i: int, y: NDArray, v: NDArray) -> tuple[NDArray, ...]:
        """The contact state ``(y_f, v_f, y_1)`` of dynamic row ``i``'s step (none without
        contact; the row's own state without ``alpha``: a step of length zero)."""
        s = self.system
        if not s.has_contact:
            return ()
        if alpha is None:
            return (y, v, y)
        row = np.ascontiguousarray(alpha[i], dtype=float)
        return (row[: s.n], row[s.n :], y)

    def _reactions(
        self,
        y: NDArray,
        res: NDArray,
        t: float,
        lam: NDArray,
        v: NDArray | None = None,
        step: tuple[NDArray, ...] = (),
    ) -> NDArray:
        s = self.system
        yc, vc, y1 = step if step else (y, v, None)
        return np.concatenate(
            [reaction_row(self.reactions(y, res, t, lam)), contact_row(s, yc, vc, y1)]
        )

    def _body_energies(self, y: NDArray, v: NDArray, t: float) -> NDArray:
        """Every flexible body's kinetic, strain and gravitational energy at time ``t`` (a
        winch's body at its length at ``t``), by the core."""
        out = np.empty(3 * len(self.system.flex))
        self.system.core.body_energies(
            np.ascontiguousarray(y), np.ascontiguousarray(v), float(t), out
        )
        return out

    def _along(
        self,
        raws: dict[str, list[NDArray]],
        stretch: dict[str, list[float]],
        t: NDArray,
        nodal: dict[str, list[NDArray]],
    ) -> NDArray:
        """Section values ``(k, n_along)`` of k rows from their strains and curvatures and
        their bodies' length factors (:func:`~rancf.system.winches.winch_factor`); the axial
        force from the nodal forces ``nodal`` where given (:mod:`rancf.bodies.nodal_forces`)."""
        parts = []
        for name, _ in self.flex:
            factors = np.asarray(stretch[name], dtype=float)
            raw = raws[name][0] if len(raws[name]) == 1 else np.concatenate(raws[name])
            vals = self.samplers[name].from_raw(raw, factors[:, None, None])
            if nodal[name]:
                vals[:, :, 1] = self.samplers[name].between_nodes(np.concatenate(nodal[name]))
            strain = np.max(np.abs(vals[:, :, 0]), axis=1)
            strain[np.isnan(strain)] = -np.inf  # NaN (a diverged state) is never larger
            i = int(np.argmax(strain)) if strain.size else 0  # the first of equal ones
            if strain.size and strain[i] > self.largest_strain[0]:
                self.largest_strain = (float(strain[i]), float(t[i]))
            stretched = np.nan_to_num(vals[:, :, 0], nan=-np.inf).max(initial=-np.inf)
            self.largest_by_body[name] = max(self.largest_by_body.get(name, -np.inf), stretched)
            parts.append(vals.reshape(vals.shape[0], -1))
        if len(parts) == 1:  # one body: no copy
            return parts[0]
        return np.concatenate(parts, axis=1) if parts else np.empty((t.size, 0))

    def body_along(self, along: NDArray, name: str) -> NDArray[np.float64]:
        """One flexible body's section values ``(k, n_points, n_names)`` of rows ``along``."""
        start = 0
        for n, w in self.along_widths.items():
            if n == name:
                cut = np.asarray(along)[:, start : start + w]
                return cut.reshape(cut.shape[0], -1, len(self.section_names[name]))
            start += w
        raise KeyError(name)
