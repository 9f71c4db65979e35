"""Flat memoryviews of the engine's arrays (physics/flat.py): the same memory, read and
written as plain Python numbers, bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from termpool.physics.flat import flat


@pytest.mark.parametrize("dtype", [np.float64, np.int8, np.int16, np.int64])
def test_a_flat_view_reads_and_writes_the_arrays_own_memory(dtype):
    arr = np.zeros((3, 4), dtype=dtype)
    view = flat(arr)
    assert len(view) == arr.size
    arr[2, 1] = 7
    assert view[2 * 4 + 1] == 7 and type(view[9]) is (float if dtype == np.float64 else int)
    view[1 * 4 + 3] = -5
    assert arr[1, 3] == -5 and int(arr.sum()) == 2


def test_a_flat_view_keeps_every_bit_of_a_float():
    values = [math.inf, -0.0, 5e-324, 0.1 + 0.2, math.nan]
    arr = np.array(values)
    view = flat(arr)
    assert [math.copysign(1.0, x) for x in view.tolist()[:2]] == [1.0, -1.0]
    back = np.zeros(len(values))
    out = flat(back)
    for k, x in enumerate(view.tolist()):
        out[k] = x
    assert back.tobytes() == arr.tobytes()


def test_a_flat_view_of_a_strided_array_is_refused_and_an_empty_one_is_empty():
    with pytest.raises(ValueError, match="C-contiguous"):
        flat(np.zeros((4, 4))[:, 1])
    assert len(flat(np.zeros((1, 0)))) == 0
