"""The engine's predictions: for every ball the time of its next motion transition, of its next
horizon check and of its next cushion, jaw tip or pocket contact, and for every pair of balls
the time of their next contact, kept per table in one row so that finding a table's next event
is one argmin. An event renews only the predictions of the balls it touched.
"""

from __future__ import annotations

from array import array

import numpy as np

from termpool.physics.balls import FEW, Balls
from termpool.physics.features import Features
from termpool.physics.flat import flat
from termpool.physics.motion import Col, swept
from termpool.physics.roots import first_contact, first_contact_few, first_contact_rows, meeting_now
from termpool.physics.state import POCKETED, ROLLING, SLIDING
from termpool.physics.vec import min_one

# Candidates (row x ball) a chunk of `predict_many` works on at once: bounds its temporaries
# (a few hundred bytes a candidate) whatever the batch, while keeping numpy calls few.
CHUNK = 16384
PLAIN_MAX = 1024  # one table's renewals of up to this many (ball x ball) in plain floats
GAP = 1e-6  # m: boxes of paths (`_overlap`) are widened by this, far above their rounding
CULL = True  # skip the pairs and points that boxes of paths show cannot be met (tests: off)
# A batch's renewals in a cascade of contacts at one instant (a break's rack meets dozens of
# times at the impact's instant, a pass each) leave the pairs and cushions that cannot be met
# within LATER_TIME for later (`_later`): the same predictions, made once, when the table's
# clock is to move.
LATER_TIME = 1e-6  # s: a pair meeting this late meets past its clock's next float (to 4e9 s)
LATER_GAP = 1e-6  # m: and a pair this far apart is not touching
_MOVING = np.array([s in (SLIDING, ROLLING) for s in range(5)])  # by state code
_LIVE = np.array([s != POCKETED for s in range(5)])
_MOVING_ONE, _LIVE_ONE = _MOVING.tolist(), _LIVE.tolist()
# Whether a ball of each state is a pair of a renewed ball that moves (the last five) or not
# (the first five): it is live, and one of the two moves.
_PAIRED = np.concatenate([_LIVE & _MOVING, _LIVE])
_PAIRED_MOVING = np.int8(len(_LIVE))


def _argmin(row: list) -> int:
    """np.argmin of a list of floats: the first smallest, or the first NaN."""
    for k, x in enumerate(row):
        if x != x:
            return k
    return row.index(min(row))


def _firsts(key: np.ndarray) -> np.ndarray:
    """The places of the first occurrence of each value of `key`, in order: what
    np.unique(key, return_index=True)[1] sorted gives, by the same stable sort, without its
    checks."""
    perm = key.argsort(kind="stable")
    ordered = key.take(perm)
    new = np.empty(key.size, dtype=bool)
    new[0] = True
    np.not_equal(ordered[1:], ordered[:-1], out=new[1:])
    first = perm[new]
    first.sort()
    return first


class Due:
    """What a prediction is of, in the order of a table's row of times: N transitions, N
    horizon checks, N cushion contacts, then N x N ball pairs. (Plain ints, not an enum:
    numpy takes an enum member through a slow path.)"""

    TRANSITION = 0
    CHECK = 1  # a moving ball's predictions looked HORIZON ahead: renew them
    CUSHION = 2  # a rail, jaw, jaw tip or pocket hole (`f_cush` says which)
    PAIR = 3


