"""Ball motion states and the small helpers and tolerances the engine's parts share."""

from __future__ import annotations

import numpy as np

STATIONARY, SPINNING, SLIDING, ROLLING, POCKETED = range(5)
STATE_NAMES = ("stationary", "spinning", "sliding", "rolling", "pocketed")
# A slip this small (m/s) would slide for under 0.15 ms: it is completed at once (see
# Engine._snap), so a pair pressed together cannot chatter through endless tiny slides.
EPS_U = 1e-3
EPS_V = 1e-9  # m/s below which a ball counts as not translating
EPS_W = 1e-9  # rad/s of side spin below which a ball counts as still
CLUSTER_GAP = 1e-6  # m: balls (and cushions) this close count as touching in a cluster

_FLIP = np.array([-1.0, 1.0])


def norm(v: np.ndarray) -> np.ndarray:
    """Length of horizontal vectors (..., 2)."""
    return np.hypot(v[..., 0], v[..., 1])


def dots(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """(M, K) dot products of rows p (M, 2) with rows q (K, 2), written out: a matrix
    product goes through BLAS, whose last bits depend on the library and the processor."""
    return p[:, 0, None] * q[None, :, 0] + p[:, 1, None] * q[None, :, 1]


def perp(v: np.ndarray) -> np.ndarray:
    """z x v for horizontal vectors."""
    return v[..., ::-1] * _FLIP
