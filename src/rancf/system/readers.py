"""What a sensor reads: a function of a block of output rows, returning its columns."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from numpy.typing import NDArray

__all__ = ["Block", "Reader", "NamedReader"]

#: Rows of outputs: ``(t, q, v, derived, energy)``.
Block = tuple[NDArray, NDArray, NDArray, dict[str, NDArray], NDArray]
#: A sensor's columns ``(k, n_columns)`` of a block of ``k`` rows.
Reader = Callable[[Block], NDArray]


@dataclass(frozen=True)
class NamedReader:
    """A reader that names its own columns (other sensors' columns are named by their table)."""

    read: Reader
    columns: list[str]

    def __call__(self, blk: Block) -> NDArray:
        return self.read(blk)
