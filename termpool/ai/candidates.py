"""Candidate strikes: hard breaks at the apex, ghost-ball pots (their aim corrected for
throw), combinations, safeties and kicks; and the one batch that simulates them all."""

from __future__ import annotations

import math

import numpy as np

from termpool.physics import libm
from termpool.physics.cue import clamp_tip, strike
from termpool.physics.engine import Engine
from termpool.physics.events import Event, EventKind
from termpool.physics.log import LIGHT
from termpool.physics.params import Physics
from termpool.physics.table import Table

from . import geometry as geo
from .balls import OnTable
from .levels import Level

SIM_SECONDS = 8.0  # simulated time per candidate; a table still moving is judged as it is
SPEED_RANGE = (0.4, 6.0)  # m/s for pots, safeties and kicks
BREAK_SPEEDS = (7.0, 8.0, 9.0)
BREAK_SAMPLES = 12  # each break is judged over this many strikes with the level's errors
KICK_FAN = (0.5, 1.0, 1.5, 2.0, 3.0)  # degrees either side of a one-rail kick's aim
BREAK_SPINS = ((0.0, 0.0),)


class Cands:
    """Candidate strikes as parallel lists."""

    def __init__(self) -> None:
        self.speed: list[float] = []
        self.angle: list[float] = []
        self.side: list[float] = []
        self.top: list[float] = []
        self.target: list[int] = []  # ball index aimed at (-1: none)
        self.pocket: list[int] = []  # pocket aimed at (-1: none)
        self.kind: list[str] = []  # "break", "pot", "combo", "safety", "kick"
        self.chance: list[float] = []
        self.via: list[int] = []  # combo: the ball the target drives into the pocket
        self.aim: list[tuple[float, float]] = []  # pots and combos: where the target heads

    def add(self, speed, angle, side, top, target, pocket, kind, chance, via=-1,
            aim=(0.0, 0.0)) -> None:
        self.speed.append(float(np.clip(speed, 0.0, BREAK_SPEEDS[-1])))
        self.angle.append(float(angle))
        self.side.append(float(side))
        self.top.append(float(top))
        self.target.append(int(target))
        self.pocket.append(int(pocket))
        self.kind.append(kind)
        self.chance.append(float(chance))
        self.via.append(int(via))
        self.aim.append((float(aim[0]), float(aim[1])))

    def extend(self, other: Cands) -> None:
        for k in range(len(other)):
            self.add(other.speed[k], other.angle[k], other.side[k], other.top[k],
                     other.target[k], other.pocket[k], other.kind[k], other.chance[k],
                     other.via[k], other.aim[k])

    def __len__(self) -> int:
        return len(self.speed)


def break_cands(t: OnTable, targets: list[str], lv: Level) -> Cands:
    """Hard shots at the rack's apex (the legal ball nearest the cue ball), at each of
    BREAK_SPEEDS and BREAK_SPINS, each struck BREAK_SAMPLES times with the level's errors (the
    same draws every time: a player's break is theirs). A break scatters the rack chaotically,
    so it is judged by its average over the samples, not by one exact outcome; the samples
    of a break are consecutive."""
    cands = Cands()
    p = t.pos
    choice = [t.ids.index(b) for b in targets] or [k for k in range(len(t.ids)) if k != t.cue]
    if not choice:
        return cands
    apex = min(choice, key=lambda k: float(np.linalg.norm(p[k] - p[t.cue])))
    base = geo.deg(p[apex] - p[t.cue])
    rng = np.random.default_rng(0)
    for speed in BREAK_SPEEDS:
        for side, top in BREAK_SPINS:
            for e_aim, e_speed, e_side, e_top in rng.normal(0.0, 1.0, (BREAK_SAMPLES, 4)):
                tip = clamp_tip(side + lv.tip_sd * e_side, top + lv.tip_sd * e_top)
                cands.add(speed * (1 + lv.speed_sd * e_speed), base + lv.aim_sd * e_aim, *tip,
                          apex, -1, "break", 1.0)
    return cands


