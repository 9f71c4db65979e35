"""Han (2005): one impulse at the nose, along the tilted contact normal, with Coulomb friction.

Han, "Dynamics in carom and three cushion billiards", J. Mech. Sci. Tech. 19 (2005). The nose
touches the ball above its centre, so the normal impulse is along the line from the contact
to the centre, tilted down by t: it reverses the contact's normal speed (vy cos t) times e, and
pushes the ball down into the slate, which absorbs that part. Friction at the nose acts on
the contact's slip before the impact (a sphere's normal impulse does not change it), capped
at mu times the normal impulse, or at the impulse that stops the slip (sticking). The slate
is not a second contact, so it takes no friction.

Two rules make the impulse safe where the model alone is not: below `v_inelastic` the
restitution is 0, and a ball that would still move into the cushion afterwards (e near 0,
or strong back spin) is stopped there instead: the tilted impulse alone takes only cos^2 t
of the normal speed away.
"""

from __future__ import annotations

import math

import numpy as np

from termpool.physics.cushion.model import CushionPhysics
from termpool.physics.cushion.rail import (
    from_rail,
    from_rail_one,
    nose,
    nose_one,
    to_rail,
    to_rail_one,
)
from termpool.physics.vec import max_one, min_one

# Restitution and nose friction when a scene gives none: nominal values, as pooltool uses
# them (Han fitted a speed-dependent e on a carom table).
E_CUSHION = 0.85
MU_CUSHION = 0.2


def bounce(n: np.ndarray, v: np.ndarray, w: np.ndarray, r: np.ndarray, m: np.ndarray,
           ph: CushionPhysics) -> tuple[np.ndarray, np.ndarray]:
    """Bounce balls off cushions with horizontal normals n (into the table); returns (v, w)."""
    s, c = nose(r, ph.cushion_height)
    vx, vy, wx, wy, wz = to_rail(n, v, w)
    ee = np.where(vy > ph.v_inelastic, ph.e_cushion, 0.0)
    p = (1.0 + ee) * m * (c * np.maximum(vy, 0.0))
    # Slip of the contact point, in the tangent plane: along the rail, and up the nose.
    a1 = (vx + r * wy * s) - r * wz * c
    a2 = r * wx - s * vy
    slip = np.sqrt(a1 * a1 + a2 * a2)
    j = np.minimum(ph.mu_cushion * p, slip * m / 3.5)
    live = slip > 0
    d1 = np.where(live, a1 / np.where(live, slip, 1.0), 0.0)
    d2 = np.where(live, a2 / np.where(live, slip, 1.0), 0.0)
    k = 2.5 * j / (m * r)
    vx = vx - j * d1 / m
    vy = np.minimum((vy - c * p / m) + j * s * d2 / m, 0.0)
    return from_rail(n, vx, vy, wx - k * d2, wy - k * s * d1, wz + k * c * d1)


def bounce_one(n: list, v: list, w: list, r: float, m: float,
               ph: CushionPhysics) -> tuple[list, list]:
    """`bounce` for one ball in plain floats, bit-identical to it."""
    s, c = nose_one(r, ph.cushion_height)
    vx, vy, wx, wy, wz = to_rail_one(n, v, w)
    ee = ph.e_cushion if vy > ph.v_inelastic else 0.0
    p = (1.0 + ee) * m * (c * max_one(vy, 0.0))
    a1 = (vx + r * wy * s) - r * wz * c
    a2 = r * wx - s * vy
    slip = math.sqrt(a1 * a1 + a2 * a2)
    j = min_one(ph.mu_cushion * p, slip * m / 3.5)
    d1, d2 = (a1 / slip, a2 / slip) if slip > 0 else (0.0, 0.0)
    k = 2.5 * j / (m * r)
    vx = vx - j * d1 / m
    vy = min_one((vy - c * p / m) + j * s * d2 / m, 0.0)
    return from_rail_one(n, vx, vy, wx - k * d2, wy - k * s * d1, wz + k * c * d1)
