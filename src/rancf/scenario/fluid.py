"""``[fluid]``, ``[hydro]`` (``[bodies.hydro]``) and ``[[loads.distributed]]``: lines in water
and wind (:mod:`rancf.system.fluid`; docs/derivations/fluid.md).

* ``[fluid]``: ``density`` [kg/m³], ``surface`` (the still free surface's height on the last
  axis; absent: every point submerged), ``current`` (a uniform velocity [m/s]) or
  ``current_profile = [[height, u...], ...]`` (linear in height), and
  ``waves = { height, period, direction_deg, depth }`` (linear Airy waves; need a surface), or
  an irregular sea: ``waves = { spectrum = "jonswap", hs, tp, gamma, depth, components, seed,
  direction_deg }`` or ``waves = { elevation = "eta.csv", depth, direction_deg }`` (a measured
  record at the origin, rows ``[t, eta]`` at equal steps).
  Air is the same table with the density of air.
* ``[hydro]`` of a flexible body: ``diameter`` (hydrodynamic, volume-equivalent; default the
  section's), ``drag_normal``, ``drag_axial`` (on ``pi d``), ``added_mass_normal``,
  ``added_mass_axial``.  A body without it feels no fluid.
* ``[[loads.distributed]]``: ``force`` [N/m] in global axes per reference length, ``body``
  (default every flexible body), ``time`` (a scalar TIME_FUNCTION multiplying it).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BeforeValidator, Field, Tag, model_validator

from rancf.scenario.base import (
    Integer,
    JsonSchema,
    KindOf,
    NonNegative,
    Number,
    Positive,
    Table,
    Vector23,
    fail,
    show,
)
from rancf.scenario.table_files import ROWS_SCHEMA, table_rows

__all__ = [
    "FluidTable",
    "WavesTable",
    "JonswapTable",
    "ElevationTable",
    "HydroTable",
    "hydro_value",
    "fluid_value",
]


class WavesTable(Table):
    """``waves``: linear (Airy) waves on the free surface."""

    height: Positive = Field(description="wave height H (crest to trough) [m]")
    period: Positive = Field(description="period T [s]")
    direction_deg: Number = Field(0.0, description="direction of travel from the x axis [deg]")
    depth: Positive = Field(description="water depth h below the still surface [m]")


class JonswapTable(Table):
    """``waves = { spectrum = "jonswap", ... }``: an irregular sea of Airy components."""

    spectrum: Literal["jonswap"] = Field(description='"jonswap"')
    hs: Positive = Field(description="significant wave height Hs [m]")
    tp: Positive = Field(description="peak period Tp [s]")
    gamma: Number = Field(3.3, ge=1.0, le=7.0, description="peak enhancement factor, 1 to 7")
    depth: Positive = Field(description="water depth h below the still surface [m]")
    components: Integer = Field(200, ge=1, description="number of components")
    seed: Integer = Field(0, ge=0, description="seed of the random frequencies and phases")
    direction_deg: Number = Field(0.0, description="direction of travel from the x axis [deg]")


class ElevationTable(Table):
    """``waves = { elevation = "eta.csv", depth }``: a measured elevation record at the origin."""

    elevation: Annotated[
        list[list[Number]], BeforeValidator(table_rows), JsonSchema(ROWS_SCHEMA)
    ] = Field(
        description="rows [t, eta] [s, m] at equal time steps: the elevation at the origin; "
        'or a CSV file of such rows ("path.csv", relative to the scenario file)'
    )
    depth: Positive = Field(description="water depth h below the still surface [m]")
    direction_deg: Number = Field(0.0, description="direction of travel from the x axis [deg]")

    @model_validator(mode="after")
    def _rows(self) -> ElevationTable:
        rows = self.elevation
        if len(rows) < 4:
            raise fail("elevation", f"needs 4 rows [t, eta] or more, got {len(rows)}")
        for i, r in enumerate(rows):
            if len(r) != 2:
                raise fail(f"elevation[{i}]", f"must be a row [t, eta], got {show(r)}")
        step = (rows[-1][0] - rows[0][0]) / (len(rows) - 1)
        for i in range(1, len(rows)):
            if not (step > 0.0 and abs(rows[i][0] - rows[i - 1][0] - step) <= 1e-6 * step):
                raise fail(
                    f"elevation[{i}][0]",
                    f"times must increase at equal steps ({show(step)} s), got "
                    f"{show(rows[i][0])} after {show(rows[i - 1][0])}",
                )
        return self


def _wave_kind(v: Any) -> str | None:
    if isinstance(v, dict):
        found = [k for k in ("spectrum", "elevation") if k in v]
        return f"[{found[0]}]" if len(found) == 1 else ("[regular]" if not found else None)
    return _WAVE_TAGS.get(type(v))


_WAVE_TAGS: dict[type, str] = {
    WavesTable: "[regular]",
    JonswapTable: "[spectrum]",
    ElevationTable: "[elevation]",
}

#: ``waves``: a regular wave, a JONSWAP sea or a measured elevation record.
WavesValue = Annotated[
    Annotated[WavesTable, Tag("[regular]")]
    | Annotated[JonswapTable, Tag("[spectrum]")]
    | Annotated[ElevationTable, Tag("[elevation]")],
    KindOf(
        _wave_kind,
        custom_error_type="waves",
        custom_error_message="must be a table of a regular wave { height, period, depth }, "
        'a sea { spectrum = "jonswap", hs, tp, depth } or a record { elevation, depth }, '
        "not both spectrum and elevation",
    ),
]


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
    waves: WavesValue | None = Field(
        None, description="linear waves, regular or irregular (need a surface)"
    )

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
    from rancf.system.fluid import Fluid

    t.check_dim(dim)
    return Fluid(
        density=t.density,
        surface=t.surface,
        current=None if t.current is None else tuple(t.current),
        current_profile=None
        if t.current_profile is None
        else tuple(tuple(r) for r in t.current_profile),
        waves=None if t.waves is None else _waves_value(t.waves),
    )


def _waves_value(w: WavesTable | JonswapTable | ElevationTable) -> Any:
    """The :mod:`rancf.system.fluid` waves of a ``waves`` table."""
    from rancf.system.fluid import JonswapWaves, RecordedWaves, Waves

    if isinstance(w, JonswapTable):
        return JonswapWaves(w.hs, w.tp, w.gamma, w.depth, w.components, w.seed, w.direction_deg)
    if isinstance(w, ElevationTable):
        t, eta = zip(*w.elevation, strict=True)
        return RecordedWaves(tuple(t), tuple(eta), w.depth, w.direction_deg)
    return Waves(w.height, w.period, w.direction_deg, w.depth)


def hydro_value(t: HydroTable) -> Any:
    """The :class:`rancf.system.fluid.Hydro` of the table."""
    from rancf.system.fluid import Hydro

    return Hydro(**t.plain())
