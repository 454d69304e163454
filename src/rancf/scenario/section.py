"""A flexible body's ``[section]`` and ``[material]``, and the checks that need several of its
tables (:func:`check_flexible`).

Rules besides the types (each violation names its key):

* ``[section]``: ``radius``; or ``area`` + ``inertia``; or (rods) ``area`` + ``inertia_y`` +
  ``inertia_z`` + ``orientation`` (the first principal axis ``m1`` at the first node, bending
  stiffness ``E inertia_y`` about it); optional ``torsion_constant`` (rods; default the polar
  moment ``I_y + I_z``, exact for a circle) and ``rotary_inertia`` (rods).
* ``[material]``: rods need exactly one of ``shear_modulus`` and ``poisson_ratio``
  (``G = E / (2 (1 + ν))``); cables and beams refuse both (they have no torsion, so a value
  there would be silently meaningless).
* ``[mesh]``: beams need 2D geometry, rods 3D.
"""

from __future__ import annotations

import math
import sys
from typing import Annotated, Any, Literal

from pydantic import BeforeValidator, Field, model_validator

from rancf.bodies.axial_law import AxialLaw
from rancf.bodies.families import family, framed
from rancf.errors import InputError
from rancf.scenario.base import (
    JsonSchema,
    Number,
    PoissonRatio,
    Positive,
    Table,
    Vector3,
    fail,
    show,
)
from rancf.scenario.mesh_table import MeshTable
from rancf.scenario.shell_checks import check_shell
from rancf.scenario.surface import is_surface
from rancf.scenario.table_files import ROWS_SCHEMA, table_rows

__all__ = ["AxialLawTable", "SectionTable", "MaterialTable", "check_flexible"]

_ROD_SECTION = ("inertia_y", "inertia_z", "orientation", "torsion_constant", "rotary_inertia")


class SectionTable(Table):
    """``[section]``: a circular section by its radius, or area and second moments."""

    radius: Positive | None = Field(None, description="circular section: radius [m]")
    area: Positive | None = Field(None, description="cross-section area [m^2]")
    inertia: Positive | None = Field(None, description="second moment of area [m^4]")
    inertia_y: Positive | None = Field(
        None, description="rods: second moment about the first principal axis [m^4]"
    )
    inertia_z: Positive | None = Field(
        None, description="rods: second moment about the second principal axis [m^4]"
    )
    orientation: Vector3 | None = Field(
        None, description="rods: the first principal axis at the first node"
    )
    torsion_constant: Positive | None = Field(
        None, description="rods: torsion constant J [m^4] (default inertia_y + inertia_z)"
    )
    thickness: Positive | None = Field(None, description="shells: the wall thickness t [m]")
    rotary_inertia: Literal["torsion", "full"] | None = Field(
        None,
        description='rods: "torsion" (default: rho I_p about the tangent) | "full" (adds rho I '
        "of both bending directions)",
    )

    @model_validator(mode="after")
    def _one_way(self) -> SectionTable:
        principal = [k for k in ("inertia_y", "inertia_z", "orientation") if self[k] is not None]
        if self.thickness is not None:
            others = [
                k for k in type(self).model_fields if k != "thickness" and self[k] is not None
            ]
            if others:
                raise fail(others[0], "a shell's section is its thickness only (no other keys)")
        elif self.radius is not None:
            _check_radius(self.radius)
            extra = [k for k in ("area", "inertia", *principal) if self[k] is not None]
            if extra:
                raise fail("", f"give either radius, or area and inertia, not both ({extra[0]})")
        elif principal:
            if self.inertia is not None:
                raise fail(
                    "inertia",
                    "give inertia (equal bending stiffnesses) or inertia_y + "
                    "inertia_z + orientation, not both",
                )
            for k in ("area", "inertia_y", "inertia_z", "orientation"):
                if self[k] is None:
                    raise fail(
                        k,
                        "required with principal inertias (area + inertia_y + "
                        "inertia_z + orientation)",
                    )
            if not any(x != 0.0 for x in self.orientation or ()):
                raise fail("orientation", "must be a nonzero vector, got [0, 0, 0]")
        elif self.area is None or self.inertia is None:
            raise fail("", "requires radius, or both area and inertia (a shell: thickness)")
        return self


def _check_radius(r: float) -> None:
    """A radius whose area ``π r²`` and second moment ``π r⁴ / 4`` are normal positive numbers
    (``1e100`` overflows, ``1e-100`` underflows to zero)."""
    try:
        area, inertia = math.pi * r**2, math.pi * r**4 / 4.0
    except OverflowError:
        area = inertia = math.inf
    if not (math.isfinite(inertia) and inertia >= sys.float_info.min and area > 0):
        raise fail(
            "radius",
            f"must give a finite, nonzero area π r² and second moment π r⁴/4, "
            f"got {r:g} (second moment {inertia:g})",
        )


