"""The unloaded state a body gets by default: ``[mesh] stress_free = "auto"``.

A spatial cable element bends with the magnitude of its curvature, ``½ EI (|κ| − κ0)²``
(docs/derivations/cable.md sec. 6).  About a curved reference that law is the energy of a rod
without torsional stiffness, and where such a line is pulled straight its equilibrium is
ill-posed: straight is no minimum, and mesh-scale helices lower the energy without bound
(docs/derivations/cable.md sec. 8).  A line whose rest curvature carries a negligible moment
(a chain, a rope: drawn curved only as a start shape) is therefore unloaded straight by
default, with a note; every other body keeps its reference (:func:`resolve_stress_free`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rancf.kernels import _core

__all__ = ["REST_MOMENT_SHARE", "resolve_stress_free"]

#: The largest rest-curvature moment ``EI max κ0``, as a share of the weight's moment
#: ``w L² / 8``, of a spatial cable drawn curved that ``"auto"`` unloads straight.
REST_MOMENT_SHARE = 1e-3


def resolve_stress_free(
    choice: str, family: Any, kernel: Any, props: Any, gravity: ArrayLike | None
) -> tuple[str, str | None]:
    """The unloaded state of a body: ``choice`` unless it is ``"auto"``; then ``"straight"``
    (the kernel straightened in place, :meth:`rancf.kernels.cable.CableKernel.straighten`) for
    a spatial cable drawn curved whose rest-curvature moment is at most
    :data:`REST_MOMENT_SHARE` of its weight's moment,

    ``EI max κ0 <= 1e-3 · w L² / 8``,  ``w = ρA |g|``,  ``L`` its reference arc length

    (docs/derivations/cable.md sec. 8), else ``"reference"``.  Returns the state and, where
    ``"auto"`` chose straight, the note that says so.
    """
    if choice != "auto":
        return choice, None
    cable = family.cable_kernel(kernel)
    if cable is None or cable.dim != 3 or gravity is None:
        return "reference", None
    if not np.any(cable.kappa0 * cable.j0 > _core.CABLE_STRAIGHT):
        return "reference", None  # drawn straight: the same either way
    weight = props.rho_a * float(np.linalg.norm(np.asarray(gravity, dtype=float)))
    length = float(np.sum(cable.wj))
    rest, loads = props.ei * float(np.max(cable.kappa0)), weight * length**2 / 8.0
    if not rest <= REST_MOMENT_SHARE * loads:
        return "reference", None
    cable.straighten()
    note = (
        f'unloaded straight (mesh.stress_free = "auto"): a spatial cable drawn curved whose '
        f"rest curvature's moment EI max|k0| = {rest:.3g} N m is below {REST_MOMENT_SHARE:g} of "
        f"its weight's moment w L^2/8 = {loads:.3g} N m (a chain, a rope: the drawing is its "
        f'start shape); give mesh.stress_free = "reference" to unload it as drawn'
    )
    return "straight", note
