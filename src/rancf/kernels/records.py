"""The named records everything crosses into the compiled core as (``src/cpp/system/system.hpp``):
the one convention of the boundary (the solvers' entry points: :mod:`rancf.kernels.call_records`).

:class:`rancf.kernels._core.System` takes one :class:`SystemModel` (its bodies and lists of
per-part records: places, joints, springs, loads, winches, ...); the integrator's entry points
take two records each: ``run(RunBuffers, RunOptions)``, ``factor_static`` and
``static_increment(StaticPoint, StaticOptions)``, and the system's ``sparse_jacobian(StatePoint,
TangentOptions)`` (statics and modes).  The bindings (``src/cpp/bindings/bindings_fields.hpp``)
read every field by its name into the C++ struct of the same name and fields, and refuse a field
of the wrong type, size or value in one line that names it (``places[2].kind: expected one of
ground, cable, ..., got 'bar'``).  Vectors of the parts' records are tuples of floats (a matrix
row-major), so that those records are immutable and hashable; arrays (band matrices, states,
buffers written in place) are NumPy arrays of float64.

Coordinates ``y`` stack the flexible bodies, then the rigid bodies and point masses
(:mod:`rancf.system.system`); places, time functions and linear rows are numbered by their
position in their lists.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:  # the contact modules load with a system that has contact
    from rancf.kernels.contact_records import ContactRecord

__all__ = [
    "PLACE_KINDS",
    "JOINT_KINDS",
    "TIME_KINDS",
    "RigidRecord",
    "PlaceRecord",
    "JointRecord",
    "SpringRecord",
    "LoadRecord",
    "TimeFunctionRecord",
    "PrescribedRecord",
    "LinearTerm",
    "FluidRecord",
    "LineRecord",
    "DistributedRecord",
    "DrumRecord",
    "WinchRecord",
    "SlidingRecord",
    "SystemModel",
    "floats",
    "vec3",
]

#: Kinds of places (``PlaceKind``, ``src/cpp/system/places.hpp``).
PLACE_KINDS = ("ground", "cable", "rod", "beam", "rigid2d", "rigid3d", "mass")
#: Kinds of joint rows (``JointKind``, ``src/cpp/system/joints.hpp``).
JOINT_KINDS = ("pin", "fixed", "tangent", "revolute", "slider", "sliding")
#: Kinds of time functions (``TimeKind``, ``src/cpp/system/time_function.hpp``).
TIME_KINDS = ("constant", "piecewise", "ramp", "harmonic", "spin_up")


def floats(values: ArrayLike) -> tuple[float, ...]:
    """A record's vector: ``values`` (an array of any shape is taken row-major) as floats."""
    return tuple(float(x) for x in np.ravel(np.asarray(values, dtype=float)))


def vec3(values: ArrayLike) -> tuple[float, float, float]:
    """A record's 3-vector: :func:`floats` of exactly three values."""
    x, y, z = floats(values)
    return x, y, z


@dataclass(frozen=True)
class RigidRecord:
    """A rigid body or point mass (``RigidInertia``, ``src/cpp/system/rigid.hpp``): ``inertia`` the
    principal moments (2D: ``(J, 0, 0)``)."""

    dim: int
    point_mass: bool
    mass: float
    inertia: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class PlaceRecord:
    """A place (``PlaceRef``, ``src/cpp/system/system.hpp``).

    Attributes
    ----------
    kind : str
        One of :data:`PLACE_KINDS`: a flexible body's node (``cable``, ``rod``, ``beam``), a rigid
        body (``rigid2d``, ``rigid3d``), a point mass (``mass``) or the ``ground``.
    body : int
        The flexible body (node kinds) or the rigid body or point mass; -1 for the ground.
    node : int
        The node of a flexible body.
    point : (3,) floats
        The ground's point (world), or a rigid body's point in its frame.
    motion : int
        The ground: the time function of the point's displacement (``dim`` components), or -1.
    angle0 : float
        A beam node: its reference tangent angle.
    rotation : int
        The ground: the time function of its frame's rotation from the world axes (2D the
        angle about z, 3D the rotation vector [rad]), or -1.
    """

    kind: str
    body: int = -1
    node: int = 0
    point: tuple[float, float, float] = (0.0, 0.0, 0.0)
    motion: int = -1
    angle0: float = 0.0
    rotation: int = -1


