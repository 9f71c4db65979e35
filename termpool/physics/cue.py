"""Cue strike: speed, aim and tip offset -> the cue ball's velocity and spin."""

from __future__ import annotations

import math

MISCUE_OFFSET = 0.5  # tip offsets beyond half a radius slip off the ball


def clamp_tip(side: float, top: float) -> tuple[float, float]:
    """The tip offset (side, top) as it is, or moved in along its direction onto the miscue
    limit when it lies beyond it: every result is a tip offset `strike` accepts (the spin
    control and the strike share this one limit)."""
    if math.hypot(side, top) <= MISCUE_OFFSET:
        return side, top
    big = max(abs(side), abs(top))  # scaled to at most 1 first: the hypot of two huge
    side, top = side / big, top / big  # offsets would overflow
    off = math.hypot(side, top)
    side, top = side * MISCUE_OFFSET / off, top * MISCUE_OFFSET / off
    while math.hypot(side, top) > MISCUE_OFFSET:  # the scaling can round a hair outside
        side, top = math.nextafter(side, 0.0), math.nextafter(top, 0.0)
    return side, top


def strike(
    speed: float, angle_deg: float, side: float = 0.0, top: float = 0.0, radius: float = 0.028575
) -> tuple[tuple[float, float], tuple[float, float, float]]:
    """Return ((vx, vy), (wx, wy, wz)) right after a level cue strike.

    `speed` is the ball's speed after the strike; `side` and `top` are tip offsets in units of R
    (side > 0 right of centre as the shooter sees it, top > 0 above centre). The impulse J = m v
    acts at the offset, so the angular impulse gives w = (5 v / 2R) * offset about the matching
    axis: top 0.4 is natural roll, right english spins counter-clockwise seen from above.
    """
    for name, val in (("speed", speed), ("angle", angle_deg), ("side", side), ("top", top)):
        if not math.isfinite(val):
            raise ValueError(f"shot.{name}: must be finite")
    if speed < 0:
        raise ValueError("shot.speed: must not be negative")
    off = math.hypot(side, top)
    if off > MISCUE_OFFSET:
        raise ValueError(
            f"shot: tip offset {off:.2f} R is a miscue (keep side and top within {MISCUE_OFFSET} R)"
        )
    a = math.radians(angle_deg)
    dx, dy = math.cos(a), math.sin(a)
    k = 2.5 * speed / radius
    # Topspin axis is z x d = (-dy, dx); rolling then holds v = R (wy, -wx).
    return (speed * dx, speed * dy), (-k * top * dy, k * top * dx, k * side)
