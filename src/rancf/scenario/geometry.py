"""A flexible body's ``[geometry]`` (conic, line, NURBS, CAD) and ``[mesh]``.

Rules besides the types (each violation names its key): the keys of the geometry's ``kind``
only; all points of one dimension (2: planar, 3: spatial); a NURBS of degree ``p`` has at least
``p + 1`` control points; ``kind = "cad"`` reads the file (relative to the scenario file) and
checks the chain of curves.  The section, the material and the checks across tables are in
:mod:`rancf.scenario.section`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal

from pydantic import (
    BeforeValidator,
    Field,
    PrivateAttr,
    Tag,
    ValidationInfo,
    model_validator,
)

from rancf.errors import InputError
from rancf.scenario.base import (
    MAX_COORDINATE,
    MAX_ELEMENTS,
    Degree,
    KindOf,
    Number,
    Point,
    Positive,
    SemiAxes,
    Table,
    Vector2,
    Vector3,
    fail,
    show,
)
from rancf.scenario.geometry_keys import GEOMETRY_KEYS
from rancf.scenario.mesh_table import MeshTable
from rancf.scenario.surface import (
    SURFACE_KINDS,
    ConeGeometry,
    CylinderGeometry,
    NurbsSurfaceGeometry,
    RectangleGeometry,
    SphereGeometry,
)

__all__ = [
    "MAX_ELEMENTS",
    "MAX_COORDINATE",
    "MAX_WEIGHT_RATIO",
    "ELEMENTS",
    "GEOMETRY_KEYS",
    "ConicGeometry",
    "LineGeometry",
    "NurbsGeometry",
    "CadGeometry",
    "EllipseGeometry",
    "Geometry",
    "MeshTable",
]

#: Largest ratio of two NURBS weights (a curve's shape depends on the ratios only).
MAX_WEIGHT_RATIO = 1e12
#: Element kinds of ``mesh.element``.
ELEMENTS = ("rancf", "ancf", "beam", "rod")


class _Geometry(Table):
    """Keys of another kind are refused as not applying to this one."""

    KIND: ClassVar[str] = ""

    @classmethod
    def unknown_key_message(cls, key: str) -> str:
        if any(key in keys for keys in GEOMETRY_KEYS.values()):
            own = ", ".join(GEOMETRY_KEYS[cls.KIND])
            return f"does not apply to kind = {cls.KIND!r} (its keys: {own})"
        return super().unknown_key_message(key)

    @property
    def dim(self) -> int:
        """Dimension of the geometry: 2 (planar) or 3 (spatial)."""
        raise NotImplementedError


def _same_dim(dim: int, key: str, v: list[float]) -> None:
    if len(v) != dim:
        raise fail(key, f"must be a list of {dim} numbers, got {show(v)}")


class LineGeometry(_Geometry):
    """A straight line from ``start`` to ``end``, of unstretched ``length`` (default: its chord)."""

    KIND: ClassVar[str] = "line"
    kind: Literal["line"] = Field(description="a straight line")
    start: Point = Field(description="start point [m]; 2 coordinates: planar, 3: spatial")
    end: Point = Field(description="end point [m], as many coordinates as start")
    length: Positive | None = Field(None, description="unstretched length [m] (default: the chord)")

    @model_validator(mode="after")
    def _dims(self) -> LineGeometry:
        _same_dim(len(self.start), "end", self.end)
        return self

    @property
    def dim(self) -> int:
        return len(self.start)


class ConicGeometry(_Geometry):
    """A conic arc (ellipse, parabola or hyperbola) from its end points, end angles and one
    interior point."""

    KIND: ClassVar[str] = "conic"
    kind: Literal["conic"] = Field(description="a conic arc")
    start: Point = Field(description="start point [m]; 2 coordinates: planar, 3: spatial")
    end: Point = Field(description="end point [m], as many coordinates as start")
    angles_deg: Vector2 = Field(
        description="tangent-to-chord angles at start and end, each in (0, 90) [deg]"
    )
    point: Point = Field(description="an interior point of the arc, global coordinates [m]")

    @model_validator(mode="after")
    def _dims(self) -> ConicGeometry:
        _same_dim(len(self.start), "end", self.end)
        _same_dim(len(self.start), "point", self.point)
        return self

    @property
    def dim(self) -> int:
        return len(self.start)


class NurbsGeometry(_Geometry):
    """A NURBS curve of degree 2 or 3."""

    KIND: ClassVar[str] = "nurbs"
    kind: Literal["nurbs"] = Field(description="a NURBS curve")
    degree: Degree = Field(description="polynomial degree, 2 or 3")
    knots: list[Number] = Field(description="knot vector, non-decreasing")
    control_points: list[Point] = Field(
        min_length=1, description="control points [m], all with 2 or all with 3 coordinates"
    )
    weights: list[Number] | None = Field(
        None, description="rational weights, > 0, one per control point (default: all 1)"
    )

    @model_validator(mode="after")
    def _points(self) -> NurbsGeometry:
        n, p = len(self.control_points), self.degree
        if n < p + 1:
            raise fail(
                "control_points",
                f"a NURBS of degree {p} needs at least {p + 1} control points, got {n}",
            )
        for i, pt in enumerate(self.control_points):
            _same_dim(self.dim, f"control_points[{i}]", pt)
        w = [abs(x) for x in self.weights or () if x != 0.0]
        if w and max(w) > MAX_WEIGHT_RATIO * min(w):
            raise fail(
                "weights",
                f"the largest weight may be at most {MAX_WEIGHT_RATIO:g} times "
                f"the smallest, got {max(w):g} and {min(w):g}",
            )
        return self

    @property
    def dim(self) -> int:
        return len(self.control_points[0])


class EllipseGeometry(_Geometry):
    """A full ellipse (a circle when ``a = b``): a closed curve, meshed exactly with conic-section
    elements (:func:`rancf.mesh.ellipse_mesh.mesh_ellipse`)."""

    KIND: ClassVar[str] = "ellipse"
    kind: Literal["ellipse"] = Field(description="a full ellipse (closed: a ring)")
    center: Point = Field(description="center [m]; 2 coordinates: planar, 3: spatial")
    semi_axes: SemiAxes = Field(
        description="semi-axes [a, b] along the first and second axis [m], each > 0"
    )
    rotation_deg: Number | None = Field(
        None, description="planar: angle of the first axis from x [deg] (default 0)"
    )
    axes: list[Vector3] | None = Field(
        None,
        description="spatial: the first and second axis directions, perpendicular (default x "
        "and y)",
    )
    start_deg: Number = Field(
        0.0,
        description="parameter t of the first node (the seam) on r(t) = center + a cos t e1 + "
        "b sin t e2 [deg]",
    )

    @model_validator(mode="after")
    def _check(self) -> EllipseGeometry:
        for i, v in enumerate(self.semi_axes):
            if not v > 0.0:
                raise fail(f"semi_axes[{i}]", f"must be > 0, got {show(v)}")
        if self.dim == 2 and self.axes is not None:
            raise fail(
                "axes",
                "applies to a spatial ellipse (3 center coordinates); a planar "
                "one turns by rotation_deg",
            )
        if self.dim == 3 and self.rotation_deg is not None:
            raise fail(
                "rotation_deg",
                "applies to a planar ellipse (2 center coordinates); a spatial one has axes",
            )
        if self.axes is not None:
            from rancf.geometry.ellipse import ellipse_axes

            if len(self.axes) != 2:
                raise fail("axes", f"must be two directions, got {show(self.axes)}")
            try:
                ellipse_axes(3, axes=self.axes)
            except InputError as exc:
                raise fail("axes", f"must be {exc.allowed}, got {show(self.axes)}") from None
        return self

    @property
    def dim(self) -> int:
        return len(self.center)

    def ellipse(self) -> Any:
        """The :class:`~rancf.geometry.ellipse.Ellipse`."""
        import numpy as np

        from rancf.geometry.ellipse import Ellipse, ellipse_axes

        e1, e2 = ellipse_axes(self.dim, self.rotation_deg or 0.0, self.axes)
        center = np.asarray(self.center, dtype=float)
        return Ellipse(center, self.semi_axes[0], self.semi_axes[1], e1, e2)


Curve = Annotated[int | str, BeforeValidator(lambda v: _curve_item(v))]


def _curve_item(v: Any) -> Any:
    if isinstance(v, bool) or not isinstance(v, int | str):
        raise fail("", f"must be an index, a name or a list, got {show(v)}")
    return v


class CadGeometry(_Geometry):
    """Curves of a CAD file (STEP, IGES, DXF, geomdl JSON) joined into one tangent-continuous
    chain (:mod:`rancf.mesh.cad_geometry`)."""

    KIND: ClassVar[str] = "cad"
    kind: Literal["cad"] = Field(description="curves of a CAD file")
    file: Annotated[str, Field(min_length=1)] = Field(
        description="CAD file (STEP, IGES, DXF, geomdl JSON), relative to the scenario file"
    )
    curve: Curve | list[Curve] | None = Field(
        None,
        description="curve index or name in the file, or a list of them forming a chain "
        "(default: the first curve)",
    )
    _curves: list[Any] = PrivateAttr(default_factory=list)
    _labels: list[str] = PrivateAttr(default_factory=list)
    _resolved: str = PrivateAttr("")
    _notes: tuple[str, ...] = PrivateAttr(default_factory=tuple)

    @model_validator(mode="after")
    def _read(self, info: ValidationInfo) -> CadGeometry:
        from rancf.mesh.cad_geometry import chain_segments, select_cad_curves

        path = str((info.context or {}).get("path", "<scenario>"))
        base = Path(path).parent if not path.startswith("<") else Path.cwd()
        file = (base / self.file).resolve()
        sel = 0 if self.curve is None else self.curve
        if isinstance(sel, list) and not sel:
            raise fail("curve", "must be an index, a name or a non-empty list, got []")
        try:
            curves, labels, notes = select_cad_curves(file, sel)
            chain_segments(curves, labels)  # report gaps and kinks now, naming the key
        except InputError as exc:
            key = "file" if exc.parameter == "file" else exc.parameter.removeprefix("geometry.")
            raise fail(key, str(exc)) from None
        self._curves, self._labels, self._resolved = curves, labels, str(file)
        self._notes = notes
        return self

    @property
    def dim(self) -> int:
        return int(self._curves[0].dim)

    @property
    def curves(self) -> list[Any]:
        """The selected curves (:class:`~rancf.geometry.nurbs.NurbsCurve`), in chain order."""
        return list(self._curves)

    @property
    def labels(self) -> list[str]:
        """The curves' labels (``curve 3 (name)``) for errors."""
        return list(self._labels)

    @property
    def notes(self) -> tuple[str, ...]:
        """The reader's one-line notes (a DXF's units converted, a spline built from fit
        points)."""
        return self._notes

    @property
    def resolved_file(self) -> str:
        """The CAD file's absolute path."""
        return self._resolved


