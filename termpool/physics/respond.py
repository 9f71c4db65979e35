"""The engine's responses to fast events: a ball's motion state ending, a ball meeting a
rail, jaw, jaw tip or pocket hole, two balls colliding. Each applies its models (transition.py,
the cushion model, pocket.py, the ball-ball model, the sinks undone) to the balls and starts
their new motions; one event takes the plain-float forms, several at once the array forms,
with the same bits.
"""

from __future__ import annotations

import numpy as np

from termpool.physics import cushion, motion, pocket, transition
from termpool.physics.ball_ball import MODELS as BALL_BALL
from termpool.physics.ball_ball import sink as ball_sink
from termpool.physics.balls import FEW, Balls
from termpool.physics.cushion import sink
from termpool.physics.features import Features
from termpool.physics.motion import Col
from termpool.physics.params import Physics
from termpool.physics.schedule import Schedule
from termpool.physics.state import POCKETED


class Responses:
    """Responses of the balls of B tables at their clocks `tb`; a cushion event's feature is
    the one its prediction found (`schedule.f_cush`)."""

    def __init__(self, physics: Physics, balls: Balls, features: Features, schedule: Schedule,
                 tb: np.ndarray) -> None:
        self.physics, self.balls, self.features, self.schedule, self.tb = (
            physics, balls, features, schedule, tb)

    def transition(self, b, i) -> None:
        """Balls (b, i) whose motion state ends now start their next one."""
        if b.size <= FEW:
            self.transition_few(b, i)
            return
        balls, t = self.balls, self.tb[b]
        p, v, w = balls.eval(b, i, t)
        v, w = transition.end(balls.state[b, i], v, w, balls.radius[b, i])
        balls.set(b, i, t, p, v, w)

    def transition_few(self, b, i) -> None:
        """`transition` in plain floats, ball by ball (bit-identical)."""
        ph, balls = self.physics, self.balls
        out = []
        for t, row, st, R in zip(self.tb[b].tolist(), balls.motion[b, i].tolist(),
                                 balls.state[b, i].tolist(), balls.radius[b, i].tolist(),
                                 strict=True):
            p, v, w = motion.at(row, t)
            v, w = transition.end_one(st, v, w, R)
            out.append(motion.start(ph, t, p, v, w, R, row[Col.RATE], st == POCKETED))
        balls.write_few(b, i, out)

    def cushion(self, b, i) -> None:
        """Balls (b, i) meet the rail, jaw, jaw tip or pocket hole they were headed for."""
        if b.size == 1:
            self.cushion_one(int(b[0]), int(i[0]))
            return
        ph, balls, feat = self.physics, self.balls, self.features
        t = self.tb[b]
        f = self.schedule.f_cush[b, i]
        p, v, w = balls.eval(b, i, t)
        hole = f >= feat.first_hole
        ref, n = feat.points(f), feat.normals(f, p)  # of the rails, jaws and tips met
        bounce = (~hole).nonzero()[0]
        if bounce.size:
            bb, ib = b[bounce], i[bounce]
            nb = n[bounce]
            vb, wb = cushion.MODELS[ph.cushion].bounce(nb, v[bounce], w[bounce],
                                                       balls.radius[bb, ib], balls.mass[bb, ib], ph)
            pb = sink.lift(p[bounce], ref[bounce], nb, balls.rc[bb, ib])
            balls.set(bb, ib, t[bounce], pb, vb, wb)
        hl = hole.nonzero()[0]
        if hl.size:
            bh, ih = b[hl], i[hl]
            k = f[hl] - feat.first_hole
            balls.state[bh, ih] = POCKETED
            balls.pocket[bh, ih] = k
            balls.set(bh, ih, t[hl], *pocket.drop(feat.table.hole_c[k]))

    def cushion_one(self, b: int, i: int) -> None:
        """`cushion` for one ball in plain floats, bit-identical to it."""
        ph = self.physics
        tab = self.features.table
        t = float(self.tb[b])
        f = int(self.schedule.f_cush[b, i])
        row = self.balls.motion[b, i].tolist()
        r = row[Col.RADIUS]
        hole = f - self.features.first_hole
        if hole >= 0:
            self.balls.state[b, i] = POCKETED
            self.balls.pocket[b, i] = hole
            p, v, w = pocket.drop_one(tab.hole_c[hole].tolist())
        else:
            p, v, w = motion.at(row, t)
            ref, n = self.features.contact_one(f, p)
            v, w = cushion.MODELS[ph.cushion].bounce_one(n, v, w, r, row[Col.MASS], ph)
            p = sink.lift_one(p, ref, n, float(self.balls.rc[b, i]))
        pocketed = bool(self.balls.state[b, i] == POCKETED)
        self.balls.write_few(np.array([b]), np.array([i]), [
            motion.start(ph, t, p, v, w, r, row[Col.RATE], pocketed)])

    def pair_one(self, b: int, i: int, j: int) -> bool:
        """One fast ball-ball contact in plain floats (the usual pass), bit-identical to the
        array path; False, doing nothing, if the contact is slow."""
        t = float(self.tb[b])
        rows = self.balls.motion[b, [i, j]].tolist()
        pi, vi, wi = motion.at(rows[0], t)
        pj, vj, wj = motion.at(rows[1], t)
        d0, d1 = pj[0] - pi[0], pj[1] - pi[1]
        dist = float(np.hypot(d0, d1))
        if not dist > 0:  # centres together: leave it to the array path's nan handling
            return False
        closing = ((vi[0] - vj[0]) * d0 + (vi[1] - vj[1]) * d1) / dist
        ph = self.physics
        if closing < ph.v_inelastic:
            return False
        ri, rj = rows[0][Col.RADIUS], rows[1][Col.RADIUS]
        mi, mj = rows[0][Col.MASS], rows[1][Col.MASS]
        vi, vj, wi, wj = BALL_BALL[ph.ball_ball].collide_one(pi, pj, vi, vj, wi, wj, ri, rj,
                                                             mi, mj, ph)
        pi, pj = ball_sink.undo_one(pi, pj, ri, rj, mi, mj)  # as `part`
        pocketed = self.balls.state[b, [i, j]] == POCKETED
        self.balls.write_few(np.array([b, b]), np.array([i, j]), [
            motion.start(ph, t, pi, vi, wi, ri, rows[0][Col.RATE], bool(pocketed[0])),
            motion.start(ph, t, pj, vj, wj, rj, rows[1][Col.RATE], bool(pocketed[1]))])
        return True

    def collide(self, b, i, j, pi, vi, wi, pj, vj, wj) -> None:
        """Fast contacts (b, i, j), balls i and j now at (pi, vi, wi) and (pj, vj, wj)."""
        ph = self.physics
        t = self.tb[b]
        ri, rj = self.balls.radius[b, i], self.balls.radius[b, j]
        mi, mj = self.balls.mass[b, i], self.balls.mass[b, j]
        vi, vj, wi, wj = BALL_BALL[ph.ball_ball].collide(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj,
                                                         ph)
        self.part(b, i, j, t, pi, pj, vi, vj, wi, wj)

    def part(self, b, i, j, t, pi, pj, vi, vj, wi, wj) -> None:
        """Start both balls of contacts (b, i, j) on their new motion, first undoing a resting
        contact's sub-micrometre sink."""
        balls = self.balls
        pi, pj = ball_sink.undo(pi, pj, balls.radius[b, i], balls.radius[b, j], balls.mass[b, i],
                                balls.mass[b, j])
        balls.set(np.concatenate([b, b]), np.concatenate([i, j]), np.concatenate([t, t]),
                  np.concatenate([pi, pj]), np.concatenate([vi, vj]), np.concatenate([wi, wj]))
