"""Defaults of ``rancf view`` that its command line shows before anything is drawn (kept apart
from :mod:`rancf.post.view`, so that building the command line imports neither NumPy nor the run
readers)."""

from __future__ import annotations

__all__ = ["DEFAULT_FRAMES"]

#: Default largest number of drawn times.
DEFAULT_FRAMES = 200