def _geometry_kind(v: Any) -> str | None:
    k = v.get("kind") if isinstance(v, dict) else getattr(v, "kind", None)
    return f"[{k}]" if isinstance(k, str) and k in GEOMETRY_KEYS else None


#: ``[geometry]``: one of the kinds, chosen by ``kind``.
Geometry = Annotated[
    Annotated[ConicGeometry, Tag("[conic]")]
    | Annotated[LineGeometry, Tag("[line]")]
    | Annotated[NurbsGeometry, Tag("[nurbs]")]
    | Annotated[CadGeometry, Tag("[cad]")]
    | Annotated[EllipseGeometry, Tag("[ellipse]")]
    | Annotated[CylinderGeometry, Tag("[cylinder]")]
    | Annotated[SphereGeometry, Tag("[sphere]")]
    | Annotated[ConeGeometry, Tag("[cone]")]
    | Annotated[RectangleGeometry, Tag("[rectangle]")]
    | Annotated[NurbsSurfaceGeometry, Tag("[nurbs_surface]")],
    KindOf(
        _geometry_kind,
        custom_error_type="choice",
        custom_error_message="must be one of the geometry kinds",
        custom_error_context={
            "key": "kind",
            "allowed": "'conic', 'line', 'nurbs', 'cad', 'ellipse' (curves); "
            + ", ".join(repr(k) for k in SURFACE_KINDS)
            + " (surfaces: a shell)",
        },
    ),
    Field(
        description="the reference geometry (its kind selects its keys; a surface kind makes "
        "the body a shell)"
    ),
]
