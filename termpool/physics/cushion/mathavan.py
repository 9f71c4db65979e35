"""Mathavan, Jackson & Parkin (2010): the impact integrated in impulse, with friction at the nose
and on the slate.

"A theoretical analysis of billiard ball dynamics under cushion impacts", Proc. IMechE C 224
(2010). The cushion pushes along the tilted contact normal and the slate pushes up; both
contacts slide with Coulomb friction (mu_cushion at the nose, mu_slide on the cloth), the
slate's normal force being whatever keeps the ball on it. The impact is followed in steps of
the nose's normal impulse: compression until the ball stops moving into the cushion, then
restitution until the cushion has given back e^2 of the work it took (the energetic
coefficient of restitution). So the rebound depends on the spin all through the impact.

The impact is integrated in the slips, which is all the friction depends on: a = (a1, a2),
the nose's contact point sliding along the rail and up the nose, and b = (b1, b2), the
slate's contact point sliding along the rail and into the cushion; with vy, the speed into
the cushion. All impulses are per unit mass. A friction impulse j along a unit direction d
at the nose changes a by -j (3.5 d1, (2.5 + s^2) d2) and b by -j ((1 - 2.5 s) d1,
(2.5 - s) d2); one along e on the slate changes b by -3.5 j e and a by -j ((1 - 2.5 s) e1,
(2.5 - s) e2) (s, c: sine and cosine of the nose's angle above the ball's centre). The
velocities and spins come from the summed impulses at the end.

Cost and safety:
- A fixed step rule: the impulse step is a frictionless compression's impulse over STEPS,
  so an impact takes about STEPS steps per phase at any speed, and at most MAX_STEPS, after
  which the phase is finished by one frictionless impulse. Compression ends with the step
  whose normal impulse stops the ball; any speed into the cushion that step's friction gives
  back is taken away without friction. Each step applies the normal impulse, then the nose's
  friction, then the slate's, each along its contact's slip at that moment. First order:
  STEPS = 8 keeps the rebound within 1% of the speed in and 0.25 degrees of the converged
  answer for cushions like the game's (mu up to 0.2), within 1.5% and 1 degree for rough
  ones (mu 0.6).
- Each friction impulse is capped where it would stop its contact's slip (the least energy
  along the slip), so a sticking contact holds instead of chattering, and no friction impulse
  adds energy. The normal work is booked exactly as the change of vy^2 / 2, and the last
  step of each phase lands on its end, so the ball leaves with at most e^2 of the normal
  energy the cushion took: it never gains energy, and at e = 1 without friction it keeps it.
- Below `v_inelastic` the restitution is 0, as for every cushion; a ball that would still be
  moving into the cushion at the end is stopped there.
"""

from __future__ import annotations

import math
from typing import NamedTuple

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

# Restitution and nose friction when a scene gives none: the values Mathavan et al. fitted
# to their measured rebounds (snooker balls and cushions).
E_CUSHION = 0.98
MU_CUSHION = 0.14

STEPS = 8  # impulse steps of a frictionless compression (restitution takes about e * STEPS)
MAX_STEPS = 8 * STEPS  # per phase; a phase still running then is finished without friction
FEW = 32  # fewer balls than this are bounced one by one in floats: numpy's per-call cost
# over the steps outweighs the work (the two forms agree to the bit, so either may run)


# The rows of `_step`'s state, a row per quantity and a column per ball: the nose's and the
# slate's summed friction impulses (fi, fc) either side of the speed into the cushion and the
# slips, so that each friction impulse updates one run of rows (the nose's fi..b2, the
# slate's vy..fc2) in one call.
FI1, FI2, VY, A1, A2, B1, B2, FC1, FC2 = range(9)
_NOSE_D = [0, 1, 1, 0, 1, 0, 1, 1]  # d's component for each of rows FI1..B2 and `up`
_SLATE_E = [1, 0, 1, 0, 1, 0, 1]  # e's component for each of rows VY..FC2


class _Rows(NamedTuple):
    """What `_step` multiplies by, a row per ball: the slips' responses to friction
    (`_gains`) as gains of d (nose) or e (slate) component by component, each row's change
    being -j (gain d) (an added change has its gain negated: x + y is x - (-y), bit for bit);
    and the constants `_step` takes (numpy takes an array faster than a Python float, with
    the same result)."""

    s: np.ndarray  # the sine of the nose's angle above the ball's centre
    mu_w: np.ndarray  # the nose's friction
    mu_s: np.ndarray  # the slate's friction
    nose2: np.ndarray  # (2, n) 3.5, k2: the nose slip's own answer to its friction
    nose: np.ndarray  # (8, n) -1, -1, -s, 3.5, k2, x1, x2 (rows FI1..B2), c (the slate's load)
    slate: np.ndarray  # (7, n) 1, x1, x2, 3.5, 3.5, -1, -1 (rows VY..FC2)
    zero: np.ndarray
    one: np.ndarray
    three5: np.ndarray


