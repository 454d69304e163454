"""The time functions of prescribed motions (supports' ``motion``, driven joints' ``angle``)
and their default build-up (:mod:`rancf.bodies.time_function`, T.6): a harmonic motion that
would start with a jump of its rate builds up smoothly, and says so in one line."""

from __future__ import annotations

from typing import Any

import numpy as np

from rancf.bodies.time_function import TimeFunction
from rancf.scenario.loads import HarmonicFunction, time_function

__all__ = ["motion_function", "BUILD_UP_PERIODS"]

#: The default build-up of a harmonic motion that would start with a jump of its rate, in
#: periods of the harmonic.
BUILD_UP_PERIODS = 2.0


def motion_function(v: Any, key: str) -> tuple[TimeFunction | None, str | None]:
    """The time function of a motion (a support's ``motion``, a joint's ``angle``) named
    ``key``, and the one-line note saying when it got its default build-up: a harmonic without
    ``build_up`` whose rate at ``t = 0`` is not zero (a jump from rest) builds up over
    :data:`BUILD_UP_PERIODS` periods."""
    if v is None:
        return None, None
    f = time_function(v)
    if not (isinstance(v, HarmonicFunction) and v.build_up is None):
        return f, None
    rate = np.atleast_1d(f.rate(0.0))
    if not np.any(np.abs(rate) > 1e-12 * max(1.0, float(np.max(np.abs(f.values))))):
        return f, None
    b = BUILD_UP_PERIODS / v.harmonic
    note = (f"{key}: the harmonic would start with a jump of its rate to "
            f"{float(np.max(np.abs(rate))):.3g}; it builds up over {b:g} s ({BUILD_UP_PERIODS:g} "
            f"periods; give build_up = 0 to start it at once)")  # fmt: skip
    return f.with_build_up(b), note
