"""The inertia of a cable whose material flows through its mesh: a winch at one end.

A winch pays the cable out of (or reels it onto) its drum at one end of the body.  The mesh
keeps its exact reference geometry; the material is spread uniformly over it
(docs/derivations/variable-length.md §2): the material at the mesh's arc fraction ``σ``
(measured from the body's start) moves through the mesh at ``σ̇ = ν d(σ)``, with ``ν = L̇ / L``
and ``d = 1 − σ`` for a winch at the start, ``d = −σ`` at the end.  Its velocity is
``v = S q̇ + ν d S_σ q`` and its acceleration (§2.2)

    a = S q̈ + 2 ν d S_σ q̇ + d (L̈/L − 2 ν²) S_σ q + ν² d² S_σσ q,

so the generalized inertia force ``∫ ρA Sᵀ a dm`` of the material outside the drum is

    λ M q̈ + 2 L̇ C1 q̇ + [(L̈ − 2 L̇² / L) C1 + (L̇² / L) C2] q,

and its kinetic energy ``½ ∫ ρA |v|² dm = ½ λ q̇ᵀ M q̇ + L̇ q̇ᵀ C1 q + ½ (L̇² / L) qᵀ D2 q``, with
the constant matrices (``S' = S_ξ``, ``J0 = |r0'|``, ``L_ref`` the reference arc length)

    C1 = ρA ∫ d Sᵀ S' dξ,
    C2 = ρA L_ref ∫ d² Sᵀ (S'' − (J0'/J0) S') / J0 dξ,
    D2 = ρA L_ref ∫ d² S'ᵀ S' / J0 dξ.

This module computes them once, in model coordinates and band storage (the mass matrix's).
Shape conventions as :mod:`rancf.kernels.cable`.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.elements.cable import cable_shape_functions
from rancf.errors import InputError
from rancf.geometry.quadrature import gauss_legendre
from rancf.kernels.cable import CableKernel

__all__ = ["ConvectiveMatrices", "convective_matrices", "arc_fractions_at_gauss_points"]

ConvectiveMatrices = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]


def arc_fractions_at_gauss_points(kernel: CableKernel) -> tuple[NDArray, float]:
    """The reference arc length fraction ``σ`` at every Gauss point ``(n_el, n_qp)`` and the
    reference length ``L_ref`` (a 16-point rule on ``[0, ξ_q]`` inside each element)."""
    xs, ws = gauss_legendre(16)
    xi = kernel.xi
    sub = (xi[:, None] * xs[None, :]).ravel()
    _, n1, _ = cable_shape_functions(kernel.weights, kernel.scales, sub)
    speed = np.linalg.norm(np.einsum("epk,ekd->epd", n1, kernel.reference), axis=-1)
    inner = (speed.reshape(kernel.n_el, xi.size, xs.size) * ws).sum(-1) * xi  # ∫_0^ξq J0
    j0 = kernel.reference_speed
    lengths = (kernel.gw[None, :] * j0).sum(1)
    total = float(lengths.sum())
    starts = np.r_[0.0, np.cumsum(lengths)[:-1]]
    return (starts[:, None] + inner) / total, total


def convective_matrices(model: Model, at: Literal["start", "end"]) -> ConvectiveMatrices:
    """``C1, C2, D2`` of the module docstring in band storage ``(2 ku + 1, n)``.

    Parameters
    ----------
    model : Model
        A cable body (``"rancf"`` or ``"ancf"`` elements, C¹).
    at : {"start", "end"}
        The end of the body at the winch.
    """
    k = model.family.cable_kernel(model.kernel)
    if k is None or model.reduction is not None:
        raise InputError(
            "winches.at",
            model.element,
            'a body of cable elements ("rancf" or "ancf") with mesh.continuity = "C1"',
        )
    if at not in ("start", "end"):
        raise InputError("winches.at", at, '"BODY:start" or "BODY:end"')
    sigma, l_ref = arc_fractions_at_gauss_points(k)
    d = 1.0 - sigma if at == "start" else -sigma
    a0 = np.einsum("eqk,ekd->eqd", k.n1, k.reference)
    b0 = np.einsum("eqk,ekd->eqd", k.n2, k.reference)
    j0 = np.linalg.norm(a0, axis=-1)
    dj0 = np.einsum("eqd,eqd->eq", a0, b0) / j0
    rho_a, gw = k.props.rho_a, k.gw
    c1 = rho_a * np.einsum("q,eq,eqk,eql->ekl", gw, d, k.n0, k.n1)
    s2 = k.n2 - (dj0 / j0)[..., None] * k.n1
    c2 = rho_a * l_ref * np.einsum("q,eq,eqk,eql->ekl", gw, d * d / j0, k.n0, s2)
    d2 = rho_a * l_ref * np.einsum("q,eq,eqk,eql->ekl", gw, d * d / j0, k.n1, k.n1)
    eye = np.eye(model.dim)
    out = []
    for m4 in (c1, c2, d2):
        el = np.einsum("ekl,ij->ekilj", m4, eye).reshape(model.n_el, model.nde, model.nde)
        out.append(np.ascontiguousarray(model.assemble_band(model.to_y_elements(el))))
    return out[0], out[1], out[2]
