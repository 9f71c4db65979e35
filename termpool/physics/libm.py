"""exp, sin, cos, tan and atan2 with the same bits on every machine: the C library's, element
by element.

numpy picks its own vectorized code for these by the processor (on a machine with AVX-512 its
exp, sin, cos and tan are not the C library's, and differ from it in the last bit), so a shot
simulated on one machine would not replay bit for bit on another. The C library's functions
are the same on both (and Python's math calls them); on arrays of a few hundred values the
loop costs microseconds.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np


def _each(f: Callable[[float], float], x) -> np.ndarray:
    a = np.asarray(x, dtype=float)
    return np.fromiter(map(f, a.ravel().tolist()), float, a.size).reshape(a.shape)


def _exp(x: float) -> float:
    try:
        return math.exp(x)
    except OverflowError:  # as numpy gives it
        return math.inf


def _trig(f: Callable[[float], float]) -> Callable[[float], float]:
    def one(x: float) -> float:
        try:
            return f(x)
        except ValueError:  # of an infinity, as numpy gives it
            return math.nan
    return one


_SIN, _COS, _TAN = _trig(math.sin), _trig(math.cos), _trig(math.tan)


def exp(x) -> np.ndarray:
    """e**x of each element (an array of x's shape)."""
    a = np.asarray(x, dtype=float)
    return _each(math.exp if (a < 709.0).all() else _exp, a)  # (the guard only if needed)


def sin(x) -> np.ndarray:
    """sin x of each element."""
    return _each(_SIN, x)


def cos(x) -> np.ndarray:
    """cos x of each element."""
    return _each(_COS, x)


def tan(x) -> np.ndarray:
    """tan x of each element."""
    return _each(_TAN, x)


def arctan2(y, x) -> np.ndarray:
    """atan2(y, x) of each pair of elements (broadcast together)."""
    y, x = np.broadcast_arrays(np.asarray(y, dtype=float), np.asarray(x, dtype=float))
    out = map(math.atan2, y.ravel().tolist(), x.ravel().tolist())
    return np.fromiter(out, float, y.size).reshape(y.shape)
