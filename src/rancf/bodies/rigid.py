"""Rigid bodies and point masses: the bodies of a system besides the flexible ones.

Coordinates (stacked after the flexible bodies by :class:`rancf.system.System`):

* a planar rigid body: ``(x, y, θ)`` of its centre of mass and its angle;
* a spatial rigid body: ``(x, y, z, p0, p1, p2, p3)``, the centre of mass and a unit quaternion
  (scalar first) of its orientation, normalized by a constraint of the system; its velocity
  ``ṗ = ½ Gᵀ(p) ω'`` with the body-frame angular velocity ``ω' = Rᵀ ω`` (Nikravesh's ``G``);
* a point mass: its position.

Named points are given in the body frame (relative to the centre of mass).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError

__all__ = ["RigidBody", "PointMass", "quaternion_from_matrix", "body_angular_velocity"]


def _vector(key: str, v: float | Sequence[float] | None, dim: int) -> NDArray[np.float64]:
    a = np.zeros(dim) if v is None else np.asarray(v, dtype=float)
    if a.shape != (dim,) or not np.all(np.isfinite(a)):
        raise InputError(key, list(v) if isinstance(v, Sequence) else v, f"{dim} finite numbers")
    return a


def quaternion_from_matrix(r: NDArray) -> NDArray[np.float64]:
    """The unit quaternion (scalar first) of a rotation matrix (Shepperd's method)."""
    r = np.asarray(r, dtype=float)
    tr = np.trace(r)
    cands = [tr, r[0, 0], r[1, 1], r[2, 2]]
    k = int(np.argmax(cands))
    if k == 0:
        s = 2.0 * np.sqrt(1.0 + tr)
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    elif k == 1:
        s = 2.0 * np.sqrt(1.0 + r[0, 0] - r[1, 1] - r[2, 2])
        q = [(r[2, 1] - r[1, 2]) / s, 0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s]
    elif k == 2:
        s = 2.0 * np.sqrt(1.0 + r[1, 1] - r[0, 0] - r[2, 2])
        q = [(r[0, 2] - r[2, 0]) / s, (r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s]
    else:
        s = 2.0 * np.sqrt(1.0 + r[2, 2] - r[0, 0] - r[1, 1])
        q = [(r[1, 0] - r[0, 1]) / s, (r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s]
    qa = np.array(q)
    return qa / np.linalg.norm(qa) * (1.0 if qa[0] >= 0 else -1.0)


def _g_matrix(p: NDArray) -> NDArray[np.float64]:
    return np.array(
        [[-p[1], p[0], p[3], -p[2]], [-p[2], -p[3], p[0], p[1]], [-p[3], p[2], -p[1], p[0]]]
    )


def body_angular_velocity(p: NDArray, pd: NDArray) -> NDArray[np.float64]:
    """Angular velocity in the body frame of a unit quaternion ``p`` and its rate ``ṗ``:
    ``ω = 2 G(p) ṗ`` (the inverse of ``ṗ = ½ G(p)ᵀ ω`` of :meth:`RigidBody.initial`)."""
    return 2.0 * _g_matrix(np.asarray(p, dtype=float)) @ np.asarray(pd, dtype=float)


@dataclass(frozen=True)
class RigidBody:
    """A rigid body.

    Parameters
    ----------
    dim : {2, 3}
    mass : float
    inertia : float or (3,)
        2D: about the centre of mass; 3D: principal moments in the body frame.
    position : ``(dim,)``
        Centre of mass.
    orientation : float or (3, 3)
        2D: the angle [rad]; 3D: the rotation matrix (body frame to world).
    velocity, angular_velocity :
        Initial velocity of the centre of mass; angular velocity (2D: a number; 3D: world).
    points : mapping name -> ``(dim,)``
        Named points in the body frame.
    """

    dim: int
    mass: float
    inertia: float | tuple[float, float, float]
    position: tuple[float, ...]
    orientation: float | tuple[tuple[float, ...], ...] = 0.0
    velocity: tuple[float, ...] | None = None
    angular_velocity: float | tuple[float, ...] | None = None
    points: Mapping[str, tuple[float, ...]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.dim not in (2, 3):
            raise InputError("dim", self.dim, "2 or 3")
        if not (np.isfinite(self.mass) and self.mass > 0):
            raise InputError("mass", self.mass, "a finite mass > 0 [kg]")
        inertia = np.atleast_1d(np.asarray(self.inertia, dtype=float))
        if inertia.shape != ((1,) if self.dim == 2 else (3,)) or not np.all(inertia > 0):
            what = "a number > 0" if self.dim == 2 else "[Ixx, Iyy, Izz], each > 0"
            raise InputError("inertia", self.inertia, what)
        _vector("position", self.position, self.dim)
        for name, pt in self.points.items():
            _vector(f"points.{name}", pt, self.dim)
        if self.dim == 3:
            r = np.asarray(self.orientation if not np.isscalar(self.orientation) else np.eye(3))
            if (
                r.shape != (3, 3)
                or not np.allclose(r @ r.T, np.eye(3), atol=1e-9)
                or np.linalg.det(r) < 0
            ):
                raise InputError("orientation", self.orientation, "a 3x3 rotation matrix (rows)")

    @property
    def size(self) -> int:
        """Coordinates: 3 (2D) or 7 (3D)."""
        return 3 if self.dim == 2 else 7

    def inertia_vector(self) -> NDArray[np.float64]:
        """``[J, 0, 0]`` (2D) or the principal moments (3D)."""
        i = np.atleast_1d(np.asarray(self.inertia, dtype=float))
        return np.array([i[0], 0.0, 0.0]) if self.dim == 2 else i

    def rotation(self) -> NDArray[np.float64]:
        """Initial rotation matrix (3D) or 2x2 (2D)."""
        if self.dim == 2:
            angle = float(np.asarray(self.orientation, dtype=float))
            c, s = np.cos(angle), np.sin(angle)
            return np.array([[c, -s], [s, c]])
        return np.asarray(
            self.orientation if not np.isscalar(self.orientation) else np.eye(3), dtype=float
        )

    def initial(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Initial coordinates and velocities of the body."""
        x = _vector("position", self.position, self.dim)
        v = _vector("velocity", self.velocity, self.dim)
        if self.dim == 2:
            w = self.angular_velocity
            rate = 0.0 if w is None else float(np.asarray(w, dtype=float))
            return np.r_[x, float(np.asarray(self.orientation, dtype=float))], np.r_[v, rate]
        p = quaternion_from_matrix(self.rotation())
        omega = _vector("angular_velocity", self.angular_velocity, 3)
        pd = 0.5 * _g_matrix(p).T @ (self.rotation().T @ omega)
        return np.r_[x, p], np.r_[v, pd]

    def point(self, name: str | None) -> NDArray[np.float64]:
        """A named point in the body frame (None: the centre of mass), 3 components."""
        if name is None:
            return np.zeros(3)
        if name not in self.points:
            raise InputError(
                "place", name, f"a point of the body: {', '.join(self.points) or 'none'}"
            )
        return np.r_[np.asarray(self.points[name], dtype=float), np.zeros(3 - self.dim)]


@dataclass(frozen=True)
class PointMass:
    """A point mass at ``position`` with an initial ``velocity``."""

    dim: int
    mass: float
    position: tuple[float, ...]
    velocity: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        if self.dim not in (2, 3):
            raise InputError("dim", self.dim, "2 or 3")
        if not (np.isfinite(self.mass) and self.mass > 0):
            raise InputError("mass", self.mass, "a finite mass > 0 [kg]")
        _vector("position", self.position, self.dim)

    @property
    def size(self) -> int:
        return self.dim

    def initial(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        return _vector("position", self.position, self.dim), _vector(
            "velocity", self.velocity, self.dim
        )
