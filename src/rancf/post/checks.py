"""Warnings for likely unit mistakes: the run goes on, the warning is one line on standard error
and an entry of ``summary.json``'s ``"warnings"`` list.

* The largest axial strain over the stored states passes :data:`STRAIN_LIMIT` (10 %): e.g. a
  Young's modulus of 50 Pa meant as 50 MPa stretches a 1 m hose to several metres.
* The section's radius (``sqrt(A / π)`` for a section given by its area) exceeds
  :data:`RADIUS_LIMIT` (a tenth) of the body's reference length: e.g. 10 m meant as 10 mm.
* A curve whose ends touch at a kink: it is an open curve (its ends are not joined), which a
  user who meant a ring should know (:attr:`rancf.mesh.mesh.CableMesh.notes`).
* Contact set up wrongly (:mod:`rancf.post.contact_checks`): a body that starts deep inside an
  obstacle, a frictional wrap with too few elements.
* An output interval that is not a whole number of fixed steps (:func:`step_warnings`): the run
  takes shorter steps of one size that divides the interval
  (:meth:`~rancf.options.DynamicOptions.fitted`; ``output_step = 1.5e-3`` with ``step =
  1e-3``: steps of 7.5e-4 s, 1333 a second instead of 1000).
* A body whose strain leaves its ``axial_law`` table (:func:`axial_law_warnings`): the tension
  beyond the table's last row is its linear extrapolation.
* An impulsive start of a dynamic run (:attr:`System.start_warnings`,
  :mod:`rancf.scenario.motions`): a prescribed rate, value or load that jumps at ``t = 0``.

The axial strain is the elements' own Green–Lagrange measure at the section sample points
(:class:`rancf.bodies.section_outputs.SectionSampler`: the compiled core's strain, at
``ξ = 0, 1/4, 1/2, 3/4`` of every element and the last node); a run's outputs track it as they
are written (:class:`rancf.system.outputs.SystemOutputs`), so checking it costs nothing extra.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.section_outputs import SectionSampler
from rancf.options import DynamicOptions
from rancf.post.contact_checks import contact_warnings
from rancf.post.energy_check import energy_warnings
from rancf.post.winch_checks import winch_warnings
from rancf.system import System, as_system
from rancf.system.energy_track import EnergyTrack

__all__ = [
    "STRAIN_LIMIT",
    "RADIUS_LIMIT",
    "section_warnings",
    "element_notes",
    "step_warnings",
    "error_warnings",
    "strain_warning",
    "axial_law_warnings",
    "largest_strain",
    "largest_stretch",
    "run_warnings",
    "before_run_warnings",
    "finished_warnings",
    "start_warnings",
    "at_time",
    "at_load_factor",
]

#: Largest axial strain (magnitude) that passes without a warning.
STRAIN_LIMIT = 0.10
#: Largest section radius, as a fraction of the body's reference length, without a warning.
RADIUS_LIMIT = 0.1


def section_warnings(model: Model | System) -> list[str]:
    """The geometry's remarks (:attr:`rancf.mesh.mesh.CableMesh.notes`, e.g. ends that touch at
    a kink: an open curve) and a warning if the section's radius exceeds a tenth of the body's
    reference length (every flexible body of a system, named)."""
    if isinstance(model, System):
        return (
            [
                f"{name}: {w}"
                for name, b in zip(model.names, model.flex, strict=False)
                if not b.family.surface  # a line's section (a shell has a thickness)
                for w in section_warnings(b)
            ]
            + _crossing_warnings(model)
            + contact_warnings(model)
            + winch_warnings(model)
        )
    notes = list(
        model.notes
    )  # remarks on the geometry (ends that touch at a kink; C² nodes kept C¹)
    r = model.section.radius
    length = float(SectionSampler(model, 1).s[-1])  # the reference arc length
    if r <= RADIUS_LIMIT * length:
        return notes
    return notes + [
        f"the section's radius {r:.4g} m is more than a tenth of the body's length "
        f"{length:.4g} m: check the units of section.radius or section.area (metres)"
    ]


#: The note on a curved spatial cable (printed by ``rancf static`` and ``simulate``; ``rancf
#: modes`` prints its own where the zero-frequency modes show it).
CURVED_CABLE_NOTE = (
    "note: a cable element on a curved spatial route bends with the magnitude of its curvature: "
    "it resists no out-of-plane bending about its curved reference, and a bend past straight "
    "(the curvature reversed, in the plane too) stores the energy of the mirror bend, far too "
    'little; where that matters, use mesh.element = "rod" (torsion, out-of-plane bending and '
    "the curvature's sign; docs/guide/rods.md)"
)


def element_notes(model: Model | System) -> list[str]:
    """The note :data:`CURVED_CABLE_NOTE` for every spatial cable body whose stress-free reference
    is curved (nodal tangents not all parallel): its bending energy
    ``½ EI (|κ| - |κ0|)²`` (docs/derivations/cable.md sec. 6) has no stiffness against turning
    the plane of the curvature and cannot tell a curvature reversed through straight from the
    reference's (a planar motion bent past straight is far too soft), which the rod element
    resists; and the note of a spatial cable that ``stress_free = "auto"`` unloaded straight
    (:func:`rancf.bodies.stress_free.resolve_stress_free`; every flexible body of a system,
    named)."""
    if isinstance(model, System):
        return [
            f"{name}: {n}"
            for name, b in zip(model.names, model.flex, strict=False)
            if not b.family.surface
            for n in element_notes(b)
        ]
    from rancf.solvers.curved_cable import curved_spatial_cable

    if curved_spatial_cable(model):
        return [CURVED_CABLE_NOTE]
    return [] if model.stress_free_note is None else [f"note: {model.stress_free_note}"]


def _crossing_warnings(system: System) -> list[str]:
    """Bodies in contact with each other whose contact points lie more than 4 tube radii apart:
    two tubes crossing at a large angle can pass through each other between them
    (docs/guide/contact.md)."""
    out = []
    for name in sorted({x for pair in system.body_contacts for x in pair}):
        b = system.bodies[name]
        r = b.section.radius  # type: ignore[union-attr]
        longest = float(np.max(b.mesh.arc_lengths()))  # type: ignore[union-attr]
        apart = longest / system.contact_points
        if apart > 4.0 * r:
            need = int(np.ceil(longest / r))
            out.append(
                f"{name}: contact points up to {apart / r:.3g} tube radii apart: tubes crossing "
                f"at a large angle can pass through each other between them; give "
                f"contact_points = {min(need, 64)} (an element's length over the radius)"
                + ("" if need <= 64 else " and shorter elements")
            )
    return out


def strain_warning(strain: float, when: str) -> str | None:
    """The warning for a largest axial strain ``strain`` reached ``when`` (None below 10 %)."""
    if not strain > STRAIN_LIMIT:  # NaN (a diverged state) says nothing about units
        return None
    return (
        f"the largest axial strain is {100.0 * strain:.4g} % ({when}), more than "
        f"{100.0 * STRAIN_LIMIT:g} %: check the units of material.youngs_modulus (Pa), the "
        "section (m) and the loads (N)"
    )


def at_time(t: float) -> str:
    """``at t = 0.5 s``."""
    return f"at t = {t:g} s"


def at_load_factor(lam: float) -> str:
    """``at load factor λ = 1``."""
    return f"at load factor λ = {lam:g}"


def step_warnings(options: DynamicOptions) -> list[str]:
    """A warning if fixed steps do not fit the output interval: ``output_step / step`` is above
    1 and not a whole number (within 1e-9), so the steps taken are shorter than ``step``
    (:meth:`~rancf.options.DynamicOptions.fitted`).  (An interval below the step makes every
    step the interval: constant, no warning.)"""
    n = options.steps_per_output
    if n is None:
        return []
    out, h = options.output_step, options.step
    fit = round(out / h) * h  # type: ignore[operator]
    return [
        f"solver.output_step = {out:g} s is not a whole number of steps (solver.step = {h:g} s): "
        f"the run takes steps of {options.fitted().step:.6g} s, {n} an output interval; "
        f"output_step = {fit:g} s keeps the step"
    ]


def error_warnings(result: Any, options: DynamicOptions) -> list[str]:
    """A warning if a run's largest local error estimate (relative to ``rtol * size``,
    :class:`~rancf.solvers.result.DynamicResult`) is above 1: where, the step and a step that
    would meet the tolerance there (TI.10 of ``docs/derivations/time-integration.md``)."""
    err, h = result.error_estimate, result.error_step
    if not err > 1.0 or h is None:
        return []
    better = h * 0.9 * err ** (-1.0 / 3.0)
    how = (
        "adaptive steps could not meet it"
        if options.adaptive
        else f"a step of about {better:.3g} s meets it there, or set solver.adaptive = true"
    )
    return [
        f"the local error estimate is {err:.3g} times solver.rtol = {options.rtol:g} (of the "
        f"model's size) at t = {result.error_time:.6g} s with a step of {h:.3g} s: the step does "
        f"not resolve the motion there (an impulsive start or a fast vibration); {how}"
    ]


def run_warnings(
    model: Model | System,
    t: NDArray | None = None,
    q: NDArray | None = None,
    static: bool = False,
    largest: tuple[float, float] | None = None,
    options: DynamicOptions | None = None,
    by_body: Mapping[str, float] | None = None,
) -> list[str]:
    """Every warning of a run: its impulsive starts (a dynamic run's), the section's radius, the
    steps against the output interval (``options``, a dynamic run's), and the largest axial
    strain — ``largest = (strain, t)`` as a :class:`~rancf.system.outputs.SystemOutputs` tracked
    it, or of a model's states ``q (n_t, n)`` at times (or load factors, ``static``) ``t``; and
    the bodies whose largest strain ``by_body`` (their names to their largest Green–Lagrange
    strains) leaves their ``axial_law`` table (:func:`axial_law_warnings`)."""
    if largest is None:
        largest = (0.0, 0.0)
        if not isinstance(model, System) and q is not None and np.size(q):
            qq = np.atleast_2d(q)
            tt = np.zeros(len(qq)) if t is None else np.atleast_1d(t)
            largest = largest_strain(model, tt, qq)
    strain = strain_warning(largest[0], (at_load_factor if static else at_time)(largest[1]))
    if options is not None and not static:
        first = before_run_warnings(model, options)
    else:
        first = ([] if static else start_warnings(model)) + section_warnings(model)
    return first + ([strain] if strain else []) + axial_law_warnings(model, by_body or {})


def axial_law_warnings(model: Model | System, by_body: Mapping[str, float]) -> list[str]:
    """One line per body with an axial law whose largest Green–Lagrange strain ``by_body[name]``
    (the name ``""``: a model's) has an engineering strain ``sqrt(1 + 2 ε) − 1`` beyond its
    table's last row (:meth:`~rancf.bodies.axial_law.AxialLaw.leaves_table`)."""
    pairs = zip(model.names, model.flex, strict=False) if isinstance(model, System) else []
    out = []
    for name, body in pairs if isinstance(model, System) else [("", model)]:
        law = (
            body.material.axial_law if isinstance(body, Model) and not body.family.surface else None
        )
        g = by_body.get(name)
        line = "" if law is None or g is None else law.leaves_table(math.sqrt(1.0 + 2.0 * g) - 1.0)
        if line:
            out.append(f"body {name!r}: {line}" if name else line)
    return out


def before_run_warnings(model: Model | System, options: DynamicOptions) -> list[str]:
    """The warnings a dynamic run can give before it starts, in :func:`run_warnings`' order:
    its impulsive starts, the section's radius and the steps against the output interval."""
    return start_warnings(model) + section_warnings(model) + step_warnings(options)


def finished_warnings(
    model: Model | System,
    largest: tuple[float, float],
    result: Any,
    options: DynamicOptions,
    by_body: Mapping[str, float] | None = None,
    energy: EnergyTrack | None = None,
) -> list[str]:
    """Every warning of a finished dynamic run: :func:`run_warnings` (``largest`` as its outputs
    tracked it) and, for a completed run, the steps whose error estimate passed the tolerance
    (:func:`error_warnings`; a failed or stopped run says so instead), and the rise of its
    ``energy`` where nothing does work on it (:func:`~rancf.post.energy_check.energy_warnings`);
    ``by_body``: as :func:`run_warnings`'."""
    found = run_warnings(model, largest=largest, options=options, by_body=by_body)
    done = result.status.value == "completed"
    rise = energy_warnings(as_system(model), energy, result, options)
    return found + (error_warnings(result, options) if done else []) + rise


def start_warnings(model: Model | System) -> list[str]:
    """The impulsive starts of a system built from a scenario (:attr:`System.start_warnings`;
    none for a model)."""
    return list(getattr(model, "start_warnings", ()))


def largest_strain(model: Model, t: NDArray, q: NDArray) -> tuple[float, float]:
    """The largest ``|ε|`` of the states ``q (n_t, n)`` at the section sample points (the
    elements' own strain, :class:`~rancf.bodies.section_outputs.SectionSampler`) and its ``t``."""
    sampler = SectionSampler(model)
    best = (0.0, 0.0)
    for tt, qq in zip(t, q, strict=True):
        eps = float(np.max(np.abs(sampler.values(model.y_from_q(qq))[:, 0])))
        if eps > best[0]:
            best = (eps, float(tt))
    return best


def largest_stretch(model: Model, q: NDArray) -> float:
    """The largest (signed) Green–Lagrange strain of the state ``q`` (full coordinates) at the
    section sample points: the most stretched point (:func:`axial_law_warnings`)."""
    return float(np.max(SectionSampler(model).values(model.y_from_q(q))[:, 0]))
