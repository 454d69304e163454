"""The energy check of a dynamic run in which nothing does work on the system.

Where no force outside the stored energies does work (no point or distributed loads, no fluid,
no prescribed motion of a support, joint or winch: :func:`work_done_by`), the total energy
``E = K + U_strain + U_gravity`` (contact and spring energies in ``U_strain``) of the stored
states can only stay (no damping) or fall (material, Rayleigh, contact damping, friction, the
integrator's ``rho_inf < 1``).  A rise is the integrator's error, and a large one is an
instability: a stiff line stepped far beyond its axial period gains energy every step, until
the bob of a pendulum flies off a kilometre while the run reports it completed.

The rise is measured against ``S = K_0 + |U_strain,0| + (max U_gravity - min U_gravity)``, the
first stored state's kinetic and strain energies and the range of the gravity's over the run
(:class:`~rancf.system.energy_track.EnergyTrack`), which bounds every energy of a motion that
nothing does work on:

* above :data:`ENERGY_BLOW_UP` of ``S`` the run is an error (its status ``failed``, exit
  status 3 of ``rancf simulate``), one line naming the energy, the time and the step and
  ``rho_inf`` to change (:func:`energy_failure`);
* above :data:`ENERGY_GROWTH` of ``S``, a warning line (:func:`energy_warnings`).

A rise below ``1e-9`` of the largest energy magnitude, or below ``1e-20`` of the model's energy
unit (:func:`energy_unit`), is round-off, never warned about.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rancf.options import DynamicOptions
from rancf.system.energy_track import EnergyTrack

__all__ = [
    "ENERGY_GROWTH",
    "ENERGY_BLOW_UP",
    "EnergyTrack",
    "work_done_by",
    "energy_unit",
    "energy_rise",
    "energy_failure",
    "energy_warnings",
]

#: Rise of the total energy, relative to the energy the motion has (``S``), above which a run
#: in which nothing does work is warned about.
ENERGY_GROWTH = 0.01
#: Rise above which such a run is an error (unstable).
ENERGY_BLOW_UP = 0.5
#: Rise, relative to the model's energy unit (:func:`energy_unit`), below which it is
#: round-off: a motion whose strains are below about 1e-10 (a clamped curved rod at rest,
#: 1e-27 J of the reference's round-off in its strain energy).
ENERGY_FLOOR = 1e-20
#: The start of the message of a run failed by the check.
UNSTABLE = "unstable: "
#: Rise, relative to the largest energy magnitude, below which it is round-off.
ENERGY_ROUND_OFF = 1e-9


def work_done_by(system: Any) -> str | None:
    """What does work on ``system`` beside the energies it stores (the first found, named as
    the scenario names it), or None where nothing does: then its energy may not grow."""
    found = [
        (bool(system.point_loads), "loads.point"),
        (any(b.point_loads for b in system.flex), "loads.point"),
        (system.fluid_part is not None, "[fluid]/[hydro]/[[loads.distributed]]"),
        (bool(system.winches), "winches"),
        (any(sup.held(system).motion is not None for sup in system.supports), "supports.motion"),
        (any(_driven(j) for j in system.joints), "a driven joint"),
    ]
    return next((name for hit, name in found if hit), None)


def _driven(joint: Any) -> bool:
    """A joint that moves its places by a time function (a motor's angle, a motion)."""
    return any(getattr(joint, k, None) is not None for k in ("angle", "motion", "rotation"))


def energy_unit(system: Any) -> float:
    """The model's energy unit [J]: ``ℓ Σ EA`` of its flexible bodies, ``ℓ |g| Σ m`` of its
    rigid bodies and point masses and ``ℓ² Σ k`` of its springs, ``ℓ`` the model's size (the
    work of stretching its bodies by 100 %, lifting its masses or stretching its springs by
    the model's size)."""
    size = float(system.size)
    flex = sum(float(b.props.ea) for b in system.flex)
    mass = sum(float(getattr(b, "mass", 0.0)) for b in system.bodies.values())
    springs = sum(float(getattr(sp, "stiffness", 0.0)) for sp in system.springs)
    g = float(np.linalg.norm(system.gravity))
    return size * flex + size * g * mass + size * size * springs


def energy_rise(track: EnergyTrack, unit: float = 0.0) -> float:
    """The rise of the total energy over its first row's, relative to the track's scale
    (0 below round-off: of the largest energy, or :data:`ENERGY_FLOOR` of the model's energy
    ``unit`` (:func:`energy_unit`); inf where the energy is not finite)."""
    rise = track.e_max - track.e0
    if not np.isfinite(rise):
        return np.inf if track.t0 < np.inf else 0.0
    floor = max(ENERGY_ROUND_OFF * track.magnitude, ENERGY_FLOOR * unit)
    if rise <= floor or rise <= 0.0:
        return 0.0
    return rise / track.scale if track.scale > 0.0 else np.inf


def _line(track: EnergyTrack, rise: float, options: DynamicOptions) -> str:
    """The words of the check: the energy's rise, where, and what to change."""
    what = (
        f"the total energy (kinetic + strain + gravity) rose from {track.e0:.4g} J at "
        f"t = {track.t0:.6g} s to {track.e_max:.4g} J at t = {track.t_max:.6g} s"
    )
    if np.isfinite(rise):
        what += f", {100 * rise:.3g} % of the energy the motion has ({track.scale:.4g} J)"
    return (
        f"{what}, while nothing does work on the system: the integrator gains energy; take a "
        f"smaller solver.step (now {options.step:g} s) or a smaller solver.rho_inf (now "
        f"{options.rho_inf:g}), or set solver.adaptive = true"
    )


def energy_failure(system: Any, track: EnergyTrack, result: Any, options: DynamicOptions) -> None:
    """Mark a completed ``result`` failed, with one line, where its energy rose by more than
    :data:`ENERGY_BLOW_UP` of its scale in a system nothing does work on."""
    if result.status.value != "completed" or work_done_by(system) is not None:
        return
    rise = energy_rise(track, energy_unit(system))
    if rise > ENERGY_BLOW_UP:
        from rancf.solvers.result import DynamicStatus

        result.status = DynamicStatus.FAILED
        result.message = UNSTABLE + _line(track, rise, options)


def energy_warnings(
    system: Any, track: EnergyTrack | None, result: Any, options: DynamicOptions
) -> list[str]:
    """A warning where a system nothing does work on gained more than :data:`ENERGY_GROWTH`
    of its scale: a completed ``result`` up to :data:`ENERGY_BLOW_UP` (above it the run failed,
    :func:`energy_failure`, and says so), a run that failed otherwise or stopped by any rise
    (it may tell why)."""
    if track is None or result.message.startswith(UNSTABLE) or work_done_by(system) is not None:
        return []
    rise = energy_rise(track, energy_unit(system))
    completed = result.status.value == "completed"
    if not rise > ENERGY_GROWTH or (completed and rise > ENERGY_BLOW_UP):
        return []
    return [_line(track, rise, options)]
