"""The parts of a model: cross-section, material, supports and point loads (frozen values)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from rancf.bodies.axial_law import AxialLaw
from rancf.bodies.families import framed
from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError

__all__ = ["Section", "Material", "Support", "PointLoad", "StrainRateDamping"]


def _positive(key: str, v: float | None, what: str = "a finite number > 0") -> None:
    if v is not None and not (np.isfinite(v) and v > 0):
        raise InputError(key, v, what)


@dataclass(frozen=True)
class Section:
    """Cross-section: area ``A``, second moments of area and (rods) torsion constant.

    ``inertia`` is ``I`` of a cable or beam; for a rod it is ``I_y``, about the first principal
    axis ``m1`` (set by ``orientation`` at the first node), and ``inertia_z`` (default
    ``inertia``) is about ``m2``.  ``torsion_constant`` ``J`` defaults to the polar moment
    ``I_y + I_z`` (exact for a circle).

    ``rotary_inertia`` (rods): ``"torsion"`` (default) gives the cross-sections the rotary
    inertia ``ρ I_p`` about the tangent (the spin); ``"full"`` adds ``ρ I`` about both bending
    axes (equal ``inertia`` and ``inertia_z`` only).  The bending part matters for thick sections
    and high frequencies: it lowers a bending frequency by about ``(k r)²/8`` relative for a wave
    number ``k`` (Rayleigh's correction), negligible for slender rods.
    """

    area: float
    inertia: float
    inertia_z: float | None = None
    torsion_constant: float | None = None
    orientation: tuple[float, float, float] | None = None
    rotary_inertia: Literal["torsion", "full"] = "torsion"

    def __post_init__(self) -> None:
        if self.rotary_inertia not in ("torsion", "full"):
            raise InputError("section.rotary_inertia", self.rotary_inertia, '"torsion" or "full"')
        for name in ("area", "inertia", "inertia_z", "torsion_constant"):
            _positive(f"section.{name}", getattr(self, name))
        if self.orientation is not None and (
            len(self.orientation) != 3 or not np.all(np.isfinite(self.orientation))
        ):
            raise InputError("section.orientation", list(self.orientation), "3 finite numbers")

    @classmethod
    def circular(cls, radius: float) -> Section:
        """Solid circular section: ``A = π r²``, ``I = π r⁴ / 4``, ``J = 2 I``."""
        if not (np.isfinite(radius) and radius > 0):
            raise InputError("section.radius", radius, "a finite radius > 0")
        return cls(np.pi * radius**2, np.pi * radius**4 / 4.0)

    @property
    def radius(self) -> float:
        """Radius of the circle of the same area, ``sqrt(A / π)`` (a circular section's radius,
        to round-off)."""
        return float(np.sqrt(self.area / np.pi))

    @property
    def inertia_2(self) -> float:
        """``I_z``, about the second principal axis."""
        return self.inertia if self.inertia_z is None else self.inertia_z

    @property
    def polar(self) -> float:
        """Polar moment of area ``I_y + I_z`` (torsional inertia per length: ``ρ`` times it)."""
        return self.inertia + self.inertia_2

    def bending_rotary(self, density: float) -> float:
        """``ρ I`` of the bending rotary inertia with ``rotary_inertia = "full"``, else 0."""
        if self.rotary_inertia != "full":
            return 0.0
        if self.inertia_2 != self.inertia:
            raise InputError(
                "section.rotary_inertia",
                "full",
                'equal inertia_y and inertia_z for "full" (else "torsion")',
            )
        return density * self.inertia

    @property
    def torsion(self) -> float:
        """Torsion constant ``J``."""
        return self.polar if self.torsion_constant is None else self.torsion_constant


#: The axial strain measures of cable elements (:class:`Material`).
AXIAL_STRAINS = ("green_lagrange", "engineering")


@dataclass(frozen=True)
class Material:
    """Linear elastic material: density ``ρ``, Young's modulus ``E`` and (rods) ``G`` or ``ν``.

    ``axial_strain``: the strain of the axial energy ``½ EA e²`` of cable elements:
    ``"green_lagrange"`` (``e = (λ² − 1)/2``, the default) or ``"engineering"`` (``e = λ − 1``,
    the tension ``EA (λ − 1)`` of mooring codes); docs/derivations/cable.md §6.

    ``axial_law``: a tension-strain table (:class:`~rancf.bodies.axial_law.AxialLaw`, cables and
    rods) in place of ``EA`` in the axial energy, in the engineering strain; bending keeps
    ``E I`` (docs/derivations/axial-law.md)."""

    density: float
    youngs_modulus: float
    shear_modulus: float | None = None
    poisson_ratio: float | None = None
    axial_strain: str = "green_lagrange"
    axial_law: AxialLaw | None = None

    def __post_init__(self) -> None:
        if self.axial_strain not in AXIAL_STRAINS:
            raise InputError(
                "material.axial_strain",
                self.axial_strain,
                " or ".join(f'"{k}"' for k in AXIAL_STRAINS),
            )
        for name in ("density", "youngs_modulus", "shear_modulus"):
            _positive(f"material.{name}", getattr(self, name))
        nu = self.poisson_ratio
        if nu is not None and not (np.isfinite(nu) and -1.0 < nu < 0.5):
            raise InputError("material.poisson_ratio", nu, "a number in (-1, 0.5)")
        if self.shear_modulus is not None and nu is not None:
            raise InputError(
                "material.poisson_ratio", nu, "absent when material.shear_modulus is given"
            )

    @property
    def shear(self) -> float:
        """Shear modulus ``G`` (given, or ``E / (2 (1 + ν))``)."""
        if self.shear_modulus is not None:
            return self.shear_modulus
        if self.poisson_ratio is None:
            raise InputError(
                "material.shear_modulus", None, "shear_modulus or poisson_ratio (rod elements)"
            )
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


@dataclass(frozen=True)
class StrainRateDamping:
    """Kelvin-Voigt strain-rate damping of a flexible body.

    The section forces get a part proportional to the strain rates: ``N = EA ε + axial ε̇``
    [``axial`` in N s], ``M = EI κ + bending κ̇`` [``bending`` in N m² s] and, for rods, the
    twist moment ``GJ τ + torsion τ̇`` [N m² s].  Rigid motions have zero strain rates: they are
    not damped.  A mode of frequency ``ω`` dominated by stretching decays with the damping ratio
    ``ζ = axial ω / (2 EA)``, one dominated by bending with ``ζ = bending ω / (2 EI)``, a rod's
    torsion mode with ``ζ = torsion ω / (2 GJ)``.  Every element (torsion: rods).  Statics
    ignore it (the velocities are zero).  Derivation: docs/derivations/strain-rate-damping.md.
    """

    axial: float = 0.0
    bending: float = 0.0
    torsion: float = 0.0

    def __post_init__(self) -> None:
        for name in ("axial", "bending", "torsion"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v >= 0):
                raise InputError(f"damping.{name}", v, "a finite number >= 0")

    @property
    def active(self) -> bool:
        """Whether any coefficient is > 0."""
        return self.axial > 0 or self.bending > 0 or self.torsion > 0

    def checked(self, element: str) -> StrainRateDamping:
        """Itself, or :class:`~rancf.errors.InputError` if ``torsion`` is given to an element
        without a twist (every element but the rod)."""
        if self.torsion > 0 and not framed(element):
            raise InputError(
                "damping.torsion",
                self.torsion,
                f"0 with {element} elements (a "
                'twist rate needs rod elements: mesh.element = "rod")',
            )
        return self


@dataclass(frozen=True)
class Support:
    """A support at a node.

    Kinds: ``"pin"`` (position held), ``"clamp"`` (position and tangent direction held; a rod's
    whole cross-section) and ``"roller"`` (the node moves freely along ``axis`` only).  For rods
    a clamp also holds the twist, and a pin or roller with ``fix_twist`` holds it too.

    ``position`` (pin, clamp; a point of the line for a roller) and ``direction`` (clamp: the
    held tangent) install the node away from its reference: the static solution moves it there
    along the load path (pre-tension by installation); default the reference.  ``motion``: a
    time function of the displacement of the held position from there (a moving support; in a
    system, :class:`rancf.system.System`).
    """

    node: int
    kind: Literal["pin", "clamp", "roller"] = "pin"
    fix_twist: bool = False
    position: tuple[float, ...] | None = None
    direction: tuple[float, ...] | None = None
    axis: tuple[float, ...] | None = None
    motion: TimeFunction | None = None


@dataclass(frozen=True)
class PointLoad:
    """A force and/or (rods) a moment at a node: constant, or ``× sin(2π f t)`` with a frequency,
    or a force times a time function ``time`` (in a system, :class:`rancf.system.System`)."""

    node: int
    force: tuple[float, ...] | None = None
    frequency_hz: float | None = None
    moment: tuple[float, ...] | None = None
    time: TimeFunction | None = None
