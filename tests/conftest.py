"""Shared fixtures and Hypothesis settings."""

from __future__ import annotations

import os
import signal

import numpy as np
import pytest
from hypothesis import HealthCheck, settings

settings.register_profile(
    "rancf", max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "rancf"))

# A suite started as a background job (`.ci/run &` in a script) inherits Ctrl-C ignored
# (POSIX), and so would every command it starts: the signal tests, which interrupt commands,
# then saw runs that ignored Ctrl-C until their own handler was set. Ctrl-C is restored here.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

#: Paper Example 1 (planar pendulum): chord, angles (deg), interior point.
EXAMPLE1 = (0.5, (30.0, 40.0), (0.315, 0.077))
#: Paper Example 2 (spatial pendulum), angles restored in the docs/derivations/cable.md.
EXAMPLE2 = (0.5, (60.0, 30.0), (0.264, 0.069))
#: Paper Example 3 (vibration).
EXAMPLE3 = (0.5, (30.0, 30.0), (0.25, 0.067))


@pytest.fixture
def example1():
    from rancf.geometry.conic import conic_arc

    return conic_arc(*EXAMPLE1)


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
