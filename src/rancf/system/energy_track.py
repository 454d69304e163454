"""The extremes of a dynamic run's stored energies, tracked as its rows are derived (a run
streamed to disk keeps no history in memory): what :mod:`rancf.post.energy_check` checks."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["EnergyTrack"]


@dataclass
class EnergyTrack:
    """Extremes of the stored states' energies as they are derived (rows seen twice are
    harmless): the first row's time and energies (kinetic, strain, gravity), the largest total
    energy and its time, the range of the gravity's and the largest magnitude of the three."""

    t0: float = np.inf
    first: tuple[float, float, float] = (0.0, 0.0, 0.0)
    e_max: float = -np.inf
    t_max: float = 0.0
    g_min: float = np.inf
    g_max: float = -np.inf
    magnitude: float = 0.0

    def add(self, t: ArrayLike, energy: ArrayLike) -> None:
        """Rows at times ``t (k,)`` with energies ``(k, 3)``: kinetic, strain, gravity (a row
        that is not finite counts as an infinite total)."""
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        if not tt.size:
            return
        e = np.asarray(energy, dtype=float).reshape(tt.size, 3)
        total = np.nan_to_num(e.sum(axis=1), nan=np.inf)
        if tt[0] < self.t0:
            self.t0, self.first = float(tt[0]), (float(e[0, 0]), float(e[0, 1]), float(e[0, 2]))
        i = int(np.argmax(total))
        if total[i] > self.e_max:
            self.e_max, self.t_max = float(total[i]), float(tt[i])
        finite = np.nan_to_num(e, nan=0.0)
        self.g_min = min(self.g_min, float(finite[:, 2].min()))
        self.g_max = max(self.g_max, float(finite[:, 2].max()))
        self.magnitude = max(self.magnitude, float(np.abs(finite).sum(axis=1).max()))

    @property
    def e0(self) -> float:
        """The first row's total energy."""
        return float(sum(self.first))

    @property
    def scale(self) -> float:
        """``S = K_0 + |U_strain,0| + (max U_gravity - min U_gravity)``: the first row's kinetic
        and strain energies and the range of the gravity's, which bound every energy of a
        motion nothing does work on."""
        span = self.g_max - self.g_min if self.g_max >= self.g_min else 0.0
        return abs(self.first[0]) + abs(self.first[1]) + span
