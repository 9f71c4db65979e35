"""Every contact the engine applies, checked as it is applied: the two balls (or the ball and
its cushion, jaw, tip or pocket hole) must touch, within the engine's tolerances.

`conftest.py` wraps `Engine._handle` with `checked_handle` for the whole suite, so every
ball-ball and cushion event of every test scene is checked, not only the recorded ones: a
contact applied at a distance (a root of the contact quartic placed wrongly) fails the test
that ran it.
"""

from __future__ import annotations

import numpy as np

from termpool.physics.roots import SINK, TOUCH
from termpool.physics.schedule import Due

# A contact is applied where the gap is at most TOUCH and the overlap at most 2 SINK (the
# engine's documented bounds, docs/physics.md), give or take rounding.
SLACK = 1e-11
DEEPEST = -2 * SINK - SLACK


class ContactAtADistance(AssertionError):
    pass


def _fail(what: str, t: float, gap: float) -> None:
    raise ContactAtADistance(f"{what} applied at t = {t!r} with a gap of {gap:.3e} m "
                             f"(allowed {DEEPEST:.1e} .. {TOUCH + SLACK:.1e})")


def _where(eng, b: int, i: int) -> np.ndarray:
    s = eng.ball_state(b, i)  # at the table's clock, which the engine has set to the event
    return np.array([s.x, s.y])


def check_events(eng, tabs: np.ndarray, code: np.ndarray) -> None:
    """Check the contacts about to be handled: tables `tabs`, event codes `code` (places in
    the engine's row of predictions, schedule.Due)."""
    tab = eng.table
    nseg, npt = len(tab.seg_a), len(tab.points)
    due, ball_i, ball_j = eng.schedule.decode(code)
    for b, q, i, j in zip(tabs.tolist(), due.tolist(), ball_i.tolist(), ball_j.tolist(),
                          strict=True):
        t = float(eng.tb[b])
        if q == Due.CUSHION:
            f = int(eng.f_cush[b, i])
            p = _where(eng, b, i)
            rc = float(eng.rc[b, i])
            if f < nseg:
                n, a = tab.seg_n[f], tab.seg_a[f]
                gap = float((p - a) @ n) - rc
                d = tab.seg_b[f] - a
                along = float((p - a) @ d) / float(d @ d)
                if not -1e-9 <= along <= 1 + 1e-9:
                    _fail(f"cushion {f} beyond its segment (along {along:.6f}) for ball {i}",
                          t, gap)
            elif f < nseg + npt:
                gap = float(np.hypot(*(p - tab.points[f - nseg]))) - rc
            else:
                k = f - nseg - npt
                gap = float(np.hypot(*(p - tab.hole_c[k]))) - float(tab.hole_r[k])
            if not DEEPEST <= gap <= TOUCH + SLACK:
                _fail(f"cushion feature {f} of ball {i}", t, gap)
        elif q == Due.PAIR:
            reach = float(eng.radius[b, i] + eng.radius[b, j])
            gap = float(np.hypot(*(_where(eng, b, j) - _where(eng, b, i)))) - reach
            if not DEEPEST <= gap <= TOUCH + SLACK:
                _fail(f"ball-ball contact {i}-{j}", t, gap)


def checked_handle(original):
    def handle(self, tabs, code):
        check_events(self, tabs, code)
        return original(self, tabs, code)

    return handle