def _step(dv, c, k: _Rows, st, go, new) -> tuple:
    """One impulse step on the rows of `st` (FI1..FC2) where `go` (None: every row): the
    normal part takes dv off vy, then friction at the nose and on the slate. Returns (the
    rows after it, room for the next: st and new in some order). k: the gains and constants
    (`_Rows`); new: room for the next rows. The same operations, element for element, as
    `_step_one`, in fewer calls."""
    zero, one, three5 = k.zero, k.one, k.three5
    x = new
    np.copyto(x, st)
    dp = dv / c
    x[VY] -= dv
    x[A2] += k.s * dv
    x[B2] -= dv
    a = x[A1:A2 + 1]
    sq = a * a
    slip = np.sqrt(sq[0] + sq[1])
    live = slip > zero
    d = a / np.where(live, slip, one)
    sq = k.nose2 * (d * d)
    j = np.minimum(k.mu_w * dp, slip / np.where(live, sq[0] + sq[1], one))
    change = j * (k.nose * d.take(_NOSE_D, axis=0))
    x[:B2 + 1] -= change[:-1]
    up = np.maximum(k.s * dp + change[-1], zero)
    b = x[B1:B2 + 1]
    sq = b * b
    slip = np.sqrt(sq[0] + sq[1])
    e = b / np.where(slip > zero, slip, one)
    j = np.minimum(k.mu_s * up, slip / three5)
    x[VY:] -= j * (k.slate * e.take(_SLATE_E, axis=0))
    if go is None:  # every row: the new rows are the next, st is room for the ones after
        return x, st
    np.copyto(st, x, where=go)
    return st, x


def _step_one(dv, s, c, k, mu_w, mu_s, st) -> tuple:
    """`_step` for one ball in plain floats, operation for operation: the next st (a tuple;
    np.minimum and np.maximum written out as vec.min_one and vec.max_one do them)."""
    vy, a1, a2, b1, b2, fi1, fi2, fc1, fc2 = st
    k2, x1, x2 = k
    dp = dv / c
    vy = vy - dv
    a2 = a2 + s * dv
    b2 = b2 - dv
    slip = math.sqrt(a1 * a1 + a2 * a2)
    if slip > 0.0:
        d1, d2 = a1 / slip, a2 / slip
        y = slip / (3.5 * (d1 * d1) + k2 * (d2 * d2))
    else:
        d1, d2 = a1 / 1.0, a2 / 1.0
        y = slip / 1.0
    x = mu_w * dp
    j = x if (x < y or x != x) else y
    a1 = a1 - j * (3.5 * d1)
    a2 = a2 - j * (k2 * d2)
    b1 = b1 - j * (x1 * d1)
    b2 = b2 - j * (x2 * d2)
    vy = vy + j * (s * d2)
    fi1 = fi1 + j * d1
    fi2 = fi2 + j * d2
    up = s * dp + j * (c * d2)
    if not (up > 0.0 or up != up):
        up = 0.0
    slip = math.sqrt(b1 * b1 + b2 * b2)
    safe = slip if slip > 0.0 else 1.0
    e1, e2 = b1 / safe, b2 / safe
    x, y = mu_s * up, slip / 3.5
    j = x if (x < y or x != x) else y
    return (vy - j * e2, a1 - j * (x1 * e1), a2 - j * (x2 * e2), b1 - j * (3.5 * e1),
            b2 - j * (3.5 * e2), fi1, fi2, fc1 + j * e1, fc2 + j * e2)


def _gains(s):
    """How the slips answer friction: an impulse j along d at the nose changes a by
    -j (3.5 d1, k2 d2) and b by -j (x1 d1, x2 d2); one along e on the slate changes b by
    -3.5 j e and a by -j (x1 e1, x2 e2). Returns (k2, x1, x2)."""
    return 2.5 + s * s, 1.0 - 2.5 * s, 2.5 - s


def bounce(n: np.ndarray, v: np.ndarray, w: np.ndarray, r: np.ndarray, m: np.ndarray,
           ph: CushionPhysics) -> tuple[np.ndarray, np.ndarray]:
    """Bounce balls off cushions with horizontal normals n (into the table); returns (v, w)."""
    if len(n) < FEW:
        rows = zip(n, v, w, r, m, strict=True)
        out = [bounce_one(*(x.tolist() for x in row), ph) for row in rows]
        return (np.array([o[0] for o in out]).reshape(-1, 2),
                np.array([o[1] for o in out]).reshape(-1, 3))
    return bounce_many(n, v, w, r, m, ph)


