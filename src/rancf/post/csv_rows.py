"""The rows of the run folders' CSV files: every number as ``%.12g``, comma separated.

:func:`write_rows` writes the bytes ``np.savetxt(fh, table, delimiter=",", fmt="%.12g")``
writes (the same ``%`` formatting of the same floats: a NumPy float formats as the Python float
it is), with one formatting of the whole table instead of one formatting and one write a row:
for a long run stored every step the files' rows cost a fifth of the time they took.
"""

from __future__ import annotations

from typing import IO

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["FORMAT", "write_rows"]

#: How every number of a CSV file is written.
FORMAT = "%.12g"


def write_rows(fh: IO[bytes], table: ArrayLike) -> None:
    """Append the rows of ``table`` (2-D; 1-D: one column) to the binary file ``fh``, each
    number as :data:`FORMAT`, ``,`` between them, ``\\n`` after each row (nothing for no
    rows)."""
    arr = np.asarray(table, dtype=float)
    if arr.ndim == 1:
        arr = arr[:, None]
    if arr.shape[0] == 0:
        return
    line = ",".join([FORMAT] * arr.shape[1]) + "\n"
    fh.write((line * arr.shape[0] % tuple(arr.ravel().tolist())).encode("latin1"))