@dataclass(frozen=True)
class JointRecord:
    """A joint (``JointData``, ``src/cpp/system/system.hpp``; its rows in
    ``src/cpp/system/joints.hpp``).

    Attributes
    ----------
    kind : str
        One of :data:`JOINT_KINDS` (the rows; a 2D revolute is a ``pin``).
    a, b : int
        The places joined.
    driven : bool
        An angle row follows the time function ``angle``.
    angle : int
        A driven joint's time function, or -1.
    beta0 : float
        The reference relative angle (2D ``fixed`` and driven rows).
    rel : (9,) floats
        3D ``fixed``: the reference relative rotation ``rel[k][j] = a_k . b_j``, row-major.
    axis_a : (3,) floats
        ``revolute``: the axis in the first place's frame.
    normals_b : (6,) floats
        ``revolute``, ``tangent``, ``slider``: two normals in the second place's frame.
    w_a, w_b : (3,) floats
        A driven 3D revolute: the reference normals whose angle is the joint angle.
    body : int
        ``sliding``: the flexible body that runs through place ``b`` (``a``: its node 0, not
        evaluated); -1 otherwise.
    """

    kind: str
    a: int
    b: int
    driven: bool = False
    angle: int = -1
    beta0: float = 0.0
    rel: tuple[float, ...] = (0.0,) * 9
    axis_a: tuple[float, float, float] = (0.0, 0.0, 0.0)
    normals_b: tuple[float, ...] = (0.0,) * 6
    w_a: tuple[float, float, float] = (0.0, 0.0, 0.0)
    w_b: tuple[float, float, float] = (0.0, 0.0, 0.0)
    body: int = -1


@dataclass(frozen=True)
class SpringRecord:
    """A spring-damper between the places ``a`` and ``b`` (``SpringData``): tension
    ``stiffness (l - length) + damping dl/dt``, or with ``law`` (a scalar table among the time
    functions, evaluated at the stretch ``e = l - length``; ``src/cpp/system/spring_law.hpp``)
    ``T(e) + damping dl/dt``."""

    a: int
    b: int
    stiffness: float
    damping: float = 0.0
    length: float = 0.0
    law: int = -1


@dataclass(frozen=True)
class LoadRecord:
    """A force (and, on rigid bodies and rod nodes, a torque) at ``place``, world axes, times
    the time function ``factor`` (-1: constant) (``PlaceLoad``)."""

    place: int
    force: tuple[float, float, float] = (0.0, 0.0, 0.0)
    torque: tuple[float, float, float] = (0.0, 0.0, 0.0)
    factor: int = -1


@dataclass(frozen=True)
class TimeFunctionRecord:
    """A time function as the core evaluates it (``TimeFunction``,
    ``src/cpp/system/time_function.hpp``).

    Attributes
    ----------
    kind : str
        One of :data:`TIME_KINDS`.
    value : floats
        One per component: the constant, the ramp's end value, the amplitude, the spin-up rate.
    duration, frequency, phase : float
        ``T`` of a ramp or spin-up [s], a harmonic's frequency [Hz] and phase [rad].
    breaks : floats
        ``piecewise``: the ``k + 1`` breakpoints.
    coef : floats
        ``piecewise``: the ``(k, 4, n)`` coefficients ``c0 + c1 s + c2 s^2 + c3 s^3``,
        row-major.
    build_up : float
        ``B`` [s] of the smooth build-up the function is multiplied by; 0: none.
    """

    kind: str
    value: tuple[float, ...]
    duration: float = 0.0
    frequency: float = 0.0
    phase: float = 0.0
    breaks: tuple[float, ...] = ()
    coef: tuple[float, ...] = ()
    build_up: float = 0.0


@dataclass(frozen=True)
class PrescribedRecord:
    """A held coordinate that follows a time function: ``y[coord] = base + u_comp(t)`` with
    ``u`` the time function ``tf`` (``Prescribed``)."""

    coord: int
    tf: int
    comp: int
    base: float


@dataclass(frozen=True)
class LinearTerm:
    """A term ``coef * y[col]`` of the linear constraint row ``row`` (0-based among the linear
    rows; they close closed flexible bodies) (``LinearTerm``)."""

    row: int
    col: int
    coef: float


@dataclass(frozen=True)
class FluidRecord:
    """The fluid the bodies are in (``FluidField``, ``src/cpp/fluid/fluid.hpp``): ``density``
    [kg/m^3], ``gravity`` (3) for buoyancy, the still ``surface`` height on the last axis (if
    ``has_surface``), a uniform ``current`` or a profile (``profile_z`` increasing heights,
    ``profile_u`` their velocities ``(n, 3)`` row-major), and linear waves (``waves``: a sum of
    Airy components ``a_i cos(k_i x.e - omega_i t - phi_i)``, their amplitudes, angular
    frequencies, wave numbers and phases; ``depth`` and the unit direction ``e``)."""

    density: float
    gravity: tuple[float, float, float]
    has_surface: bool = False
    surface: float = 0.0
    current: tuple[float, float, float] = (0.0, 0.0, 0.0)
    profile_z: tuple[float, ...] = ()
    profile_u: tuple[float, ...] = ()
    waves: bool = False
    wave_amplitude: tuple[float, ...] = ()
    wave_omega: tuple[float, ...] = ()
    wave_k: tuple[float, ...] = ()
    wave_phase: tuple[float, ...] = ()
    wave_depth: float = 0.0
    wave_dir: tuple[float, float, float] = (1.0, 0.0, 0.0)