def bounce_many(n: np.ndarray, v: np.ndarray, w: np.ndarray, r: np.ndarray,
                m: np.ndarray, ph: CushionPhysics) -> tuple[np.ndarray, np.ndarray]:
    """`bounce` on arrays all the way (whatever their size)."""
    s, c = nose(r, ph.cushion_height)
    vx, vy, wx, wy, wz = to_rail(n, v, w)
    hit = vy > 0.0
    ee = np.where(vy > ph.v_inelastic, ph.e_cushion, 0.0)
    mu_w, mu_s = ph.mu_cushion, ph.mu_slide
    cdp = c * (vy / (c * STEPS))  # vy's fall in a step of the normal impulse alone
    zero = np.zeros_like(vy)
    st = np.array([zero, zero, vy, (vx + r * wy * s) - r * wz * c, r * wx - s * vy,
                   vx - r * wy, vy + r * wx, zero, zero])  # rows FI1..FC2
    k2, x1, x2 = _gains(s)
    three5, one = np.full_like(s, 3.5), np.ones_like(s)
    k = _Rows(s, np.full_like(s, mu_w), np.full_like(s, mu_s),
              np.array([three5, k2]), np.array([-one, -one, -s, three5, k2, x1, x2, c]),
              np.array([one, x1, x2, three5, three5, -one, -one]), zero, one, three5)
    half, two = np.full_like(s, 0.5), np.full_like(s, 2.0)
    new = np.empty_like(st)
    work = zero
    last = ~hit
    # Compression: until a step's normal impulse stops the ball moving into the cushion.
    # (A step of every ball, the usual one, needs no mask.)
    for _ in range(MAX_STEPS):
        go = ~last & (st[VY] > zero)
        count = np.count_nonzero(go)
        if not count:
            break
        every = count == go.size
        vy = st[VY]
        vn = vy - cdp
        last = last | ((vn <= zero) if every else (go & (vn <= zero)))
        vn = np.maximum(vn, zero)
        more = work + half * (vy * vy - vn * vn)
        work = more if every else np.where(go, more, work)
        st, new = _step(vy - vn, c, k, st, None if every else go, new)
    vy = st[VY]
    go = hit & (vy > 0.0)
    work = np.where(go, work + 0.5 * (vy * vy), work)
    st[VY] = np.where(go, 0.0, vy)
    # Restitution: until the cushion has given back e^2 of that work.
    rest = ee * ee * work
    for _ in range(MAX_STEPS):
        go = hit & (rest > zero)
        count = np.count_nonzero(go)
        if not count:
            break
        every = count == go.size
        vy = st[VY]
        vn = vy - cdp
        gain = half * (vn * vn - vy * vy)
        end = gain >= rest
        vn = np.where(end, -np.sqrt(vy * vy + two * rest), vn)
        less = np.where(end, zero, rest - gain)
        rest = less if every else np.where(go, less, rest)
        st, new = _step(vy - vn, c, k, st, None if every else go, new)
    vy = st[VY]
    vy = np.minimum(np.where(hit & (rest > 0.0), -np.sqrt(vy * vy + 2.0 * rest), vy), 0.0)
    q = 2.5 / r  # R m / I: spin per unit of friction impulse per unit mass
    fi1, fi2, fc1, fc2 = st[FI1], st[FI2], st[FC1], st[FC2]
    vo, wo = from_rail(n, vx - (fi1 + fc1), vy, wx - q * (fi2 + fc2),
                       wy - q * (s * fi1 - fc1), wz + q * (c * fi1))
    return np.where(hit[:, None], vo, v), np.where(hit[:, None], wo, w)


def bounce_one(n: list, v: list, w: list, r: float, m: float,
               ph: CushionPhysics) -> tuple[list, list]:
    """`bounce` for one ball in plain floats, bit-identical to it."""
    s, c = nose_one(r, ph.cushion_height)
    vx, vy, wx, wy, wz = to_rail_one(n, v, w)
    if not vy > 0.0:
        return list(v), list(w)
    ee = ph.e_cushion if vy > ph.v_inelastic else 0.0
    mu_w, mu_s = ph.mu_cushion, ph.mu_slide
    cdp = c * (vy / (c * STEPS))
    st = (vy, (vx + r * wy * s) - r * wz * c, r * wx - s * vy, vx - r * wy, vy + r * wx,
          0.0, 0.0, 0.0, 0.0)
    k = _gains(s)
    work = 0.0
    for _ in range(MAX_STEPS):
        vy = st[0]
        if not vy > 0.0:
            break
        vn = vy - cdp
        last = vn <= 0.0
        vn = max_one(vn, 0.0)
        work = work + 0.5 * (vy * vy - vn * vn)
        st = _step_one(vy - vn, s, c, k, mu_w, mu_s, st)
        if last:
            break
    vy = st[0]
    if vy > 0.0:
        work = work + 0.5 * (vy * vy)
        st = (0.0, *st[1:])
    rest = ee * ee * work
    for _ in range(MAX_STEPS):
        if not rest > 0.0:
            break
        vy = st[0]
        vn = vy - cdp
        gain = 0.5 * (vn * vn - vy * vy)
        if gain >= rest:
            vn, rest = -math.sqrt(vy * vy + 2.0 * rest), 0.0
        else:
            rest = rest - gain
        st = _step_one(vy - vn, s, c, k, mu_w, mu_s, st)
    vy = st[0]
    if rest > 0.0:
        vy = -math.sqrt(vy * vy + 2.0 * rest)
    q = 2.5 / r
    fi1, fi2, fc1, fc2 = st[5:]
    return from_rail_one(n, vx - (fi1 + fc1), min_one(vy, 0.0), wx - q * (fi2 + fc2),
                         wy - q * (s * fi1 - fc1), wz + q * (c * fi1))
