"""A ball that falls into a pocket: it is placed at the hole's centre, at rest and without spin,
and stays there (its state is POCKETED, which no motion leaves)."""

from __future__ import annotations

import numpy as np


def drop(centre: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Positions, velocities and spins of K balls dropped into holes with these centres."""
    return centre, np.zeros((len(centre), 2)), np.zeros((len(centre), 3))


def drop_one(centre: list) -> tuple[list, list, list]:
    """`drop` for one ball in plain floats."""
    return list(centre), [0.0, 0.0], [0.0, 0.0, 0.0]
