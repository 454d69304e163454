"""Banded linear algebra with fixed (Dirichlet) entries.

Band storage is LAPACK's general form ``ab[ku + i - j, j] = A[i, j]`` with ``kl = ku``.  A fixed
entry ``i`` has its row and column replaced by the identity and a zero right-hand side, which
keeps the band and the symmetry.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import solve_banded, solveh_banded

__all__ = ["BandedSystem"]


class BandedSystem:
    """Solves band-stored systems of fixed size with some entries held at zero increment.

    Parameters
    ----------
    n : int
        Matrix size.
    ku : int
        Half bandwidth.
    fixed : ndarray of bool, shape (n,)
    """

    def __init__(self, n: int, ku: int, fixed: NDArray[np.bool_]) -> None:
        self.n, self.ku = n, ku
        self.fixed = np.asarray(fixed, dtype=bool)
        rows, cols = [], []
        for i in np.flatnonzero(self.fixed):
            j = np.arange(max(0, i - ku), min(n, i + ku + 1))
            rows.append(ku + i - j)  # row i of A
            cols.append(j)
            rows.append(np.arange(2 * ku + 1))  # column i of A
            cols.append(np.full(2 * ku + 1, i))
        self._rows = np.concatenate(rows) if rows else np.empty(0, dtype=int)
        self._cols = np.concatenate(cols) if cols else np.empty(0, dtype=int)
        self._diag = np.flatnonzero(self.fixed)
        self.n_factorizations = 0

    def constrain(self, ab: NDArray) -> NDArray:
        """Replace the fixed rows and columns by the identity (in place); returns ``ab``."""
        ab[self._rows, self._cols] = 0.0
        ab[self.ku, self._diag] = 1.0
        return ab

    def solve(self, ab: NDArray, rhs: NDArray) -> NDArray[np.float64]:
        """Solve ``A x = rhs`` with ``x[fixed] = 0`` (LU with partial pivoting, LAPACK gbsv)."""
        self.constrain(ab)
        b = np.array(rhs, dtype=float)
        b[self.fixed] = 0.0
        self.n_factorizations += 1
        return solve_banded((self.ku, self.ku), ab, b, overwrite_ab=True, check_finite=False)

    def solve_spd(self, ab: NDArray, rhs: NDArray) -> NDArray[np.float64]:
        """Solve a symmetric positive definite system (Cholesky, LAPACK pbsv) with fixed entries."""
        a = self.constrain(np.array(ab))
        b = np.array(rhs, dtype=float)
        b[self.fixed] = 0.0
        self.n_factorizations += 1
        return solveh_banded(a[: self.ku + 1], b, lower=False, check_finite=False)
