"""Element kernels: the compiled core (:mod:`rancf.kernels._core`) and the data it works on.

The core (C++17, ``src/cpp/``) holds every element formula once — cable 2D/3D and beam forces,
tangents and energies — together with banded assembly, the banded LU, the generalized-α Newton
step, the fixed-step loop and static Newton iterations.  The Python modules here prepare its
named input structures (:mod:`rancf.kernels.cable`, :mod:`rancf.kernels.beam`) and hold the
constant mass and gravity integrals.
"""

import rancf.kernels._core as _core

__all__ = ["_core"]
