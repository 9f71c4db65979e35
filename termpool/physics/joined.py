"""Balls pressed together move as one body: the forces of resting contacts.

When touching balls (or a ball and a cushion) neither close nor part and the cloth's friction
pushes them together (a cue ball that stopped against a row and still spins forward, a ball
driven into a rail by its spin), the contact carries a steady force instead of a train of tiny
collisions. `push` finds those forces for a group of touching balls: the smallest contact
forces lam >= 0 that leave no contact accelerating into itself (the complementarity problem of
`cluster.py`, on accelerations instead of velocities). Each ball then moves on a quadratic with
its cloth friction plus its contact forces.

Forces through a ball's centre do not turn it, so a sliding ball keeps its friction torque and
a rolling ball stays rolling (static friction carries it, and it answers a push as if 7/5 as
heavy). A ball at rest that is pushed starts to roll, against its rolling resistance, or stays
held where the push is too weak to move it. Cloth friction acts against each ball's slip (or,
rolling, its velocity); when contact forces turn that direction, the quadratic holds it fixed
and the motion is renewed after it has turned by TURN radians (or when the slip would pass
its smallest), which bounds the error. A push along the slip, as in a straight line of balls,
never turns it: then the motion is exact and ends at the exact time the slip or the speed
runs out.

`Groups` keeps which balls of each table move so: any event of a grouped ball renews the whole
group's motion, since its contact forces change with it.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from termpool.physics import libm
from termpool.physics.balls import Balls
from termpool.physics.cluster import PLAIN, TOL, Rows, inelastic_plain, solve_inelastic, solve_psd
from termpool.physics.flat import flat
from termpool.physics.motion import Col
from termpool.physics.params import Physics
from termpool.physics.roots import A_MIN
from termpool.physics.schedule import Due
from termpool.physics.state import EPS_V, EPS_W, ROLLING, SLIDING, SPINNING, STATIONARY
from termpool.physics.vec import any_by
from termpool.physics.vec import norm as _norm
from termpool.physics.vec import perp as _perp

TURN = 0.01  # rad: a fixed friction direction is renewed after the true one turns this far
TURN_ROLL = 0.2  # rad: the same for a rolling ball's resistance, 20 times weaker
ROLL_MASS = 1.4  # a rolling ball pushed through its centre answers as if 7/5 as heavy
EPS_SLIP = 1e-7  # m/s: a slip this small is completed at once (within 50 ns here, where a
# pressed ball slides to the end of its slip, unlike state.EPS_U for free balls)
BLOCKS = 64  # groups whose contact matrices are built at once (bounds the temporaries)
SETTLE = 1e-3  # s: a rolling ball in a group that would be braked to rest this soon rests
EPS_TURNED = 3.5e-5  # m/s: a slip the contact forces turn ends at once below this (the
# completion moves the ball's velocity by u / 3.5, at most 1e-5 m/s)


def _renewal(x: np.ndarray, k: np.ndarray, turn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """How long x + k t (rows) may be taken as keeping its direction: the exact time it
    reaches zero when it runs straight to zero (inf when it never shrinks); the time it
    passes closest to zero when it runs within `turn` of straight at it (it turns fast
    there); else the time it has turned by `turn` (rows). Returns (time, straight)."""
    xx = (x * x).sum(axis=1)
    kk = (k * k).sum(axis=1)
    d = (x * k).sum(axis=1)
    c = np.abs(x[:, 0] * k[:, 1] - x[:, 1] * k[:, 0])
    size = np.sqrt(xx * kk)
    live = (kk > 0) & (xx > 0)
    straight = (c <= 1e-12 * size) | ~live
    near = ~straight & (d < 0) & (c < libm.sin(turn) * size)
    with np.errstate(divide="ignore", invalid="ignore"):
        to_zero = np.where(d < 0, np.sqrt(xx / kk), np.inf)
        tan = libm.tan(turn)
        den = c - d * tan
        turn = np.where(den > 0, tan * xx / den, np.inf)
        least = -d / kk
    out = np.where(straight, to_zero, np.where(near, least, turn))
    return np.where(live, out, np.inf), straight


def push(ph: Physics, v: np.ndarray, w: np.ndarray, R: np.ndarray, m: np.ndarray,
         rate: np.ndarray, rows: list) -> tuple:
    """Motion of M balls held by resting contacts.

    v, w: (M, 2), (M, 3) velocities and spins; R, m, rate: radii, masses, side-spin decay rates.
    rows: contacts (a, c, n, bend): ball a, ball c or -1 for a cushion, the unit normal
    pushing a away from c, and the separating acceleration the contact has without forces
    from its curvature (|relative tangential velocity|^2 / distance).
    Returns (v, acc, alpha, state, duration, w): the velocities (balls at rest exactly at
    rest), the accelerations, the rates of change of (wx, wy), the motion states, how long
    each motion holds, and the spins (rolling balls' kept exact).
    """
    g = ph.g
    M = len(m)
    v_in, w_in = v, w
    a_idx = np.array([r[0] for r in rows], dtype=np.int64)
    c_idx = np.array([r[1] for r in rows], dtype=np.int64)
    normal = np.array([r[2] for r in rows], dtype=float).reshape(-1, 2)
    bend = np.array([r[3] for r in rows], dtype=float)
    J = Rows(a_idx, c_idx, normal, M)
    v, w, rolled = _trim_slip(ph, v, w, R)
    settled = np.zeros(M, dtype=bool)
    for _ in range(M + 1):
        v = _resting(v, np.where(settled, 0.0, 1.0 / m), J)
        # A rolling ball whose speed the contacts trimmed rolls on (its spin follows), as
        # a rolling ball pushed through its centre does.
        w[:, :2] = np.where(rolled[:, None], _perp(v) / R[:, None], w[:, :2])
        u, vs, sliding, rolling, rest, safe_u, free, inv = _free(ph, v, w, R, m)
        acc = _solve(free, inv, J, bend)
        # A slow rolling ball that the forces brake to rest within SETTLE rests now (its
        # partners' speeds into it taken out with it): pushed off its line it would
        # otherwise approach rest in ever shorter renewals.
        brake = -(v * acc).sum(axis=1)
        settle = rolling & (brake > 0) & (vs * vs < brake * SETTLE)
        if not settle.any():
            break
        v = np.where(settle[:, None], 0.0, v)
        settled |= settle
    held = np.zeros(M, dtype=bool)
    resisted = np.zeros(M, dtype=bool)
    for _ in range(2 * M + 2 if rest.any() else 0):
        # A ball at rest that is pushed rolls, against its rolling resistance; where the
        # resistance wins (the ball would move backwards) it is held where it is.
        start = rest & ~held & ~resisted & (_norm(acc) > A_MIN) & (ph.mu_roll > 0)
        stop = resisted & ~held & ((free * acc).sum(axis=1) >= 0)
        if not (start.any() or stop.any()):
            break
        size = np.where(start, _norm(acc), 1.0)[:, None]
        free = np.where(start[:, None], -ph.mu_roll * g * acc / size, free)
        resisted |= start
        held |= stop
        free = np.where(held[:, None], 0.0, free)
        acc = _solve(free, np.where(held, 0.0, inv), J, bend)
    m_ = _motions(ph, v, w, R, u, acc, sliding, rolling, rest, held, safe_u)
    ends = _ending(m_, sliding, safe_u)
    if ends.any():  # those slips completed, the group pushed again from the start
        return push(ph, *_completed(v_in, w_in, R, ends), R, m, rate, rows)
    if m_.turning.any():
        free, spin_acc = _at_middle(ph, R, m_, sliding, free)
        acc = _solve(free, np.where(held, 0.0, inv), J, bend)
        acc = np.where((rest & ~m_.pushed)[:, None], 0.0, acc)
        m_ = m_._replace(acc=acc, spin_acc=spin_acc)
    return _states(m_, rest, sliding, rate, R)


def _ending(m_: _Motion, sliding, safe_u) -> np.ndarray:
    """Sliding balls whose slip the contact forces turn, under EPS_TURNED: renewed each
    time it turns TURN, such a slip approaches its end in ever shorter pieces (hundreds of
    renewals in a geometric series); it ends now instead. A slip the forces do not turn
    runs to its exact end in one piece."""
    return sliding & m_.turning & (safe_u[:, 0] <= EPS_TURNED)


def _completed(v, w, R, ends) -> tuple:
    """(v, w) with the slips of balls `ends` completed as cloth friction would complete them
    (v -= u / 3.5, rolling on): copies."""
    u = v + R[:, None] * _perp(w[:, :2])
    v = np.where(ends[:, None], v - u / 3.5, v)
    w = w.copy()
    w[:, :2] = np.where(ends[:, None], _perp(v) / R[:, None], w[:, :2])
    return v, w


def _trim_slip(ph: Physics, v, w, R) -> tuple:
    """A slip too small to slide on (state.EPS_U) completed at once, as motion.snap does:
    the ball rolls on with the speed the slide would have left it. Returns (v, w, rolled):
    w a copy, rolled the balls rolling after it."""
    us = _norm(v + R[:, None] * _perp(w[:, :2]))
    v, w = _completed(v, w, R, (us <= EPS_SLIP) & (us > 0) & (ph.mu_slide > 0))
    return v, w, _norm(v + R[:, None] * _perp(w[:, :2])) <= EPS_SLIP


def _free(ph: Physics, v, w, R, m) -> tuple:
    """Each ball's slip and motion, and the forces on it but its contacts': (u, |v|,
    sliding, rolling, rest, |u| where sliding (else 1), free forces, inverse masses as the
    contacts see them: a rolling ball pushed through its centre answers ROLL_MASS times as
    heavy)."""
    g = ph.g
    u = v + R[:, None] * _perp(w[:, :2])
    us, vs = _norm(u), _norm(v)
    sliding = us > (EPS_SLIP if ph.mu_slide > 0 else 0.0)
    rolling = ~sliding & (vs > EPS_V)
    rest = ~sliding & ~rolling
    safe_u = np.where(sliding, us, 1.0)[:, None]
    safe_v = np.where(rolling, vs, 1.0)[:, None]
    free = np.where(sliding[:, None], -ph.mu_slide * g * u / safe_u,
                    np.where(rolling[:, None], -ph.mu_roll * g * v / safe_v, 0.0))
    inv = np.where(sliding, 1.0, 1.0 / ROLL_MASS) / m
    return u, vs, sliding, rolling, rest, safe_u, free, inv


class _Motion(NamedTuple):
    """The pushed balls' motions as first predicted (see `_motions`)."""

    pushed: np.ndarray
    acc: np.ndarray
    v: np.ndarray
    w: np.ndarray
    roll: np.ndarray
    spin_acc: np.ndarray
    moving: np.ndarray
    rate_of: np.ndarray
    duration: np.ndarray
    turning: np.ndarray


def _motions(ph: Physics, v, w, R, u, acc, sliding, rolling, rest, held, safe_u) -> _Motion:
    """From the contacts' accelerations: which balls at rest are pushed, the velocities
    (balls at rest exactly at rest), spins, each sliding ball's alpha, how long each motion
    holds, and where the friction's direction turns within it."""
    g = ph.g
    pushed = rest & ~held & (_norm(acc) > A_MIN)
    acc = np.where((rest & ~pushed)[:, None], 0.0, acc)
    v = np.where(rest[:, None], 0.0, v)  # a ball at rest starts from rest, pushed or not
    w = w.copy()
    roll = rolling | pushed
    w[:, :2] = np.where(roll[:, None], _perp(v) / R[:, None],
                        np.where((rest & ~pushed)[:, None], 0.0, w[:, :2]))
    uhat = u / safe_u
    spin_acc = (2.5 * ph.mu_slide * g / R)[:, None] * _perp(uhat)  # a sliding ball's alpha
    # How long each motion holds: the slip of a sliding ball changes at acc + R z x alpha,
    # the velocity of a rolling one at acc.
    slip_rate = acc + R[:, None] * _perp(spin_acc)
    moving, rate_of = np.where(sliding[:, None], u, v), np.where(sliding[:, None], slip_rate, acc)
    # The direction of a rolling ball's resistance may err as far as a sliding ball's friction
    # may err in force: a turn TURN x mu_s / mu_r (at most TURN_ROLL).
    turn = np.where(sliding, TURN, TURN_ROLL)
    duration, straight = _renewal(moving, rate_of, turn)
    duration = np.where(sliding | roll, duration, np.inf)
    turning = (sliding | rolling) & ~straight & np.isfinite(duration)
    return _Motion(pushed, acc, v, w, roll, spin_acc, moving, rate_of, duration, turning)


def _at_middle(ph: Physics, R, m_: _Motion, sliding, free) -> tuple:
    """Where the friction's direction turns, it is taken at the middle of the motion's time
    (the direction there as first predicted), which makes the error second order in TURN:
    the free forces and sliding balls' alphas so taken (the contacts' forces are the
    caller's to solve again)."""
    g, turning = ph.g, m_.turning
    mid = m_.moving + m_.rate_of * (0.5 * np.where(turning, m_.duration, 0.0))[:, None]
    size = np.where(turning, _norm(mid), 1.0)[:, None]
    mu = np.where(sliding, ph.mu_slide, ph.mu_roll)[:, None]
    free = np.where(turning[:, None], -mu * g * mid / size, free)
    spin_acc = np.where(turning[:, None],
                        (2.5 * ph.mu_slide * g / R)[:, None] * _perp(mid / size), m_.spin_acc)
    return free, spin_acc


def _states(m_: _Motion, rest, sliding, rate, R) -> tuple:
    """`push`'s result from the motions: (v, acc, alpha, state, duration, w), a ball left at
    rest spinning down on its side spin."""
    acc, w, duration = m_.acc, m_.w, m_.duration
    alpha = np.where(sliding[:, None], m_.spin_acc, _perp(acc) / R[:, None])
    wz = np.abs(w[:, 2])
    spinning = rest & ~m_.pushed & (wz > EPS_W)
    duration = np.where(spinning, wz / rate, duration)
    w[:, 2] = np.where(rest & ~m_.pushed & ~spinning, 0.0, w[:, 2])
    state = np.where(sliding, SLIDING, np.where(m_.roll, ROLLING,
                                                np.where(spinning, SPINNING, STATIONARY)))
    return m_.v, acc, alpha, state, duration, w


def blocks(J: Rows, starts: np.ndarray, counts: np.ndarray, k: np.ndarray) -> list:
    """`Rows.matrix(k)` of each of several sets of rows at once: the rows of set q are
    J's rows starts[q] to starts[q] + counts[q], and touch no ball of another set. Element
    for element the same operations as `Rows.matrix`, so the same bits."""
    out = []
    for A, ct in _padded(J, starts, counts, k):
        out += [A[q, :r, :r] for q, r in enumerate(ct)]
    return out


def _padded(J: Rows, starts: np.ndarray, counts: np.ndarray, k: np.ndarray):
    """`blocks`' matrices, BLOCKS sets at a time: (matrices padded to the largest set of
    them, their sets' sizes as a list)."""
    for s in range(0, len(starts), BLOCKS):
        st, ct = starts[s:s + BLOCKS], counts[s:s + BLOCKS]
        top = int(ct.max()) if ct.size else 0
        j = np.arange(top)
        idx = np.where(j < ct[:, None], st[:, None] + j, 0)  # padding: any row, then cut off
        a, c, n, ball = J.a[idx], J.c[idx], J.n[idx], J.ball[idx]
        # n_i . n_j as numpy's two-term sum adds it (from 0.0: -0.0 comes out 0.0)
        nn = (0.0 + n[:, :, None, 0] * n[:, None, :, 0]) + n[:, :, None, 1] * n[:, None, :, 1]
        # The signs -1, 0, 1 in small ints: exact as floats, and cheaper to build.
        by_a = (a[:, None, :] == a[:, :, None]).astype(np.int8) - (c[:, None, :] == a[:, :, None])
        by_c = (c[:, None, :] == c[:, :, None]).astype(np.int8) - (a[:, None, :] == c[:, :, None])
        kc = np.where(ball, k[np.maximum(c, 0)], 0.0)
        yield (k[a][:, :, None] * (nn * by_a)
               + kc[:, :, None] * (nn * np.where(ball[:, :, None], by_c, 0))), ct.tolist()


class Sets:
    """Groups pushed at once: ball b belongs to group `ball_group[b]`, the rows of group q
    are J's rows starts[q] to starts[q] + counts[q]."""

    def __init__(self, J: Rows, ball_group: np.ndarray, row_group: np.ndarray,
                 count: int) -> None:
        self.J, self.ball_group, self.row_group, self.count = J, ball_group, row_group, count
        self.counts = np.bincount(row_group, minlength=count)
        self.starts = np.concatenate([[0], np.cumsum(self.counts)[:-1]]).astype(np.int64)
        self.first = self.starts.tolist()
        self._key: bytes | None = None  # the inverse masses of the matrices kept in _mats
        self._mats: dict[int, list] = {}

    def matrices(self, k: np.ndarray, q_list: list[int]) -> list:
        """The contact matrices of groups q_list for inverse masses k (`blocks`), cut to the
        rows with anything that can move (as np.abs(A).sum(axis=1) > 0 keeps them): (those
        rows, the cut matrix's columns as lists, or its rows when it is too large for plain
        floats), each group's built once for the same k (push solves again with the same
        masses after turning the forces)."""
        key = k.tobytes()
        if key != self._key:
            self._key, self._mats = key, {}
        need = [q for q in q_list if q not in self._mats]
        if need:
            q_need = np.array(need, dtype=np.int64)
            at = 0
            for A, ct in _padded(self.J, self.starts[q_need], self.counts[q_need], k):
                # A row's sum of magnitudes over its set's columns (the padding's are left
                # out) is positive where any is: in any order, whatever the rounding.
                inside = np.arange(A.shape[1]) < np.array(ct)[:, None]
                moves = (np.where(inside[:, None, :], np.abs(A), 0.0).sum(axis=2) > 0).tolist()
                by_col = A.transpose(0, 2, 1).tolist()
                for q, r, AT, mv in zip(need[at:at + len(ct)], ct, by_col, moves, strict=True):
                    live = [i for i in range(r) if mv[i]]
                    if len(live) == r:
                        cols = [col[:r] for col in AT[:r]]
                    else:
                        cols = [[AT[j][i] for i in live] for j in live]
                    if len(live) > PLAIN:  # rows, for the array solve
                        cols = [list(row) for row in zip(*cols, strict=True)]
                    self._mats[q] = (live, cols)
                at += len(ct)
        return [self._mats[q] for q in q_list]

    def rows(self, q: int) -> slice:
        return slice(int(self.starts[q]), int(self.starts[q] + self.counts[q]))

    def solve(self, free, k, bend, chosen: np.ndarray) -> np.ndarray:
        """`_solve` for the groups `chosen` (bools per group): their balls' accelerations,
        each group's contact forces found on its own (other balls: anything). The groups'
        few contacts are solved in plain floats, as `solve_inelastic` does."""
        J = self.J
        q_list = chosen.nonzero()[0].tolist()
        b = (J.speeds(free) + bend).tolist()
        lam = [0.0] * len(J)
        for q, (live, A) in zip(q_list, self.matrices(k, q_list), strict=True):
            # Rows with nothing that can move carry no force.
            if not live:
                continue
            s = self.first[q]
            n = len(live)
            every = live[-1] == n - 1  # (live is ascending: then it is every row)
            bl = b[s:s + n] if every else [b[s + i] for i in live]
            if n > PLAIN:
                part = solve_inelastic(np.array(A, dtype=float), np.array(bl, dtype=float))
                part = part.tolist()
            else:
                part = inelastic_plain(A, bl, TOL)
            if every:
                lam[s:s + n] = part
            else:
                for i, x in zip(live, part, strict=True):
                    lam[s + i] = x
        return free + J.spread(np.array(lam, dtype=float).reshape(len(J)), k)

    def resting(self, v, k) -> np.ndarray:
        """`_resting` of every group."""
        J = self.J
        u = J.speeds(v)
        need = any_by(np.abs(u) > EPS_V, self.row_group, self.count)
        if not need.any():
            return v
        q_list = need.nonzero()[0]
        lam = np.zeros(len(J))
        for q, A in zip(q_list.tolist(), blocks(J, self.starts[q_list], self.counts[q_list], k),
                        strict=True):
            rows = self.rows(q)
            lam[rows] = solve_psd(A, -u[rows])
        return np.where(need[self.ball_group][:, None], v + J.spread(lam, k), v)


def push_many(ph: Physics, v: np.ndarray, w: np.ndarray, R: np.ndarray, m: np.ndarray,
              rate: np.ndarray, sets: Sets, bend: np.ndarray) -> tuple:
    """`push` of several groups at once: balls and rows as `sets` orders them (group by
    group; a row's balls are its group's), with the contacts' bends. The same operations
    ball by ball and row by row, each group's forces solved on its own, so the same bits as
    `push` group by group; a group whose rolling balls the forces brake to rest (the rare
    second round of `push`) is pushed by `push` itself. Returns `push`'s arrays."""
    g = ph.g
    J, grp = sets.J, sets.ball_group
    v_in, w_in = v, w
    v, w, rolled = _trim_slip(ph, v, w, R)
    v = sets.resting(v, 1.0 / m)
    w[:, :2] = np.where(rolled[:, None], _perp(v) / R[:, None], w[:, :2])
    u, vs, sliding, rolling, rest, safe_u, free, inv = _free(ph, v, w, R, m)
    every = np.ones(sets.count, dtype=bool)
    acc = sets.solve(free, inv, bend, every)
    brake = -(v * acc).sum(axis=1)
    again = any_by(rolling & (brake > 0) & (vs * vs < brake * SETTLE), grp, sets.count)
    held = np.zeros(len(m), dtype=bool)
    resisted = np.zeros(len(m), dtype=bool)
    # The pushed balls at rest, group by group, each for as many rounds as `push` allows.
    live = any_by(rest, grp, sets.count)
    limit = 2 * np.bincount(grp, minlength=sets.count) + 2
    rounds = 0
    while live.any():
        start = rest & ~held & ~resisted & (_norm(acc) > A_MIN) & (ph.mu_roll > 0)
        stop = resisted & ~held & ((free * acc).sum(axis=1) >= 0)
        live &= any_by(start | stop, grp, sets.count) & (rounds < limit)
        if not live.any():
            break
        mine = live[grp]
        start &= mine
        stop &= mine
        size = np.where(start, _norm(acc), 1.0)[:, None]
        free = np.where(start[:, None], -ph.mu_roll * g * acc / size, free)
        resisted |= start
        held |= stop
        free = np.where(held[:, None], 0.0, free)
        acc = np.where(mine[:, None], sets.solve(free, np.where(held, 0.0, inv), bend, live),
                       acc)
        rounds += 1
    m_ = _motions(ph, v, w, R, u, acc, sliding, rolling, rest, held, safe_u)
    # A group with a slip to end now (`_ending`) is pushed by `push` itself, as above.
    again |= any_by(_ending(m_, sliding, safe_u), grp, sets.count)
    bent = any_by(m_.turning, grp, sets.count)
    if bent.any():
        free, spin_acc = _at_middle(ph, R, m_, sliding, free)
        acc = np.where(bent[grp][:, None], sets.solve(free, np.where(held, 0.0, inv), bend, bent),
                       m_.acc)
        acc = np.where((rest & ~m_.pushed)[:, None], 0.0, acc)
        m_ = m_._replace(acc=acc, spin_acc=spin_acc)
    v, acc, alpha, state, duration, w = _states(m_, rest, sliding, rate, R)
    out = [v, acc, alpha, state, duration, w]
    for q in again.nonzero()[0].tolist():  # push's second round: push itself
        balls = (grp == q).nonzero()[0]
        rows = sets.rows(q)
        first = int(balls[0])
        one = [(int(a) - first, int(c) - first if c >= 0 else -1, n, bb) for a, c, n, bb in
               zip(J.a[rows], J.c[rows], J.n[rows], bend[rows], strict=True)]
        for x, y in zip(out, push(ph, v_in[balls], w_in[balls], R[balls], m[balls],
                                  rate[balls], one), strict=True):
            x[balls] = y
    return tuple(out)


def _resting(v, k, J: Rows) -> np.ndarray:
    """v with the contacts' normal speeds (a micrometre per second at most, left by the
    solve of slow contacts) taken out by the least change weighted by inverse masses k:
    a resting contact neither closes nor parts, else the force that holds it would hold a
    ball creeping away for ever."""
    if len(J) == 0:
        return v
    u = J.speeds(v)
    if not (np.abs(u) > EPS_V).any():  # slower than a ball at rest: nothing creeps
        return v
    return v + J.spread(solve_psd(J.matrix(k), -u), k)


def _solve(free, k, J: Rows, bend):
    """Accelerations of balls with free accelerations `free` and inverse masses k under the
    contact rows J: the smallest forces lam >= 0 with no contact accelerating into itself."""
    if len(J) == 0:
        return free
    A = J.matrix(k)
    b = J.speeds(free) + bend
    # Rows with nothing that can move (a held ball against a rail) carry no force.
    live = np.abs(A).sum(axis=1) > 0
    lam = np.zeros(len(J))
    if live.any():
        lam[live] = solve_inelastic(A[np.ix_(live, live)], b[live])
    return free + J.spread(lam, k)


class Groups:
    """The groups of B tables: a label per ball (-1: in no group) and, per table, how many balls
    are grouped, so that tables without any pay nothing. `tb` is the tables' clocks."""

    def __init__(self, physics: Physics, balls: Balls, tb: np.ndarray) -> None:
        self.physics, self.balls, self.tb = physics, balls, tb
        self.label = np.full((balls.B, balls.N), -1, dtype=np.int64)
        self.count = np.zeros(balls.B, dtype=np.int64)
        self.flat_count = flat(self.count)  # (flat.py: read without a numpy call)

    def involved(self, tabs, i, j, due):
        """Events (by position in the pass) that involve a grouped ball, or None if no table
        of the pass has a group (the usual case, decided without array work)."""
        if (not self.count[int(tabs[0])]) if tabs.size == 1 else not self.count[tabs].any():
            return None
        out = (self.label[tabs, i] >= 0) & (due != Due.CHECK)
        pair = due == Due.PAIR
        out[pair] |= self.label[tabs[pair], j[pair]] >= 0
        return out

    def members(self, b: int, i: int) -> list[int]:
        """The balls of ball i's group (itself alone if it has none)."""
        g = int(self.label[b, i])
        if g < 0:
            return [i]
        return (self.label[b] == g).nonzero()[0].tolist()

    def break_up(self, tabs, i, j, due, involved) -> tuple[list, list]:
        """A fast contact or bounce of a grouped ball breaks its group: the others move freely
        again (those still pressed together are joined again as their predictions find them:
        a cheap step where a break's impacts cross a group). Returns the balls set moving
        anew, (tables, balls) arrays, for their predictions."""
        sel = (involved & (due >= Due.CUSHION)).nonzero()[0]
        if not sel.size:
            return [], []
        tb = tabs[sel]
        if np.unique(tb).size < tb.size:  # (a table twice in a pass: one event after another)
            return self._break_each(tabs, i, j, sel)
        # Every table's groups broken at once: a ball is freed with an event's own balls if
        # it shares a group with either.
        at = np.arange(sel.size)
        ii, jj = i[sel], j[sel]
        label = self.label[tb]
        k = np.arange(self.balls.N)
        own = (k == ii[:, None]) | (k == jj[:, None])
        gi = label[at, ii][:, None]
        gj = np.where(jj >= 0, label[at, np.maximum(jj, 0)], -1)[:, None]
        members = own | ((label == gi) & (gi >= 0)) | ((label == gj) & (gj >= 0))
        label = np.where(members, -1, label)
        self.label[tb] = label
        self.count[tb] = (label >= 0).sum(axis=1)
        row, ball = (members & ~own).nonzero()
        if not row.size:
            return [], []
        bb = tb[row]
        tt = self.tb[bb]
        self.balls.set(bb, ball, tt, *self.balls.eval(bb, ball, tt))
        return [bb], [ball]

    def _break_each(self, tabs, i, j, sel) -> tuple[list, list]:
        """`break_up` event by event (events `sel`), each seeing the groups the ones before
        it left."""
        out_b, out_i = [], []
        for n in sel.tolist():
            b = int(tabs[n])
            own = {int(x) for x in (i[n], j[n]) if x >= 0}
            members = {k for x in own for k in self.members(b, x)}
            rest = sorted(members - own)
            self.label[b, sorted(members)] = -1
            self.count[b] = int((self.label[b] >= 0).sum())
            if rest:
                out_b.append(np.full(len(rest), b))
                out_i.append(np.array(rest))
        if out_b:  # every table's freed balls started at once (each table's own balls)
            bb, k = np.concatenate(out_b), np.concatenate(out_i)
            tt = self.tb[bb]
            self.balls.set(bb, k, tt, *self.balls.eval(bb, k, tt))
        return out_b, out_i

    def join(self, b: int, mem, t: float, p, v, w, ra, rc_, rn, bend) -> None:
        """Start the motion of balls `mem` of table b at time t from (p, v, w) (all N balls):
        balls in resting contacts (rows ra, rc_, rn, bend as in slow.SlowContacts' cluster
        solve) move as a group held by the contacts' forces; the others move freely."""
        balls = self.balls
        # (In plain ints: a group has a few balls, and np.unique and np.isin cost more.)
        in_rows = set(ra.tolist())
        in_rows.update(x for x in rc_.tolist() if x >= 0)
        held = np.array(sorted(in_rows), dtype=np.int64)
        free = np.array([x for x in mem.tolist() if x not in in_rows], dtype=np.int64)
        self.label[b, mem] = -1
        if free.size:
            balls.set(np.full(free.size, b), free, np.full(free.size, t), p[free], v[free], w[free])
        if held.size:
            where = {int(x): n for n, x in enumerate(held.tolist())}
            rows = [(where[int(x)], where.get(int(y), -1), n, bb)
                    for x, y, n, bb in zip(ra, rc_, rn, bend, strict=True)]
            vj, acc, alpha, state, duration, wj = push(
                self.physics, v[held], w[held], balls.radius[b, held], balls.mass[b, held],
                balls.spin_rate[b, held], rows)
            balls.state[b, held] = state
            balls.t_trans[b, held] = t + duration
            balls.motion[b, held, :Col.RATE] = np.concatenate(
                [np.full((held.size, 1), t), p[held], vj, acc, wj, alpha], axis=1)
            self.label[b, held] = int(held.min())
        self.count[b] = int((self.label[b] >= 0).sum())