class Schedule:
    """The predictions of B tables of N balls. `times` is the (B, 3 N + N N) row of every
    prediction (`new_times`), whose first N columns are the balls' `t_trans`; `tb` the
    tables' clocks; predictions look at most `horizon` seconds ahead."""

    @staticmethod
    def new_times(B: int, N: int) -> np.ndarray:
        return np.full((B, 3 * N + N * N), np.inf)

    def __init__(self, times: np.ndarray, balls: Balls, features: Features, tb: np.ndarray,
                 horizon: float) -> None:
        B, N = balls.B, balls.N
        self.N, self.balls, self.features, self.tb, self.horizon = N, balls, features, tb, horizon
        self.times = times
        self.t_trans = times[:, :N]
        assert np.shares_memory(balls.t_trans, times)  # the balls write their transitions here
        self.t_check = times[:, N:2 * N]
        self.t_cush = times[:, 2 * N:3 * N]
        self.f_cush = np.zeros((B, N), dtype=np.int64)  # the feature each t_cush is of
        self.t_pair = times[:, 3 * N:].reshape(B, N, N)
        assert np.shares_memory(self.t_pair, times)  # a view, not a copy
        self._times_1d = times.reshape(-1)  # the same, one index (pair times at 3 N on)
        assert np.shares_memory(self._times_1d, times)
        self.t_next = np.full(B, np.inf)  # each table's next event time and its code
        self.c_next = np.zeros(B, dtype=np.int64)
        self._row = np.full((B, N), -1, dtype=np.int64)  # a ball's row in a renewal, or -1
        self._place = np.zeros(B, dtype=np.intp)  # `_tables`' marks, zero between calls
        self.chunk = CHUNK
        self.one = B == 1
        # Predictions left for later (`_later`): the balls whose pairs or cushion wait, and
        # their tables; off for one table and until the engine has made its first ones.
        self.defer = False
        self.pending = False  # whether any table has predictions waiting
        self._late = np.zeros((B, N), dtype=bool)
        self._late_1d = self._late.reshape(-1)  # (a view)
        self._late_tables = np.zeros(B, dtype=bool)
        # Flat views of the arrays the plain-float paths read and write (flat.py): the row
        # of times of table b begins at b * width.
        self.width = 3 * N + N * N
        self.flat, self._tb = flat(times), flat(tb)
        self._inf_row = array("d", [np.inf] * N)
        balls.flat_times, balls.width = self.flat, self.width  # where t_trans lives
        self._next, self._c_next = flat(self.t_next), flat(self.c_next)
        self._row0 = times[0] if B else times  # table 0's row of times (a view)
        self.code_one = 0  # the last code refresh_one found
        self._ones: dict[int, np.ndarray] = {}  # one_array's arrays
        self.flat_f_cush = flat(self.f_cush)
        self._f_cush_1d = self.f_cush.reshape(-1)  # a view
        # `_near_features`' reach of each hole and the features' boxes, as columns (F, 1).
        self._hole_gap = (features.table.hole_r + GAP)[:, None]
        self._boxes = features.box_lo[..., None], features.box_hi[..., None]
        tab = features.table  # the holes' x, y and radius as columns (H, 1)
        self._holes = tab.hole_c[:, 0, None], tab.hole_c[:, 1, None], tab.hole_r[:, None]

    def decode_one(self, code: int) -> tuple[int, int, int]:
        """`decode` of one event code, as ints (what: Due, ball i, ball j or -1)."""
        q, r = divmod(code, self.N)
        return (Due.PAIR, q - Due.PAIR, r) if q >= Due.PAIR else (q, r, -1)

    def one_array(self, x: int) -> np.ndarray:
        """The read-only int array [x], made once (one table's events index with these)."""
        a = self._ones.get(x)
        if a is None:
            a = self._ones[x] = np.array([x])
            a.flags.writeable = False
        return a

    def decode(self, code: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Event codes (places in the row of times) as (what: Due, ball i, ball j or -1)."""
        if code.size == 1:  # one event (one table): in plain ints, three small arrays
            q, r = divmod(int(code[0]), self.N)
            pair = q >= Due.PAIR
            return (np.array([Due.PAIR if pair else q]), np.array([q - Due.PAIR if pair else r]),
                    np.array([r if pair else -1]))
        q, r = np.divmod(code, self.N)
        due = np.minimum(q, Due.PAIR)
        return due, np.where(q < Due.PAIR, r, q - Due.PAIR), np.where(q < Due.PAIR, -1, r)

    def predict(self, b: np.ndarray, i: np.ndarray) -> None:
        """Renew the contact predictions of balls (b, i) from their tables' clocks on."""
        # One table renews a cluster's balls in plain floats too, up to PLAIN_MAX candidate
        # pairs (its numpy calls would cost about as much as its candidates); batches and big
        # tables keep the arrays.
        if b.size <= FEW or self.one and b.size * self.N <= PLAIN_MAX:
            self.predict_few(b, i)
        else:
            self.predict_many(b, i)

    def predict_many(self, b: np.ndarray, i: np.ndarray) -> None:
        """`predict` on arrays."""
        N = self.N
        key = b * N + i  # (one-index lookups: a two-index one costs several times more)
        if b.size > 1:  # a ball renewed twice (an event's ball, and its cluster's): once
            first = _firsts(key)
            if first.size < b.size:
                b, i, key = b.take(first), i.take(first), key.take(first)
        if self.pending:  # renewed now: none of their pairs waits (unless `_later` says)
            self._late_1d[key] = False
        t = self.tb.take(b)
        st = self.balls.state.reshape(-1).take(key)
        moving = _MOVING.take(st)
        t_check = np.where(moving, t + self.horizon, np.inf)
        at = b * self.width + i  # the ball's transition time in the flat rows of times
        self._times_1d[at + N] = t_check
        end = np.minimum(self._times_1d.take(at), t_check)
        self._times_1d[at + 2 * N] = np.inf
        self.t_pair[b, i, :] = np.inf
        self.t_pair[b, :, i] = np.inf
        live = st != POCKETED
        if not live.all():
            m = live.nonzero()[0]
            if m.size == 0:
                return
            b, i, t, end, moving, key = b[m], i[m], t[m], end[m], moving[m], key[m]
        # In chunks of rows, so that the temporaries (each row's candidates against every
        # ball of its table) stay bounded however many tables renew at once; every row's
        # predictions are its own, so chunks give the same times as one piece.
        step = max(1, self.chunk // N)
        row = self._row.reshape(-1)  # (a view)
        row[key] = np.arange(b.size)
        try:
            for s in range(0, b.size, step):
                self._predict_rows(b[s:s + step], i[s:s + step], t[s:s + step],
                                   end[s:s + step], moving[s:s + step], s)
        finally:
            row[key] = -1

    def _predict_rows(self, b, i, t, end, moving, first: int) -> None:
        """`predict_many`'s contact predictions for live balls (b, i) at clocks t, whose
        motions hold until `end`, their own predictions already cleared; they are rows
        `first` on of the renewal (`_row`)."""
        balls, feat, N = self.balls, self.features, self.N
        M = b.size
        # Every ball of the tables involved, evaluated once a table, in six planes (x, y,
        # vx, vy, ax, ay; ball i of table tabs[u] in column u N + i): each candidate's
        # relative motion is then one take and one difference, and each component one
        # contiguous row. (Two-index lookups cost several times more than these takes.)
        tabs, u = self._tables(b)
        tbt = self.tb.take(tabs)[:, None]
        Q = balls.planes(tabs, tbt)
        ui = u * N + i
        q = Q.take(ui, axis=1)  # the rows' own balls
        end_k = np.minimum(self.t_trans[tabs], self.t_check[tabs])
        radius = balls.radius.take(tabs, axis=0).ravel()
        # Pairs: every other ball on the table, where at least one of the two moves. Two
        # renewed balls meet as the first one's pair only: their times are the same bits
        # either way round (each difference the other's negated, each product the same).
        # (A row's own ball is renewed as that row, so it is no pair of its own; renewed
        # balls' rows, and -1 for others, compared as unsigned: -1 is above every row.)
        stk = balls.state.take(b, axis=0)
        renewed = self._row.take(b, axis=0).view(np.uint64)
        valid = _PAIRED.take(stk + (_PAIRED_MOVING * moving)[:, None])
        valid &= renewed > np.arange(first, first + M, dtype=np.uint64)[:, None]
        if CULL:
            # A pair's window ends with the shorter of its balls' own, at most a moving
            # ball's (`horizon`): a ball at rest's is cut at twice that.
            lo, hi = swept(Q[0:2], Q[2:4], Q[4:6],
                           np.maximum(np.minimum(end_k - tbt, 2.0 * self.horizon), 0.0).ravel())
            valid &= self._overlap(lo, hi, radius, u, ui)
        mi, kk = valid.nonzero()
        k = u.take(mi) * N + kk
        rel = Q.take(k, axis=1)
        rel -= q.take(mi, axis=1)
        dist = [radius.take(k) + radius.take(ui).take(mi)]
        horizon = [np.minimum(end.take(mi), end_k.ravel().take(k)) - t.take(mi)]
        hot = None  # rows of tables with a pair meeting now (`_later`)
        if self.defer and mi.size:
            now, hot = self._later(rel, dist[0], horizon[0], mi, u, tabs, b, i)
            if now is not None:
                mi, kk, rel = mi.take(now), kk.take(now), rel.take(now, axis=1)
                dist, horizon = [dist[0].take(now)], [horizon[0].take(now)]
        # Cushions, jaw tips and pocket holes, for moving balls that can reach the cushion
        # noses or a hole within their window (a ball in open felt costs nothing here); tips
        # and holes are the same quartic as a pair.
        T = end - t
        rc = balls.rc.ravel().take(b * N + i)
        hv, ha = np.hypot(q[2], q[3]), np.hypot(q[4], q[5])
        reach = hv * T + 0.5 * ha * T * T + rc
        near = self._reaching(q[0], q[1], reach)
        if hot is not None:  # as pairs: cushions that cannot be met at the clock can wait
            soon = LATER_GAP + LATER_TIME * (hv + ha * T) + rc
            wait = hot & moving & near & ~self._reaching(q[0], q[1], soon)
            if wait.any():
                self._wait(b[wait], i[wait])
                near &= ~wait
        mv = (moving & near).nonzero()[0]
        nc, S = len(feat.circles), feat.nseg
        qm, rcm, Tm = q.take(mv, axis=1), rc.take(mv), T.take(mv)
        if CULL and mv.size:  # the features the moving balls' boxes come within reach of
            um = ui.take(mv)
            near_f = self._near_features(lo.take(um, axis=1), hi.take(um, axis=1), rcm)
        if mv.size and nc:
            D = np.empty((mv.size, nc))  # a tip is met at the nose reach, a hole at its radius
            D[:, :feat.npt] = rcm[:, None]
            D[:, feat.npt:] = feat.table.hole_r
            if CULL:
                mr, cc = near_f[:, S:].nonzero()
            else:
                mr, cc = np.divmod(np.arange(mv.size * nc), nc)
            m = qm.take(mr, axis=1)
            # After the pairs: the point relative to the ball, the ball's motion negated.
            circ = np.negative(m)
            np.subtract(feat.circle_rows.take(cc, axis=1), m[:2], out=circ[:2])
            rel = np.concatenate([rel, circ], axis=1)
            dist.append(D.ravel().take(mr * nc + cc))
            horizon.append(Tm.take(mr))
        found = first_contact_rows(rel, np.concatenate(dist), np.concatenate(horizon))
        npair = mi.size
        if npair:
            tp = t.take(mi) + found[:npair]
            # Written through one flat index each way: a one-index store is cheaper than
            # t_pair's three.
            at = b.take(mi) * self.width + 3 * N
            ii = i.take(mi)
            self._times_1d[at + ii * N + kk] = tp
            self._times_1d[at + kk * N + ii] = tp
        if mv.size:
            # Each ball's segments, then its points (tips and holes), in one row.
            allt = np.full((mv.size, S + nc), np.inf)
            if nc:
                allt.ravel()[mr * (S + nc) + (S + cc)] = found[npair:]
            if mv.size <= FEW:
                allt[:, :S] = feat.lines_few(qm[0:2].T, qm[2:4].T, qm[4:6].T, rcm, Tm,
                                             reach.take(mv))
            else:  # (the segments the ball's box comes within reach of)
                feat.lines(qm, rcm, Tm, near=near_f[:, :S] if CULL else None, out=allt)
            f = allt.argmin(axis=1)
            bm, im = b.take(mv), i.take(mv)
            self._times_1d[bm * self.width + 2 * N + im] = t.take(mv) + allt[np.arange(mv.size), f]
            self._f_cush_1d[bm * N + im] = f

    def _later(self, rel, dist, hz, mi, u, tabs, b, i) -> np.ndarray | None:
        """Which pair candidates (rows of rel, of renewal rows mi) to predict now (None:
        all), and which renewal rows are of tables with a pair meeting now (None: none).
        Where a pair of a table meets now, the table's next event is at its clock, and
        pairs that cannot meet before the clock's next float do not decide it: they wait
        until the table's clock is to move (`complete`). A pair must close its gap to
        meet, at no more than its speed and acceleration over its window allow, so a pair
        more than LATER_GAP and LATER_TIME of that apart meets LATER_TIME on at the soonest.
        (A window that is not a number keeps its pair.)"""
        px, py, vx, vy, ax, ay = rel
        _, r0, _, _, now = meeting_now(px, py, vx, vy, dist)
        if not now.any():
            return None, None
        hot = np.zeros(tabs.size, dtype=bool)
        hot[u.take(mi[now])] = True
        late = ((r0 - dist > LATER_GAP + LATER_TIME * (np.sqrt(vx * vx + vy * vy)
                                                       + np.sqrt(ax * ax + ay * ay) * hz))
                & hot.take(u.take(mi)))
        hot = hot.take(u)
        if not late.any():
            return None, hot
        rows = mi[late]
        self._wait(b.take(rows), i.take(rows))
        return (~late).nonzero()[0], hot

    def _wait(self, b, i) -> None:
        """Balls (b, i) have predictions left for later (`complete`)."""
        self._late_1d[b * self.N + i] = True
        self._late_tables[b] = True
        self.pending = True

    def _reaching(self, x, y, reach) -> np.ndarray:
        """Whether balls at (x, y) (M,) may come within reach (M,) of a cushion nose, or
        of a hole's edge (a corner hole may reach into the table past the rail lines, up to
        its mouth)."""
        tab = self.features.table
        near = (x < reach) | (y < reach) | (x > tab.length - reach) | (y > tab.width - reach)
        if len(tab.hole_r):  # (a hole a row, so that each operation runs along the balls)
            hx, hy, hr = self._holes
            dx, dy = x - hx, y - hy
            # hypot(dx, dy) >= max(|dx|, |dy|): a ball that far from every hole is near none,
            # and hypot (slow) is worked out only for the others.
            c = (((np.maximum(np.abs(dx), np.abs(dy)) - hr) < reach).any(axis=0)
                 & ~near).nonzero()[0]
            if c.size:
                near[c] = ((np.hypot(dx[:, c], dy[:, c]) - hr) < reach.take(c)).any(axis=0)
        return near

    def complete(self, force: bool = False) -> None:
        """Predict the pairs `_later` left, of every table whose next event is no longer at
        its clock (with `force`, of every table): its balls with pairs waiting are renewed
        in full, which gives the pairs that did not wait the same times again."""
        due = self._late_tables.nonzero()[0]
        if not force:
            due = due[self.t_next.take(due) != self.tb.take(due)]
        if due.size:
            b, i = self._late[due].nonzero()
            b = due.take(b)
            self._late[due] = False
            self._late_tables[due] = False
            self.defer = False
            try:
                self.predict(b, i)
            finally:
                self.defer = True
            self.refresh(due)
        self.pending = bool(self._late_tables.any())

    def _tables(self, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """np.unique(b, return_inverse=True) for table numbers b: the tables in order, and
        each b's place among them (marks in an array of B, no sort)."""
        place = self._place
        place[b] = 1
        tabs = place.nonzero()[0]
        place[tabs] = np.arange(tabs.size)
        u = place.take(b)
        place[tabs] = 0
        return tabs, u

    def _overlap(self, lo, hi, radius, u, ui) -> np.ndarray:
        """(M, N) whether ball ui of the (table, ball) columns (ball i[r] of table u[r]) and
        each ball of its table can come within touching distance in their windows, from the
        boxes (lo, hi) (2, tables N) their paths sweep over their own windows (`swept`),
        widened by their radii and GAP: boxes that stay apart are balls further apart than
        touching, for which `first_contact` finds no contact (not even a touching one), so
        skipping them changes no prediction. Boxes that are not numbers (an endless window)
        keep their pairs."""
        rg = radius + GAP
        lo, hi = lo - rg, hi + rg
        tables = (2, -1, self.N)
        # Apart along x or y: one's lo past the other's hi (nan: not apart).
        apart = lo.reshape(tables).take(u, axis=1) > hi.take(ui, axis=1)[..., None]
        apart |= hi.reshape(tables).take(u, axis=1) < lo.take(ui, axis=1)[..., None]
        return ~(apart[0] | apart[1])

    def _near_features(self, lo, hi, rc) -> np.ndarray:
        """(M, S + C) whether balls whose paths sweep boxes (lo, hi) (2, M) can come within
        reach of each cushion segment and each point (jaw tips, hole centres), in the
        features' order: a segment's box or a tip within the ball's nose reach rc (M,), a
        hole's centre within its radius (and GAP). A contact is a centre that far from a
        point of the feature, within the window, so it is in both boxes; as in `_overlap`,
        a feature further than that from the box is never met."""
        # Worked a feature a row (S + C, M), so that each operation runs along the balls;
        # returned as its transpose.
        feat = self.features
        Dg = np.empty((feat.nseg + len(feat.circles), rc.size))
        Dg[:feat.first_hole] = rc + GAP
        Dg[feat.first_hole:] = self._hole_gap
        lo_f, hi_f = self._boxes
        apart = ((lo_f[0] - hi[0] > Dg) | (lo[0] - hi_f[0] > Dg)
                 | (lo_f[1] - hi[1] > Dg) | (lo[1] - hi_f[1] > Dg))
        return (~apart).T

    def predict_few(self, b, i) -> None:
        """`predict` for a few balls in plain floats: the same candidates in the same order,
        culled by `first_contact_few`, so the predictions are bit-identical. As there, a
        ball renewed twice is renewed once, and two renewed balls meet as the first one's
        pair only (the same bits either way round). `b` and `i` are arrays or lists; times,
        motions and states are read and written through flat memoryviews (flat.py)."""
        balls, feat, tab = self.balls, self.features, self.features.table
        inf, horizon, N, W = np.inf, self.horizon, self.N, self.width
        F, tb, states = self.flat, self._tb, balls.flat_state
        motions, rcs = balls.flat_motion, balls.flat_rc
        bl = b.tolist() if isinstance(b, np.ndarray) else b
        il = i.tolist() if isinstance(i, np.ndarray) else i
        P = 3 * N  # where a row's pair times begin
        rows = []
        renewed: dict = {}  # (table, ball) -> its row
        for bm, im in zip(bl, il, strict=True):
            t = tb[bm]
            st = states[bm * N + im]
            moving = _MOVING_ONE[st]
            t_check = t + horizon if moving else inf
            base = bm * W
            F[base + N + im] = t_check
            end = min_one(F[base + im], t_check)
            F[base + 2 * N + im] = inf
            F[base + P + im * N:base + P + (im + 1) * N] = self._inf_row
            F[base + P + im:base + P + N * N:N] = self._inf_row
            if st != POCKETED and (bm, im) not in renewed:  # (a ball renewed twice: once)
                renewed[bm, im] = len(rows)
                rows.append((bm, im, t, end, moving))
        if not rows:
            return
        cands: list = []
        pairs = []  # (table, ball, other ball, clock) of the first len(pairs) candidates
        tables: dict = {}
        C = Col.N
        for r, (bm, im, t, end, moving) in enumerate(rows):
            if bm not in tables:
                flat_m = motions[bm * N * C:(bm + 1) * N * C].tolist()
                base = bm * W
                tables[bm] = ([flat_m[k * C:(k + 1) * C] for k in range(N)],
                              states[bm * N:(bm + 1) * N].tolist(),
                              [min_one(x, y) for x, y in zip(F[base:base + N].tolist(),
                                                             F[base + N:base + 2 * N].tolist(),
                                                             strict=True)])
            motion, stk, end_k = tables[bm]
            me = motion[im]
            d = t - me[Col.T0]
            pix = me[Col.PX] + (me[Col.VX] + 0.5 * me[Col.AX] * d) * d
            piy = me[Col.PY] + (me[Col.VY] + 0.5 * me[Col.AY] * d) * d
            vix, viy = me[Col.VX] + me[Col.AX] * d, me[Col.VY] + me[Col.AY] * d
            aix, aiy, ri = me[Col.AX], me[Col.AY], me[Col.RADIUS]
            for k, (other, sk) in enumerate(zip(motion, stk, strict=True)):
                if not _LIVE_ONE[sk] or k == im or not (moving or _MOVING_ONE[sk]):
                    continue
                if renewed.get((bm, k), r) < r:  # met as the earlier renewed ball's pair
                    continue
                d = t - other[Col.T0]
                ax, ay = other[Col.AX], other[Col.AY]
                cands.append((
                    other[Col.PX] + (other[Col.VX] + 0.5 * ax * d) * d - pix,
                    other[Col.PY] + (other[Col.VY] + 0.5 * ay * d) * d - piy,
                    other[Col.VX] + ax * d - vix, other[Col.VY] + ay * d - viy,
                    ax - aix, ay - aiy, other[Col.RADIUS] + ri,
                    (end if end < end_k[k] or end != end else end_k[k]) - t))
                pairs.append((bm, im, k, t))
        # Cushions, as in `predict`: only moving balls that can reach a cushion nose or a
        # hole within their window. Lengths go through numpy's hypot (the C library's can
        # differ in the last bit), one call a ball.
        hole_c, hole_r = feat.hole_c, feat.hole_r
        mv = []  # (row, position, velocity, acceleration, window, reach, contact distance)
        for bm, im, t, end, moving in rows:
            if not moving:
                continue
            px, py, vx, vy, ax, ay = self._at(tables[bm][0][im], t)
            T = end - t
            rc = rcs[bm * N + im]
            hv, ha, *edge = np.hypot([vx, ax] + [px - hx for hx, _ in hole_c],
                                     [vy, ay] + [py - hy for _, hy in hole_c]).tolist()
            reach = hv * T + 0.5 * ha * T * T + rc
            if (px < reach or py < reach or px > tab.length - reach or py > tab.width - reach
                    or any(e - r < reach for e, r in zip(edge, hole_r, strict=True))):
                mv.append((bm, im, t, [px, py], [vx, vy], [ax, ay], T, reach, rc))
        nc = len(feat.circles)
        if nc:
            for _, _, _, (px, py), (vx, vy), (ax, ay), T, _, rc in mv:
                dists = [rc] * feat.npt + hole_r
                cands += [(cx - px, cy - py, -vx, -vy, -ax, -ay, dk, T)
                          for (cx, cy), dk in zip(feat.circle_list, dists, strict=True)]
        found = first_contact_few(cands)
        npair = len(pairs)
        for (bm, im, k, t), f in zip(pairs, found, strict=False):
            F[bm * W + P + im * N + k] = F[bm * W + P + k * N + im] = t + f
        fc = self.flat_f_cush
        for n, (bm, im, t, p, v, a, T, reach, rc) in enumerate(mv):
            circles = found[npair + n * nc:npair + (n + 1) * nc]
            allt = feat.lines_one(p, v, a, rc, T, reach) + circles
            f = _argmin(allt)
            F[bm * W + 2 * N + im] = t + allt[f]
            fc[bm * N + im] = f

    @staticmethod
    def _at(me: list, t: float) -> tuple:
        """Position, velocity and acceleration at t of a ball whose packed motion is `me`,
        as `Balls.eval` computes them."""
        d = t - me[Col.T0]
        ax, ay = me[Col.AX], me[Col.AY]
        return (me[Col.PX] + (me[Col.VX] + 0.5 * ax * d) * d,
                me[Col.PY] + (me[Col.VY] + 0.5 * ay * d) * d,
                me[Col.VX] + ax * d, me[Col.VY] + ay * d, ax, ay)

    def refresh(self, tabs: np.ndarray) -> None:
        """Recompute the next event of tables `tabs` from their predictions."""
        if tabs.size == 1:  # one table: its row of times, no gathers
            self.refresh_one(int(tabs[0]))
            return
        if 2 * tabs.size >= len(self.times):  # most tables: every row's argmin, no copy
            code = self.times.argmin(axis=1).take(tabs)
        else:
            code = self.times[tabs].argmin(axis=1)
        self.t_next[tabs] = self._times_1d.take(tabs * self.width + code)
        self.c_next[tabs] = code

    def refresh_one(self, b: int) -> None:
        """`refresh` of table b alone: one argmin, the rest through the flat views; the code
        is also kept as an int (`code_one`)."""
        code = int((self._row0 if b == 0 else self.times[b]).argmin())
        self._next[b] = self.flat[b * self.width + code]
        self._c_next[b] = self.code_one = code

    def unstick(self, b: int, i: int, j: int) -> None:
        """A pressed pair whose solve changed nothing, found pressed again at the same
        instant, would be met there for ever (a ball slowing to a stop as it parts, a group
        whose push leaves it pressed): it is looked for again as a pair that is not pressed,
        when it has sunk SINK."""
        t = self.tb[b]
        if self.t_pair[b, i, j] > t:
            return
        k = np.array([i, j])
        p, v, _ = self.balls.eval(np.full(2, b), k, np.full(2, t), spin=False)
        a = self.balls.acc[b, k]
        end = np.minimum(self.t_trans[b, k], self.t_check[b, k]).min() - t
        found = first_contact((p[1] - p[0])[None], (v[1] - v[0])[None], (a[1] - a[0])[None],
                              self.balls.radius[b, k].sum()[None], np.array([end]), pressed=False)
        self.t_pair[b, i, j] = self.t_pair[b, j, i] = t + found[0]