@dataclass(frozen=True)
class DistributedRecord:
    """A force per reference length [N/m] (world axes) times the time function ``factor`` (-1:
    constant) (``DistributedLoad``)."""

    force: tuple[float, float, float]
    factor: int = -1


@dataclass(frozen=True)
class LineRecord:
    """A flexible body in the fluid (``LineFluid``): ``hydro`` whether the fluid acts on it
    (its ``diameter`` and Morison coefficients), its elements' quadrature (``n0``, ``n1`` the
    shape functions and their ξ-derivatives ``(n_el, n_qp, 4)``, ``gw`` ``(n_qp)``, ``j0`` the
    reference ``|r0'|`` ``(n_el, n_qp)``) and its distributed ``loads``."""

    body: int
    hydro: bool
    diameter: float
    drag_normal: float
    drag_axial: float
    added_mass_normal: float
    added_mass_axial: float
    n_qp: int
    n0: tuple[float, ...]
    n1: tuple[float, ...]
    gw: tuple[float, ...]
    j0: tuple[float, ...]
    loads: tuple[DistributedRecord, ...] = ()


@dataclass(frozen=True, eq=False)
class DrumRecord:
    """A winch's driven drum (``Winch``, ``src/cpp/system/winch.hpp``): the time function
    ``torque`` [N m] reeling in, ``mass = J / r²`` [kg], ``radius`` [m], the line's ``rho_a``
    [kg/m] and weight per length ``weight`` (3) [N/m], ``exit``, the body's coordinate of the
    exit node's position, and ``convective``, the weights ``gw d L_ref / L_s`` of the line's
    fluid loads in the drum's balance per Gauss point ``(n_el * n_qp)``
    (docs/derivations/variable-length.md §3.5).  Its length ``L`` is a coordinate of the
    system, after every body and drum before it."""

    torque: int
    mass: float
    radius: float
    rho_a: float
    weight: tuple[float, float, float]
    exit: int
    convective: NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class WinchRecord:
    """A winch at a cable body's end (``Winch``): the flexible ``body``, the time function
    ``length`` of ``L(t)``, ``length_set`` the length the body's arrays hold, the convective band
    matrices ``c1``, ``c2``, ``d2`` (``(2 ku + 1, n)``) and its driven ``drum`` (or None)."""

    body: int
    length: int
    length_set: float
    c1: NDArray[np.float64]
    c2: NDArray[np.float64]
    d2: NDArray[np.float64]
    drum: DrumRecord | None = None


@dataclass(frozen=True, eq=False)
class SlidingRecord:
    """A flexible body sliding joints run along (``SlidingBody``, ``src/cpp/system/sliding.hpp``):
    its rational ``weights`` ``(n_el, 4)`` and gradient ``scales`` ``(n_el)``, row-major, and
    whether it is ``closed``."""

    body: int
    weights: tuple[float, ...]
    scales: tuple[float, ...]
    closed: bool


@dataclass(frozen=True, eq=False)
class SystemModel:
    """A whole system as the core is built from it, once (``System``,
    ``src/cpp/system/system.hpp``; ``src/cpp/bindings/bindings_system_model.cpp``).

    Attributes
    ----------
    dim : int
        2 or 3.
    models : sequence of :class:`rancf.kernels._core.Model`
        The flexible bodies' cores, in the order of ``y``.
    rigid, places, joints, springs, loads, time_functions, prescribed, linear : sequences
        The parts' records (:class:`RigidRecord`, :class:`PlaceRecord`, ...), indices between
        them by position.
    gravity : (3,) floats
        On rigid bodies and point masses.
    damping, stiffness_damping : float
        Mass-proportional ``c`` [1/s] of every body, stiffness-proportional ``β`` [s] of the
        flexible bodies.
    y_ref : (n,) array
        The reference coordinates of the bodies (a driven drum's coordinate is added after them).
    fluid : :class:`FluidRecord` or None
        The fluid, and ``lines`` (:class:`LineRecord`) the flexible bodies in it.
    contact : :class:`ContactRecord` or None
        Obstacles and contact pairs (the core's ``System.contact`` is built from it).
    winches : sequence of :class:`WinchRecord`
    sliding : sequence of :class:`SlidingRecord`
    """

    dim: int
    models: tuple[Any, ...]
    y_ref: NDArray[np.float64]
    gravity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    damping: float = 0.0
    stiffness_damping: float = 0.0
    rigid: tuple[RigidRecord, ...] = ()
    places: tuple[PlaceRecord, ...] = ()
    joints: tuple[JointRecord, ...] = ()
    springs: tuple[SpringRecord, ...] = ()
    loads: tuple[LoadRecord, ...] = ()
    time_functions: tuple[TimeFunctionRecord, ...] = ()
    prescribed: tuple[PrescribedRecord, ...] = ()
    linear: tuple[LinearTerm, ...] = ()
    fluid: FluidRecord | None = None
    lines: tuple[LineRecord, ...] = ()
    contact: ContactRecord | None = None
    winches: tuple[WinchRecord, ...] = ()
    sliding: tuple[SlidingRecord, ...] = ()
