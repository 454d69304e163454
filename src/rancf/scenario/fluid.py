"""``[fluid]``, ``[hydro]`` (``[bodies.hydro]``) and ``[[loads.distributed]]``: lines in water
and wind (:mod:`rancf.system.fluid`; docs/derivations/fluid.md).

* ``[fluid]``: ``density`` [kg/m³], ``surface`` (the still free surface's height on the last
  axis; absent: every point submerged), ``current`` (a uniform velocity [m/s]) or
  ``current_profile = [[height, u...], ...]`` (linear in height), and
  ``waves = { height, period, direction_deg, depth }`` (linear Airy waves; need a surface).
  Air is the same table with the density of air.
* ``[hydro]`` of a flexible body: ``diameter`` (hydrodynamic, volume-equivalent; default the
  section's), ``drag_normal``, ``drag_axial`` (on ``pi d``), ``added_mass_normal``,
  ``added_mass_axial``.  A body without it feels no fluid.
* ``[[loads.distributed]]``: ``force`` [N/m] in global axes per reference length, ``body``
  (default every flexible body), ``time`` (a scalar TIME_FUNCTION multiplying it).
"""

from __future__ import annotations

from typing import Any

from pydantic import Field, model_validator

from rancf.scenario.base import NonNegative, Number, Positive, Table, Vector23, fail

__all__ = ["FluidTable", "WavesTable", "HydroTable", "hydro_value", "fluid_value"]


class WavesTable(Table):
    """``waves``: linear (Airy) waves on the free surface."""

    height: Positive = Field(description="wave height H (crest to trough) [m]")
    period: Positive = Field(description="period T [s]")
    direction_deg: Number = Field(0.0, description="direction of travel from the x axis [deg]")
    depth: Positive = Field(description="water depth h below the still surface [m]")


class FluidTable(Table):
    """``[fluid]``: the fluid every body with ``hydro`` coefficients is in."""

    density: Positive = Field(description="density [kg/m^3] (1025 seawater, 1.225 air)")
    surface: Number | None = Field(
        None,
        description="height of the still free surface on the vertical (last) axis [m]; "
        "absent: every point submerged",
    )
    current: Vector23 | None = Field(None, description="uniform current velocity [m/s]")
    current_profile: list[list[Number]] | None = Field(
        None, description="rows [height, u...]: the current, linear in height [m, m/s]"
    )
    waves: WavesTable | None = Field(None, description="linear waves (need a surface)")

    @model_validator(mode="after")
    def _consistent(self) -> FluidTable:
        if self.current is not None and self.current_profile is not None:
            raise fail("current_profile", "give current or current_profile, not both")
        rows = self.current_profile
        if rows is not None:
            if not rows:
                raise fail("current_profile", "needs one row [height, u...] or more")
            n = len(rows[0])
            for i, r in enumerate(rows):
                if len(r) != n or n not in (3, 4):
                    raise fail(
                        f"current_profile[{i}]",
                        f"must be [height, u...] with 2 or 3 "
                        f"velocity components like row 0, got {r}",
                    )
            z = [r[0] for r in rows]
            if any(b <= a for a, b in zip(z, z[1:], strict=False)):
                raise fail("current_profile", f"heights must increase, got {z}")
        if self.waves is not None and self.surface is None:
            raise fail("waves", "need a free surface (give fluid.surface)")
        return self

    def check_dim(self, dim: int) -> None:
        """Raise unless the velocities have ``dim`` components."""
        if self.current is not None and len(self.current) != dim:
            raise fail("current", f"must be a list of {dim} numbers, got {self.current}")
        if self.current_profile is not None and len(self.current_profile[0]) != dim + 1:
            raise fail(
                "current_profile[0]",
                f"must be [height, u...] with {dim} velocity "
                f"components, got {self.current_profile[0]}",
            )


class HydroTable(Table):
    """``[hydro]`` / ``[bodies.hydro]``: a flexible body's hydrodynamic coefficients."""

    diameter: Positive | None = Field(
        None, description="hydrodynamic (volume-equivalent) diameter [m]; default the section's"
    )
    drag_normal: NonNegative = Field(1.2, description="normal drag coefficient (on d)")
    drag_axial: NonNegative = Field(0.0, description="axial drag coefficient (on pi d)")
    added_mass_normal: NonNegative = Field(1.0, description="normal added-mass coefficient")
    added_mass_axial: NonNegative = Field(0.0, description="axial added-mass coefficient")


def fluid_value(t: FluidTable | None, dim: int) -> Any:
    """The :class:`rancf.system.fluid.Fluid` of the table (None without one)."""
    if t is None:
        return None
    from rancf.system.fluid import Fluid, Waves

    t.check_dim(dim)
    w = t.waves
    return Fluid(
        density=t.density,
        surface=t.surface,
        current=None if t.current is None else tuple(t.current),
        current_profile=None
        if t.current_profile is None
        else tuple(tuple(r) for r in t.current_profile),
        waves=None if w is None else Waves(w.height, w.period, w.direction_deg, w.depth),
    )


def hydro_value(t: HydroTable) -> Any:
    """The :class:`rancf.system.fluid.Hydro` of the table."""
    from rancf.system.fluid import Hydro

    return Hydro(**t.plain())