class AxialLawTable(Table):
    """``axial_law = { table = [[strain, tension], ...] }`` or ``{ table = "file.csv" }``: the
    tension-strain curve of a cable or rod (:class:`~rancf.bodies.axial_law.AxialLaw`)."""

    table: Annotated[list[list[Number]], BeforeValidator(table_rows), JsonSchema(ROWS_SCHEMA)] = (
        Field(
            description="rows [engineering strain, tension N] from [0, 0], both strictly "
            "increasing (monotone cubic between rows, the last slope beyond); or a CSV file of "
            'such rows ("path.csv", relative to the scenario file; a header row is allowed)'
        )
    )

    @model_validator(mode="after")
    def _law(self) -> AxialLawTable:
        try:
            AxialLaw(self.table)
        except InputError as exc:
            key = exc.parameter.removeprefix("material.axial_law.")
            raise fail(key, f"needs {exc.allowed}, got {show(exc.value)}") from None
        return self

    def law(self) -> AxialLaw:
        """The law of the table."""
        return AxialLaw(self.table)


class MaterialTable(Table):
    """``[material]``: density and elastic moduli."""

    density: Positive = Field(description="mass density rho [kg/m^3]")
    youngs_modulus: Positive = Field(description="Young's modulus E [Pa]")
    shear_modulus: Positive | None = Field(
        None, description="rods: shear modulus G [Pa] (or poisson_ratio)"
    )
    poisson_ratio: PoissonRatio | None = Field(
        None,
        description="rods (or shear_modulus): G = E / (2 (1 + nu)); shells: required; in (-1, 0.5)",
    )
    axial_strain: Literal["green_lagrange", "engineering"] = Field(
        "green_lagrange",
        description="cable elements: the strain of the axial energy EA e^2 / 2: green_lagrange "
        "e = (lambda^2 - 1) / 2, or engineering e = lambda - 1 (tension EA (lambda - 1), as "
        "mooring codes)",
    )

    axial_law: AxialLawTable | None = Field(
        None,
        description="cables and rods: a tension-strain table { table = [[strain, tension], "
        '...] } or { table = "file.csv" } in place of EA in the axial energy (engineering '
        "strain); bending keeps E I",
    )

    @model_validator(mode="before")
    @classmethod
    def _nu_range(cls, data: Any) -> Any:
        nu = data.get("poisson_ratio") if isinstance(data, dict) else None
        if isinstance(nu, int | float) and not isinstance(nu, bool) and not -1.0 < nu < 0.5:
            raise fail("poisson_ratio", f"must be in (-1, 0.5), got {show(nu)}")
        return data

    @model_validator(mode="after")
    def _one_modulus(self) -> MaterialTable:
        if self.shear_modulus is not None and self.poisson_ratio is not None:
            raise fail("poisson_ratio", "give shear_modulus or poisson_ratio, not both")
        if self.axial_law is not None and "axial_strain" in self.model_fields_set:
            if self.axial_strain != "engineering":
                raise fail(
                    "axial_strain",
                    'is "engineering" with an axial_law (its table is in the engineering '
                    f"strain), got {show(self.axial_strain)}",
                )
        return self


def _rod_only(key: str, element: str) -> None:
    if not framed(element):
        raise fail(key, f'applies to rod elements only (mesh.element = "rod"), not {element!r}')


def check_flexible(
    geometry: Any,
    mesh: MeshTable,
    section: SectionTable,
    material: MaterialTable,
    form: Any = None,
) -> None:
    """The checks of a flexible body that need several of its tables (keys relative to the
    body: ``mesh.element``, ``section.inertia_y``, ``material.shear_modulus``, ``form``)."""
    if is_surface(geometry):
        check_shell(geometry, mesh, section, material, form)
        return
    if section.thickness is not None:
        raise fail("section.thickness", "applies to shells (a surface [geometry]), not to a line")
    if not isinstance(mesh.elements, int):
        raise fail(
            "mesh.elements",
            f"must be one number for a line ([nu, nv] is a shell's), got {show(mesh.elements)}",
        )
    el, dim = mesh.element, geometry.dim
    fam = family(el)
    if form is not None and not fam.gradient:
        raise fail("form", f"applies to cable and rod elements, not {el!r}")
    if form is not None and getattr(geometry, "length", None) is not None:
        raise fail(
            "form",
            "finds the unstretched length: give [form] or geometry.length, not both",
        )
    if dim not in fam.dims:
        plane = "planar: use 2-coordinate" if fam.dims == (2,) else "spatial: use 3-coordinate"
        raise fail("mesh.element", f"the {el} element is {plane} geometry")
    if getattr(geometry, "length", None) is not None and not fam.gradient:
        raise fail(
            "geometry.length",
            f'applies to cable and rod elements (mesh.element = "rancf", "ancf" or "rod"), '
            f"not {el!r}",
        )
    for k in _ROD_SECTION:
        if section[k] is not None:
            _rod_only(f"section.{k}", el)
    for k in ("shear_modulus", "poisson_ratio"):
        if material[k] is not None:
            _rod_only(f"material.{k}", el)
    if material.axial_strain != "green_lagrange" and not fam.engineering_strain:
        raise fail(
            "material.axial_strain",
            f'"engineering" applies to cable elements '
            f'(mesh.element = "rancf" or "ancf"), not {el!r}',
        )
    if material.axial_law is not None and not fam.gradient:
        raise fail(
            "material.axial_law",
            f'applies to cable and rod elements (mesh.element = "rancf", "ancf" or "rod"), '
            f"not {el!r}",
        )
    if fam.has_triads and material.shear_modulus is None and material.poisson_ratio is None:
        raise fail(
            "material.shear_modulus",
            "required for rod elements: give shear_modulus or "
            "poisson_ratio (the torsional stiffness is G J)",
        )
