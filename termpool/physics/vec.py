"""Small vector helpers the physics shares, in array and plain-float forms.

Products are written out component by component: np.cross is slow on small arrays, and a
matrix product goes through BLAS, whose last bits depend on the library and the processor.
The plain-float forms do the same operations in the same order as the array forms.
"""

from __future__ import annotations

import numpy as np

_FLIP = np.array([-1.0, 1.0])


def norm(v: np.ndarray) -> np.ndarray:
    """Length of horizontal vectors (..., 2)."""
    return np.hypot(v[..., 0], v[..., 1])


def columns(*rows: np.ndarray) -> np.ndarray:
    """(K, len(rows)) with the rows (K,) as its columns, C-ordered: np.stack(rows, axis=1)
    without its Python (a third of the time on small arrays)."""
    return np.array(rows).T.copy()


def length(v: np.ndarray) -> np.ndarray:
    """Lengths of rows v (K, C): np.linalg.norm(v, axis=1)'s operations (the squares summed
    along the row, then the root), without its Python."""
    return np.sqrt((v * v).sum(axis=1))


def dots(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """(M, K) dot products of rows p (M, 2) with rows q (K, 2)."""
    return p[:, 0, None] * q[None, :, 0] + p[:, 1, None] * q[None, :, 1]


def perp(v: np.ndarray) -> np.ndarray:
    """z x v for horizontal vectors."""
    return v[..., ::-1] * _FLIP


def any_by(mask: np.ndarray, owner: np.ndarray, count: int) -> np.ndarray:
    """(count,) True for each owner 0..count-1 that any True element of `mask` belongs to
    (`owner` gives each element's owner)."""
    return np.bincount(owner[mask], minlength=count) > 0


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise a x b of (K, 3) arrays."""
    ax, ay, az = a[:, 0], a[:, 1], a[:, 2]
    bx, by, bz = b[:, 0], b[:, 1], b[:, 2]
    return columns(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx)


def cross_one(a: list, b: list) -> list:
    """`cross` for one pair of 3-vectors in plain floats."""
    ax, ay, az = a
    bx, by, bz = b
    return [ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx]


def to3(v2: np.ndarray) -> np.ndarray:
    """Horizontal vectors (..., 2) as 3-vectors (..., 3) with z = 0."""
    return np.concatenate([v2, np.zeros(v2.shape[:-1] + (1,))], axis=-1)


# numpy's maximum and minimum give the second argument where the two are equal, so that
# np.maximum(-0.0, 0.0) is 0.0 and np.maximum(0.0, -0.0) is -0.0 (numpy 2 as measured; its
# documentation says np.where(a >= b, a, b)), and NaN where either is NaN.


def min_one(a: float, b: float) -> float:
    """np.minimum for two floats, bit for bit."""
    return a if (a < b or a != a) else b


def max_one(a: float, b: float) -> float:
    """np.maximum for two floats, bit for bit."""
    return a if (a > b or a != a) else b
