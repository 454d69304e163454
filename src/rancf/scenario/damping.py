"""``[damping]``: Rayleigh damping (``mass_proportional``, ``stiffness_proportional``) and
Kelvin-Voigt strain-rate damping (``axial``, ``bending``, ``torsion``) of the flexible bodies, and
a flexible body's own ``[bodies.damping]`` (the strain-rate keys;
docs/derivations/strain-rate-damping.md)."""

from __future__ import annotations

from pydantic import Field

from rancf.scenario.base import NonNegative, Table

__all__ = ["StrainRateDampingTable", "DampingTable"]


class StrainRateDampingTable(Table):
    """``[bodies.damping]``: Kelvin-Voigt strain-rate damping of one flexible body (the keys of
    ``[damping]`` that a body may have of its own; docs/derivations/strain-rate-damping.md).

    The section forces get parts proportional to the strain rates; rigid motions are not damped,
    statics ignore them.  A mode of frequency ``ω`` dominated by stretching (bending) decays with
    the damping ratio ``ζ = axial ω / (2 EA)`` (``ζ = bending ω / (2 EI)``).  MoorDyn's ``BA`` is
    ``axial``; its negative form ``BA = −ζ`` is ``axial = ζ (L/N) √(EA m)`` (``m`` the mass per
    length, ``L/N`` MoorDyn's segment length).  Every element; ``torsion`` rods only.
    """

    axial: NonNegative = Field(
        0.0,
        description="c_a in the tension N = EA eps + c_a d(eps)/dt [N s] (MoorDyn's BA): "
        "a stretching mode of frequency omega decays with zeta = c_a omega / (2 EA)",
    )
    bending: NonNegative = Field(
        0.0,
        description="c_b in the bending moment M = EI kappa + c_b d(kappa)/dt [N m^2 s]: a "
        "bending mode of frequency omega decays with zeta = c_b omega / (2 EI)",
    )
    torsion: NonNegative = Field(
        0.0,
        description="rod elements: c_t in the twist moment GJ tau + c_t d(tau)/dt [N m^2 s]: "
        "a torsion mode of frequency omega decays with zeta = c_t omega / (2 GJ); refused on the "
        "other elements",
    )


class DampingTable(StrainRateDampingTable):
    """``[damping]``: Rayleigh damping of the flexible bodies, ``C = c M + β K_T``, and their
    Kelvin-Voigt strain-rate damping ``axial``, ``bending``, ``torsion``
    (:class:`StrainRateDampingTable`; a body's own ``[bodies.damping]`` replaces these three)."""

    mass_proportional: NonNegative = Field(0.0, description="c in C = c M [1/s]")
    stiffness_proportional: NonNegative = Field(
        0.0, description="beta in C = beta K_T [s] (K_T the tangent stiffness at the state)"
    )