def pot_cands(t, targets, pockets, table, physics, lv: Level, budget: int) -> Cands:
    cands = Cands()
    n = len(t.ids)
    alive = np.ones((1, n), bool)
    tmask = np.array([[b in targets for b in t.ids]])
    chance, u = geo.pot_chances(t.pos[t.cue][None], t.pos[None], alive, tmask, t.radius,
                                t.cue, pockets, table, lv.aim_sd)
    chance, u = chance[0], u[0]
    # Pairs by chance; a blocked pair (chance 0) is left to the safeties.
    order = [(float(chance[i, k]), i, k) for i, k in zip(*np.nonzero(chance > 1e-4), strict=True)]
    order.sort(key=lambda x: (-x[0], x[1], x[2]))
    per_pair = len(lv.speeds) * len(lv.spins)
    for c, i, k in order[: max(budget // per_pair, 0)]:
        ghost = t.pos[i] - (t.radius[t.cue] + t.radius[i]) * u[i, k]
        d1 = float(np.linalg.norm(ghost - t.pos[t.cue]))
        d2 = float(np.linalg.norm(pockets.aim[k] - t.pos[i]))
        cos_cut = float(np.dot((ghost - t.pos[t.cue]) / max(d1, 1e-9), u[i, k]))
        base = geo.pot_speed(d1, d2, cos_cut, physics)
        # Speeds clipped to the same value would only repeat a table.
        for speed in dict.fromkeys(float(np.clip(base * f, *SPEED_RANGE)) for f in lv.speeds):
            for side, top in lv.spins:
                cands.add(speed, geo.deg(ghost - t.pos[t.cue]), side, top, i, k, "pot", c,
                          aim=pockets.aim[k])
    return cands


def combo_cands(t, targets, mode: str, pockets, physics, lv: Level, budget: int) -> Cands:
    """Combinations: a legal ball driven into another object ball that goes in.

    The target is sent to the ghost spot of the second ball's pot. The chance is that of
    both cuts (the first to within a quarter ball of its spot), blockers left to the batch."""
    cands = Cands()
    if budget <= 0 or not len(pockets.names):
        return cands
    pc, rc = t.pos[t.cue], float(t.radius[t.cue])
    eight = mode == "8ball"
    rows = []
    for b in targets:
        i = t.ids.index(b)
        ri = float(t.radius[i])
        for j in range(len(t.ids)):
            # In 8-ball only a ball the shooter may pot is worth driving in.
            if j in (i, t.cue) or (eight and t.ids[j] not in targets):
                continue
            rj = float(t.radius[j])
            for k in range(len(pockets.names)):
                uj = pockets.aim[k] - t.pos[j]
                d3 = float(np.linalg.norm(uj))
                uj = uj / max(d3, 1e-9)
                if float(np.dot(uj, pockets.out[k])) <= pockets.cos_limit[k]:
                    continue
                spot = t.pos[j] - (ri + rj) * uj  # where the target must arrive
                ui = spot - t.pos[i]
                d2 = float(np.linalg.norm(ui))
                ui = ui / max(d2, 1e-9)
                cos2 = float(np.dot(ui, uj))
                ghost = t.pos[i] - (rc + ri) * ui
                c = ghost - pc
                d1 = float(np.linalg.norm(c))
                if d1 < 1e-3 or cos2 < 0.5:
                    continue
                cos1 = float(np.dot(c / d1, ui))
                if cos1 < math.cos(math.radians(geo.MAX_CUT)):
                    continue
                tol = max(float(pockets.half[k]) * float(np.dot(uj, pockets.out[k])) - 0.6 * rc,
                          0.004)
                p2 = geo.pot_chance(tol, d2, d3, cos2, ri + rj, lv.aim_sd)  # the second ball's cut
                p1 = geo.pot_chance(0.25 * ri, d1, d2, cos1, rc + ri, lv.aim_sd)
                speed = geo.pot_speed(d1, d2 + d3, cos1 * cos2, physics)
                rows.append((p1 * p2, i, j, k, speed, geo.deg(c), spot))
    rows.sort(key=lambda r: (-r[0], r[1], r[2], r[3]))
    for p, i, j, k, speed, angle, spot in rows[: budget // 2]:
        if p < 1e-4:
            break
        for v in dict.fromkeys(float(np.clip(speed * f, *SPEED_RANGE)) for f in (1.0, 1.8)):
            cands.add(v, angle, 0.0, 0.0, i, k, "combo", p, via=j, aim=spot)
    return cands


def safety_cands(t: OnTable, targets: list[str], table: Table, physics: Physics,
                  budget: int) -> Cands:
    """Safeties and kicks at each legal ball, most useful first: touches (full and half-ball
    hits about hard enough to send the ball to a rail: the cue ball stays near where it is),
    soft full and half-ball hits, one-rail kicks (two guesses of the rebound: the cushion's
    restitution, and halfway to a mirror), a harder one-rail kick, two-rail kicks, more hits
    (thin cuts, firmer half-ball hits, a firm full hit: the batch finds the one that leaves
    least), then fans of one- and two-rail kicks aimed up to a few degrees to either side (the
    rebound of a spinning ball is only roughly known: the batch finds the one that hits)."""
    cands = Cands()
    pc = t.pos[t.cue]
    rc = geo.contact_offset(table, physics, float(t.radius[t.cue]))
    e, mid = physics.e_cushion, (1 + physics.e_cushion) / 2
    per_ball = []
    for b in targets:
        i = t.ids.index(b)
        d = t.pos[i] - pc
        base = geo.deg(d)
        reach = (t.radius[i] + t.radius[t.cue]) / max(float(np.linalg.norm(d)), 1e-9)
        half = math.degrees(math.asin(min(reach / 2, 1.0)))
        thin = math.degrees(math.asin(min(0.85 * reach, 1.0)))
        rows = [(speed, angle, "safety") for speed, angle in
                _touches(pc, t.pos[i], base, half, table, physics)]
        rows += [(0.9, base, "safety"), (1.8, base, "safety"), (1.3, base + half, "safety"),
                 (1.3, base - half, "safety")]
        more = [(1.0, base + thin), (1.0, base - thin), (2.4, base + half), (2.4, base - half),
                (1.8, base + thin), (1.8, base - thin), (2.8, base)]
        one = geo.kick_aims(pc, t.pos[i], table, rc, e)
        two = geo.kick_aims(pc, t.pos[i], table, rc, mid, 2)
        rows += [(2.2, a, "kick") for a in one + geo.kick_aims(pc, t.pos[i], table, rc, mid)]
        rows += [(3.5, a, "kick") for a in one]
        rows += [(3.0, a, "kick") for a in two]
        rows += [(speed, angle, "safety") for speed, angle in more]
        rows += [(2.5, a + s * f, "kick") for f in KICK_FAN for s in (1, -1) for a in one]
        rows += [(3.0, a + s * 1.5, "kick") for s in (1, -1) for a in two]
        per_ball.append([(speed, angle, i, kind) for speed, angle, kind in rows])
    # Interleave the balls, rank by rank, so that a small budget still covers every one.
    for rank in range(max((len(r) for r in per_ball), default=0)):
        for rows in per_ball:
            if rank < len(rows):
                if len(cands) >= budget:
                    return cands
                speed, angle, i, kind = rows[rank]
                cands.add(speed, angle, 0.0, 0.0, i, -1, kind, 0.0)
    return cands


def _touches(pc: np.ndarray, pt: np.ndarray, base: float, half: float, table: Table,
             physics: Physics) -> list[tuple[float, float]]:
    """(speed, angle) of a full hit and the two half-ball hits (which send the object ball
    30 degrees off the cue's line) about hard enough for the object ball to reach a rail
    (1.3 times `geo.pot_speed` to it), and a little harder."""
    out = []
    d1 = float(np.linalg.norm(pt - pc))
    for aim, turn in ((base, 0.0), (base + half, -30.0), (base - half, 30.0)):
        a = math.radians(base + turn)
        u = np.array([math.cos(a), math.sin(a)])
        # How far the object ball rolls along u before it meets a cushion line.
        reach = min((hi - pt[k]) / u[k] if u[k] > 1e-9 else (pt[k] - 0.0) / -u[k]
                    if u[k] < -1e-9 else math.inf
                    for k, hi in ((0, table.length), (1, table.width)))
        v = geo.pot_speed(d1, max(reach - 0.3, 0.0), math.cos(math.radians(turn)), physics)
        out += [(1.3 * v, aim), (1.8 * v, aim)]
    return out


def calibrate(t: OnTable, cands: Cands, table: Table, physics: Physics,
               rounds: int = 2) -> None:
    """Correct the aim of every pot for throw, in place.

    Each round simulates the cue ball and its target alone on a table without pockets,
    measures where the object ball actually heads, and turns the contact normal by the
    error (a fixed-point iteration: the throw changes little with the normal). A pot whose
    ball (or the cue ball) sits in a pocket's mouth, beyond the line the cushion takes on a
    table without pockets, keeps its aim: there it would overlap that cushion.
    """
    plain = Table(length=table.length, width=table.width, pockets="none")
    inside = [plain.inside(float(x), float(y), float(r))
              for (x, y), r in zip(t.pos, t.radius, strict=True)]
    pots = [k for k, kind in enumerate(cands.kind)
            if kind in ("pot", "combo") and inside[cands.target[k]] and inside[t.cue]]
    if not pots:
        return
    tgt = np.array([cands.target[k] for k in pots])
    want = np.array([geo.deg(np.array(cands.aim[k]) - t.pos[cands.target[k]]) for k in pots])
    normal = want.copy()
    pc = t.pos[t.cue]
    pt = t.pos[tgt]
    reach = t.radius[t.cue] + t.radius[tgt]
    B = len(pots)
    for _ in range(rounds):
        rad = np.radians(normal)
        ghost = pt - reach[:, None] * np.stack([libm.cos(rad), libm.sin(rad)], axis=1)
        angles = np.degrees(libm.arctan2(ghost[:, 1] - pc[1], ghost[:, 0] - pc[0]))
        pos = np.stack([np.broadcast_to(pc, (B, 2)), pt], axis=1)
        vel = np.zeros((B, 2, 2))
        w = np.zeros((B, 2, 3))
        for n, k in enumerate(pots):
            v, s = strike(cands.speed[k], float(angles[n]), cands.side[k], cands.top[k],
                          float(t.radius[t.cue]))
            vel[n, 0], w[n, 0] = v, s
        radius = np.stack([np.full(B, t.radius[t.cue]), t.radius[tgt]], axis=1)
        mass = np.stack([np.full(B, t.mass[t.cue]), t.mass[tgt]], axis=1)
        eng = Engine(plain, physics, pos, vel, w, radius, mass, record=True)
        heading = _run_to_heading(eng)
        final = eng.pos[:, 1]
        for n in range(B):
            where = heading[n]
            end = final[n] if where is None else where
            d = end - pt[n]
            if float(np.linalg.norm(d)) < 0.02:  # not hit, or barely moved: keep the aim
                continue
            err = (geo.deg(d) - want[n] + 180.0) % 360.0 - 180.0
            if abs(err) < 20.0:
                normal[n] -= err
        for n, k in enumerate(pots):
            rad = math.radians(normal[n])
            ghost = pt[n] - reach[n] * np.array([math.cos(rad), math.sin(rad)])
            cands.angle[k] = geo.deg(ghost - pc)


CALIBRATE_SLICE = 0.25  # simulated seconds between looks at which tables are done


def _run_to_heading(eng: Engine) -> list[np.ndarray | None]:
    """Run the two-ball tables until each object ball has shown where it heads (or to
    SIM_SECONDS); returns those points. A table is stopped once its point is known: what it
    does after is not read, and the rest run on exactly as in one run."""
    heading: list[np.ndarray | None] = [None] * eng.B
    seen = [0] * eng.B  # events already looked at, per table
    hit = [False] * eng.B
    t = 0.0
    while t < SIM_SECONDS and not eng.at_rest().all():
        t = min(t + CALIBRATE_SLICE, SIM_SECONDS)
        eng.run_events(duration=t)
        done = []
        for n in range(eng.B):
            if heading[n] is None:
                heading[n], hit[n], seen[n] = _heading_point(eng.log[n], hit[n], seen[n])
                if heading[n] is not None:
                    done.append(n)
        if done:
            eng.stop(done)
    eng.run_events(duration=SIM_SECONDS)
    return heading


def _heading_point(events: list[Event], hit: bool, start: int
                   ) -> tuple[np.ndarray | None, bool, int]:
    """Where the object ball (index 1) first meets a cushion or a ball again after it was
    hit, looking from event `start` on; returns (the point or None, hit yet, events seen)."""
    for ev in events[start:]:
        if 1 not in ev.balls:
            continue
        if ev.kind is EventKind.BALL_BALL and not hit:
            hit = True
            continue
        if hit and ev.kind in (EventKind.CUSHION, EventKind.BALL_BALL):
            s = ev.states[ev.balls.index(1)]
            return np.array([s.x, s.y]), hit, len(events)
    return None, hit, len(events)


def simulate(t: OnTable, cands: Cands, table: Table, physics: Physics,
              cue_at: np.ndarray | None = None) -> Engine:
    """All candidates in one batch; `cue_at` (B, 2) puts the cue ball elsewhere per table.
    Its event log is the light one (no balls' states): the referee reads no more."""
    B, n = len(cands), len(t.ids)
    pos = np.broadcast_to(t.pos, (B, n, 2)).copy()
    if cue_at is not None:
        pos[:, t.cue] = cue_at
    vel = np.zeros((B, n, 2))
    w = np.zeros((B, n, 3))
    for b in range(B):
        v, s = strike(cands.speed[b], cands.angle[b], cands.side[b], cands.top[b],
                      float(t.radius[t.cue]))
        vel[b, t.cue], w[b, t.cue] = v, s
    eng = Engine(table, physics, pos, vel, w, t.radius, t.mass, record=LIGHT)
    eng.run_events(duration=SIM_SECONDS)
    return eng
