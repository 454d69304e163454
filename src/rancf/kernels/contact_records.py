"""The named records of a system's contact as the compiled core reads them
(``src/cpp/contact/contact.hpp``, ``src/cpp/bindings/bindings_contact.cpp``): one
:class:`ContactRecord` of the flexible bodies' contact points, the obstacles and the pairs in
contact, the model record's ``contact`` (:class:`rancf.kernels.records.SystemModel`); the
conventions of :mod:`rancf.kernels.records`."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "OBSTACLE_KINDS",
    "ContactBodyRecord",
    "ObstacleRecord",
    "ContactPairRecord",
    "BodyPairRecord",
    "ContactRecord",
]

#: Kinds of obstacles (``ObstacleKind``, ``src/cpp/contact/contact.hpp``).
OBSTACLE_KINDS = ("plane", "cylinder", "sphere")


@dataclass(frozen=True, eq=False)
class ContactBodyRecord:
    """A flexible body as contact reads it (``ContactBody``, ``src/cpp/contact/contact.hpp``):
    ``n_c`` Gauss points per element (0: in no pair with an obstacle), its tube ``radius``, the
    shape functions ``n`` and their ξ-derivatives ``n1`` ``(n_el, n_c, 4)``, the weights ``gw``
    ``(n_c)`` and ``w`` (Gauss weight × reference ``|r0'|``, ``(n_el, n_c)``); a body in contact
    with bodies also its elements' rational ``weights`` ``(n_el, 4)``, ``scales`` ``(n_el)`` and
    reference arc lengths ``arc0`` ``(n_el + 1)`` (else empty).  Arrays row-major."""

    n_c: int
    radius: float
    n: NDArray[np.float64]
    n1: NDArray[np.float64]
    gw: NDArray[np.float64]
    w: NDArray[np.float64]
    weights: NDArray[np.float64]
    scales: NDArray[np.float64]
    arc0: NDArray[np.float64]


@dataclass(frozen=True)
class ObstacleRecord:
    """An obstacle (``Obstacle``): its ``kind`` (one of :data:`OBSTACLE_KINDS`), the rigid
    ``body`` that carries it (-1: fixed), its ``point`` and ``direction`` (in the carrying
    body's frame if any) and its ``radius``."""

    kind: str
    body: int
    point: tuple[float, float, float]
    direction: tuple[float, float, float]
    radius: float


@dataclass(frozen=True)
class ContactPairRecord:
    """A flexible ``body`` on an ``obstacle`` (``ContactPair``): penalty ``stiffness`` ``k``
    [N/m²], ``onset`` ``d`` [m], Hunt–Crossley ``damping`` ``χ`` [s/m], Coulomb ``friction``
    ``μ``, its regularization ``slip_velocity`` ``ε`` [m/s] and the normal damping per length
    ``damping_normal`` ``c D`` [N s/m²]."""

    body: int
    obstacle: int
    stiffness: float
    onset: float
    damping: float
    friction: float
    slip_velocity: float
    damping_normal: float


@dataclass(frozen=True)
class BodyPairRecord:
    """Two flexible bodies ``a`` and ``b`` in contact (the same: self-contact; ``BodyPair``,
    ``src/cpp/contact/body_contact.hpp``): penalty ``stiffness``, ``onset``, Coulomb
    ``friction`` and its regularization ``slip_velocity``."""

    a: int
    b: int
    stiffness: float
    onset: float
    friction: float
    slip_velocity: float


@dataclass(frozen=True, eq=False)
class ContactRecord:
    """The contact of a system (``ContactSet``): one :class:`ContactBodyRecord` per flexible
    body, the obstacles, the body-obstacle pairs and the pairs of bodies.  The core builds its
    :class:`rancf.kernels._core.Contact` from it (``System.contact``)."""

    bodies: tuple[ContactBodyRecord, ...] = ()
    obstacles: tuple[ObstacleRecord, ...] = ()
    pairs: tuple[ContactPairRecord, ...] = ()
    body_pairs: tuple[BodyPairRecord, ...] = ()
