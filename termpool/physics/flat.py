"""Plain-number access to the engine's arrays, for the paths of one table and few balls.

Reading one element of an array, or writing one, is a numpy call that costs more than the
number it moves; a memoryview over the same memory reads and writes Python floats and ints
without numpy, and sees every write made through the array (and the array sees its writes).
The numbers are the same bits either way.
"""

from __future__ import annotations

import numpy as np


def flat(arr: np.ndarray) -> memoryview:
    """A 1-D memoryview over every element of C-contiguous `arr`, in row-major order."""
    if not arr.flags.c_contiguous:
        raise ValueError("flat: the array must be C-contiguous")
    if arr.size == 0:  # (memoryview cannot cast an empty shape; nothing is read from it)
        return memoryview(bytearray()).cast(arr.dtype.char)
    return memoryview(arr).cast("B").cast(arr.dtype.char)
