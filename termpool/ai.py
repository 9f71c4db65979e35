"""The computer opponent: candidate shots simulated in one batch and judged by the referee.

`choose_shot` builds candidate strikes (the break: hard shots at the rack's apex; otherwise
ghost-ball pots for every legal target and pocket at a few speeds and spins, combinations, and
soft safeties and one-rail kicks at each legal ball), simulates them all in ONE batched Engine,
judges every table with the rules and scores it; the best few are simulated again aimed a
little to either side, and the best expected score is played (`Plan`). `score_shots` returns
every candidate of the batch with its score. `choose_placement` picks a spot for the cue ball
in hand from cheap geometry (the shots the spot leaves).

Scores: a win far above a legal pot (the shooter continues) above a shot that passes the turn
without a foul above a foul above a loss. A pot is weighted by its chance to go in under the
level's notional aim error (thin cuts and long shots are risky), plus a position term: how
makeable the next shot is from where the cue ball stops. A turn that passes is marked down by
how makeable the table it leaves is for the opponent.

Cut shots throw the object ball off the line of centres (ball-ball friction), so before the
batch each pot's aim is corrected by two cheap rounds on two-ball tables without pockets
(cue ball and target only): the object ball's measured heading corrects the contact angle.

Geometry (pockets, chances, blocked paths, kick aims) is in `ai_geometry`. The module reads the
physics and rules and never changes them; no terminal code here.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from termpool import ai_geometry as geo
from termpool.game.layout import head_string, in_area
from termpool.physics.cue import clamp_tip, strike
from termpool.physics.engine import POCKETED, Engine
from termpool.physics.params import Physics
from termpool.physics.table import Table
from termpool.rules import words
from termpool.rules.codes import Choice, Option
from termpool.rules.common import AREAS, State, legal_targets
from termpool.rules.events import summarize
from termpool.rules.referee import judge
from termpool.rules.words import voice


class Plan(NamedTuple):
    """A shot to play: cue.strike's speed (m/s), angle (degrees), side and top (units of R)."""

    speed: float
    angle: float
    side: float
    top: float
    called: tuple[str, str] | None  # (ball, pocket name) when the rules need a call (the 8)
    score: float
    note: str  # why, in words for people ("3 in the foot left pocket")
    kind: str = ""  # "break", "pot", "combo", "safety", "kick" ("": none of them)
    ball: str | None = None  # pots and combinations: the ball meant to drop ...
    pocket: str | None = None  # ... and the pocket it is sent to
    sees: str = ""  # what the batch saw the shot do: "win", "loss", "foul" (its note is then
    # the referee's verdict), "pot" (a pot that keeps the table) or "pass" ("": no batch)


class Level(NamedTuple):
    """Everything that makes a level, in one place (docs/ai.md has the figures they give)."""

    # What it tries.
    share: float  # fraction of max_candidates used
    speeds: tuple[float, ...]  # pot speeds: multiples of the slowest that reaches the pocket
    spins: tuple[tuple[float, float], ...]  # (side, top) tip offsets of pots
    combos: int  # candidates kept for combinations (two speeds each)
    verify: int  # best candidates simulated again under its errors before choosing
    spots: int  # ball in hand: distances behind the ghost ball tried per cut angle
    break_spots: tuple[float, ...]  # where it may break from: across the head string, as
    # shares of the width (0.5: the head spot); with several, it tries its break from each
    # How it weighs a shot.
    position: float  # weight of its next shot's chance from where the cue ball stops after a
    # pot (0: it plans no position, only the pot)
    leave: float  # weight of the opponent's best chance when the turn passes, a miss
    # included (0: it never plays safe while a pot is possible)
    # How it strikes: the sd of each error, drawn from a normal distribution per shot.
    aim_sd: float  # degrees of aim (also the error it weighs a pot's risk with)
    speed_sd: float  # relative speed
    tip_sd: float  # tip position, in ball radii, across and along
    spot_sd: float  # m, where it puts the cue ball in hand


STUN, FOLLOW, DRAW = (0.0, 0.0), (0.0, 0.3), (0.0, -0.3)
LEVELS = {
    # A beginner: the pot in front of it, hit firmly; no position, no safeties.
    "easy": Level(0.25, (1.3, 2.4), (STUN, FOLLOW), 0, 4, 1, (0.5,),
                  0.0, 0.0, 0.9, 0.10, 0.10, 0.03),
    # A club player: a sound choice of pot, some thought of what a miss leaves.
    "normal": Level(0.8, (1.0, 1.8, 3.0), (STUN, FOLLOW, DRAW), 8, 8, 2, (0.5,),
                    0.0, 30.0, 0.3, 0.06, 0.06, 0.01),
    # A strong amateur: plays position for the next ball, safe when the pot is poor, and
    # breaks from where its break works best on the rack.
    "hard": Level(1.2, (1.0, 1.4, 1.9, 2.6, 3.4),
                  (STUN, (0.0, 0.35), (0.0, -0.35), (0.25, 0.1), (-0.25, 0.1), (0.25, -0.3),
                   (-0.25, -0.3)), 16, 10, 3, (0.5, 0.16, 0.275, 0.35, 0.65, 0.725, 0.84),
                  100.0, 200.0, 0.23, 0.03, 0.03, 0.0),
    # A professional: a steadier stroke, more of the batch.
    "pro": Level(1.5, (1.0, 1.4, 1.9, 2.6, 3.4),
                 (STUN, (0.0, 0.35), (0.0, -0.4), (0.3, 0.1), (-0.3, 0.1), (0.25, -0.3),
                  (-0.25, -0.3)), 24, 12, 3, (0.5, 0.16, 0.275, 0.35, 0.65, 0.725, 0.84),
                 150.0, 300.0, 0.07, 0.02, 0.015, 0.0),
}
WIN, LOSS, CONTINUE, PASS, FOUL = 1000.0, -1000.0, 300.0, 0.0, -250.0
MISS_LEAVE = 0.7  # what a missed pot usually leaves the opponent, as a leave value (0..1)
LEAVE_SIGMA = 0.5  # degrees: the aim error a table left behind is valued with, for the
# shooter's next shot and for the opponent alike (a club player's, whatever the level: an
# error as small as a pro's would call every open shot certain, and tell no leave from another)
FLUKE = 0.3  # chance a legal pot the sim found by a kiss or a combination happens in play
SIM_SECONDS = 8.0  # simulated time per candidate; a table still moving is judged as it is
SPEED_RANGE = (0.4, 6.0)  # m/s for pots, safeties and kicks
BREAK_SPEEDS = (7.0, 8.0, 9.0)
BREAK_SAMPLES = 12  # each break is judged over this many strikes with the level's errors
KICK_FAN = (0.5, 1.0, 1.5, 2.0, 3.0)  # degrees either side of a one-rail kick's aim
BREAK_SPINS = ((0.0, 0.0),)
MIN_CANDIDATES = 8
OPTION_ANSWERS = {Option.RERACK_OR_ACCEPT: Choice.ACCEPT, Option.SHOOT_OR_PASS: Choice.SHOOT}
SAID = voice(("player 0", "player 1"))  # the notes' words: pockets as people say them


# ------------------------------------------------------------------------------ inputs


class _Table(NamedTuple):
    """The balls on the table, in the order given; `cue` is the cue ball's index."""

    ids: list[str]
    pos: np.ndarray  # (n, 2)
    radius: np.ndarray  # (n,)
    mass: np.ndarray  # (n,)
    cue: int


def _per_ball(x, n: int, name: str) -> np.ndarray:
    try:
        arr = np.broadcast_to(np.asarray(x, dtype=float), (n,)).copy()
    except (ValueError, TypeError):
        raise ValueError(f"{name}: must be a number or one number per ball ({n})") from None
    if not (np.isfinite(arr).all() and (arr > 0).all()):
        raise ValueError(f"{name}: must be positive and finite")
    return arr


def _inputs(table, physics, ids, pos, radius, mass, on_table, state, level, seed) -> _Table:
    if not isinstance(table, Table):
        raise ValueError("table: must be a termpool Table")
    if not isinstance(physics, Physics):
        raise ValueError("physics: must be a termpool Physics")
    if not isinstance(state, State):
        raise ValueError("state: must be a termpool.rules State")
    if level not in LEVELS:
        raise ValueError(f"level: must be one of {', '.join(LEVELS)}, not {level!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"seed: must be an integer, not {seed!r}")
    ids = [str(b) for b in ids]
    n = len(ids)
    if "cue" not in ids:
        raise ValueError("ids: no cue ball 'cue'")
    if len(set(ids)) != n:
        raise ValueError("ids: duplicate ball ids")
    try:
        p = np.asarray(pos, dtype=float)
    except (ValueError, TypeError):
        raise ValueError("pos: must be numbers, shape (N, 2)") from None
    if p.shape != (n, 2):
        raise ValueError(f"pos: shape {p.shape} does not fit {n} ids (need ({n}, 2))")
    r = _per_ball(radius, n, "radius")
    m = _per_ball(mass, n, "mass")
    on = np.asarray(on_table)
    if on.shape != (n,) or on.dtype != bool:
        raise ValueError(f"on_table: must be {n} booleans, one per ball")
    cue = ids.index("cue")
    if not on[cue]:
        raise ValueError("on_table: the cue ball is not on the table")
    if not np.isfinite(p[on]).all():  # balls off the table may be anywhere, NaN included
        raise ValueError("pos: must be finite for the balls on the table")
    keep = np.nonzero(on)[0]
    sub = [ids[k] for k in keep]
    return _Table(sub, p[keep], r[keep], m[keep], sub.index("cue"))


# --------------------------------------------------------------------------- candidates


class _Cands:
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

    def extend(self, other: _Cands) -> None:
        for k in range(len(other)):
            self.add(other.speed[k], other.angle[k], other.side[k], other.top[k],
                     other.target[k], other.pocket[k], other.kind[k], other.chance[k],
                     other.via[k], other.aim[k])

    def __len__(self) -> int:
        return len(self.speed)


def _break_cands(t: _Table, targets: list[str], lv: Level) -> _Cands:
    """Hard shots at the rack's apex (the legal ball nearest the cue ball), at each of
    BREAK_SPEEDS and BREAK_SPINS, each struck BREAK_SAMPLES times with the level's errors (the
    same draws every time: a player's break is theirs). A break scatters the rack chaotically,
    so it is judged by its average over the samples, not by one exact outcome; the samples
    of a break are consecutive."""
    cands = _Cands()
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


def _pot_cands(t, targets, pockets, table, physics, lv: Level, budget: int) -> _Cands:
    cands = _Cands()
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


def _combo_cands(t, targets, mode: str, pockets, physics, lv: Level, budget: int) -> _Cands:
    """Combinations: a legal ball driven into another object ball that goes in.

    The target is sent to the ghost spot of the second ball's pot. The chance is that of
    both cuts (the first to within a quarter ball of its spot), blockers left to the batch."""
    cands = _Cands()
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


def _safety_cands(t: _Table, targets: list[str], table: Table, physics: Physics,
                  budget: int) -> _Cands:
    """Safeties and kicks at each legal ball, most useful first: touches (full and half-ball
    hits about hard enough to send the ball to a rail: the cue ball stays near where it is),
    soft full and half-ball hits, one-rail kicks (two guesses of the rebound: the cushion's
    restitution, and halfway to a mirror), a harder one-rail kick, two-rail kicks, more hits
    (thin cuts, firmer half-ball hits, a firm full hit: the batch finds the one that leaves
    least), then fans of one- and two-rail kicks aimed up to a few degrees to either side (the
    rebound of a spinning ball is only roughly known: the batch finds the one that hits)."""
    cands = _Cands()
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


def _calibrate(t: _Table, cands: _Cands, table: Table, physics: Physics,
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
        ghost = pt - reach[:, None] * np.stack([np.cos(rad), np.sin(rad)], axis=1)
        angles = np.degrees(np.arctan2(ghost[:, 1] - pc[1], ghost[:, 0] - pc[0]))
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
        eng.run_events(duration=SIM_SECONDS)
        final = eng.pos[:, 1]
        for n in range(B):
            where = _heading_point(eng.events[n])
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


def _heading_point(events: list[dict]) -> np.ndarray | None:
    """Where the object ball (index 1) first meets a cushion or a ball again after it was hit."""
    hit = False
    for ev in events:
        if 1 not in ev["i"]:
            continue
        if ev["type"] == "ball_ball" and not hit:
            hit = True
            continue
        if hit and ev["type"] in ("cushion", "ball_ball"):
            k = ev["i"].index(1)
            return np.array([ev["balls"][k]["x"], ev["balls"][k]["y"]])
    return None


# ------------------------------------------------------------------------------ judging


def _simulate(t: _Table, cands: _Cands, table: Table, physics: Physics,
              cue_at: np.ndarray | None = None) -> Engine:
    """All candidates in one batch; `cue_at` (B, 2) puts the cue ball elsewhere per table."""
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
    eng = Engine(table, physics, pos, vel, w, t.radius, t.mass, record=True)
    eng.run_events(duration=SIM_SECONDS)
    return eng


def _call(state: State, targets: list[str], t: _Table, cands: _Cands, b: int, summary,
          pockets: geo.Pockets) -> tuple[str, str] | None:
    """The call for candidate b: only for the 8 when it is the legal target. The pocket the
    simulation drops it in, else the pocket aimed at, else the one nearest the 8."""
    if state.mode != "8ball" or targets != ["8"] or not pockets.names:
        return None
    if "8" in summary.pocketed:
        return ("8", summary.pocketed["8"])
    if cands.pocket[b] >= 0:
        return ("8", pockets.names[cands.pocket[b]])
    p8 = t.pos[t.ids.index("8")]
    k = int(np.argmin(np.linalg.norm(pockets.aim - p8, axis=1)))
    return ("8", pockets.names[k])


def _score(state, targets, t, cands, eng, table, pockets, lv,
           sampled: bool = False) -> tuple[np.ndarray, list, list]:
    """Score every simulated table; returns (scores, calls, notes: (note, sees) pairs, see
    `Plan`). With `sampled`, the tables are samples of aim error and every pot counts in
    full."""
    B, n = eng.B, eng.N
    alive = eng.state != POCKETED
    final = eng.pos
    scores = np.zeros(B)
    calls: list = []
    notes: list = []
    sees: list = []
    leave_for: list[tuple[int, float, State]] = []  # (table, pot chance or -1, next state)
    practice = state.mode == "practice"
    # A pot that misses in play: the opponent gets the table (in practice, nobody does).
    miss = 0.0 if practice else -lv.leave * MISS_LEAVE
    foul = FOUL - (0.0 if practice else lv.leave)  # ball in hand: the best table to leave
    for b in range(B):
        summary = summarize(eng.events[b], t.ids, is_break=state.is_break)
        called = _call(state, targets, t, cands, b, summary, pockets)
        out, nxt = judge(replace(state, called=called), summary)
        calls.append(called)
        tgt = t.ids[cands.target[b]] if cands.target[b] >= 0 else None
        aimed = pockets.names[cands.pocket[b]] if cands.pocket[b] >= 0 else None
        potted = summary.object_pocketed
        # How likely the shot is to do in play what it did here: a pot aimed at a pocket
        # by its chance, the break as it is, anything else (a kiss, a combination) a fluke.
        sunk = t.ids[cands.via[b]] if cands.via[b] >= 0 else tgt  # the ball aimed at a pocket
        intended = sunk is not None and aimed is not None and summary.pocketed.get(sunk) == aimed
        p = 1.0 if cands.kind[b] == "break" or sampled else cands.chance[b] if intended \
            else FLUKE
        pocket = None if aimed is None else SAID.pocket(aimed)
        if out.winner is not None:
            scores[b] = p * WIN + (1 - p) * miss if out.winner == state.shooter else LOSS
            notes.append(words.reason(out.said, SAID))
            sees.append("win" if out.winner == state.shooter else "loss")
        elif out.foul is not None or (practice and out.ball_in_hand):
            scores[b] = foul
            why = words.reason(out.said, SAID)
            notes.append(f"foul: {why}" if out.foul else why)
            sees.append("foul")
        elif out.continue_turn and potted:
            scores[b] = p * CONTINUE + (1 - p) * miss
            leave_for.append((b, p, nxt))
            if intended and cands.kind[b] == "combo":
                notes.append(f"combination: the {tgt} into the {sunk}, {sunk} in the {pocket} "
                             "pocket")
            elif intended:
                notes.append(f"{tgt} in the {pocket} pocket")
            else:
                how = "the break" if cands.kind[b] == "break" else "a kiss or combination"
                notes.append(f"{', '.join(potted)} in by {how}")
            sees.append("pot")
        else:
            scores[b] = PASS
            if not practice:  # in practice the same player shoots again: nothing to deny
                leave_for.append((b, -1.0, nxt))
            word = {"break": "break", "safety": "safety", "kick": "kick"}.get(cands.kind[b])
            if word is None:
                word = f"try {sunk} in the {pocket} pocket"
            notes.append(f"{word} on the {tgt}" if cands.kind[b] in ("safety", "kick")
                         else word)
            sees.append("pass")
    if leave_for:
        rows = [b for b, _, _ in leave_for]
        tmask = np.zeros((len(rows), n), bool)
        for r, (b, _, nxt) in enumerate(leave_for):
            present = [t.ids[k] for k in range(n) if alive[b, k]]
            nxt_t = legal_targets(nxt, present) if "cue" in present else []
            tmask[r] = [bid in nxt_t for bid in t.ids]
        cue_alive = alive[rows, t.cue]
        chance, _ = geo.pot_chances(final[rows, t.cue], final[rows], alive[rows], tmask,
                                    t.radius, t.cue, pockets, table, LEAVE_SIGMA)
        value = geo.leave_value(chance)
        now = _opponent_now(state, t, pockets, table)
        for r, (b, p, _) in enumerate(leave_for):
            if not cue_alive[r]:
                continue
            # After a pot (p >= 0): the shooter's next shot, as likely as the pot itself.
            # After the turn passes (p < 0): the opponent's. A safety that leaves the opponent
            # no less than the table has now hides nothing: it counts as leaving them the
            # best table there is (a pot with any chance then goes first).
            if p >= 0:
                scores[b] += p * lv.position * value[r]
            elif cands.kind[b] == "safety" and value[r] >= now:
                scores[b] -= lv.leave
            else:
                scores[b] -= lv.leave * value[r]
    return scores, calls, list(zip(notes, sees, strict=True))


def _opponent_now(state: State, t: _Table, pockets: geo.Pockets, table: Table) -> float:
    """The leave value of the table as it lies, for the opponent (their legal balls, the cue
    ball where it is)."""
    opp = replace(state, shooter=state.opponent)
    tmask = np.array([[b in legal_targets(opp, t.ids) for b in t.ids]])
    chance, _ = geo.pot_chances(t.pos[t.cue][None], t.pos[None], np.ones((1, len(t.ids)), bool),
                                tmask, t.radius, t.cue, pockets, table, LEAVE_SIGMA)
    return float(geo.leave_value(chance)[0])


# ----------------------------------------------------------------------------------- API


class _Eval(NamedTuple):
    t: _Table
    targets: list[str]
    pockets: geo.Pockets
    lv: Level
    cands: _Cands
    scores: np.ndarray
    calls: list
    notes: list


def _evaluate(table, physics, ids, pos, radius, mass, on_table, state, level,
              max_candidates) -> _Eval:
    if isinstance(max_candidates, bool) or not isinstance(max_candidates, (int, np.integer)) \
            or max_candidates < MIN_CANDIDATES:
        raise ValueError(f"max_candidates: must be an integer of at least {MIN_CANDIDATES}")
    t = _inputs(table, physics, ids, pos, radius, mass, on_table, state, level, 0)
    lv = LEVELS[level]
    budget = max(int(max_candidates * lv.share), MIN_CANDIDATES)
    targets = legal_targets(state, t.ids)
    pockets = geo.pocket_geometry(table, float(t.radius[t.cue]))
    if state.is_break:
        cands = _break_cands(t, targets, lv)
    else:
        reserve = min(budget // 3, 24 * max(len(targets), 1))
        cands = _pot_cands(t, targets, pockets, table, physics, lv,
                           budget - reserve - lv.combos)
        cands.extend(_combo_cands(t, targets, state.mode, pockets, physics, lv,
                                  min(lv.combos, budget - reserve - len(cands))))
        _calibrate(t, cands, table, physics)
        # With a likely pot on the table the fallbacks get only their reserve; without one
        # they may fill the budget (a snooker needs many kicks).
        likely = any(c > 0.3 for c in cands.chance)
        cands.extend(_safety_cands(t, targets, table, physics,
                                   reserve if likely else budget - len(cands)))
    if len(cands) == 0:
        return _Eval(t, targets, pockets, lv, cands, np.zeros(0), [], [])
    eng = _simulate(t, cands, table, physics)
    scores, calls, notes = _score(state, targets, t, cands, eng, table, pockets, lv)
    return _Eval(t, targets, pockets, lv, cands, scores, calls, notes)


def _plan(ev: _Eval, b: int, score: float) -> Plan:
    c = ev.cands
    ball = pocket = None
    if c.kind[b] in ("pot", "combo"):
        ball = ev.t.ids[c.via[b] if c.via[b] >= 0 else c.target[b]]
        pocket = ev.pockets.names[c.pocket[b]]
    return Plan(c.speed[b], (c.angle[b] + 180.0) % 360.0 - 180.0, c.side[b], c.top[b],
                ev.calls[b], float(score), ev.notes[b][0], c.kind[b], ball, pocket,
                ev.notes[b][1])


def score_shots(table: Table, physics: Physics, ids: Sequence[str], pos, radius, mass,
                on_table, state: State, *, level: str = "normal",
                max_candidates: int = 256) -> list[Plan]:
    """Every candidate shot, simulated in one batch and scored, in a fixed order (before
    `choose_shot` checks the best few under aim error). Arguments as for `choose_shot`; the
    list is empty when no object ball is on the table."""
    ev = _evaluate(table, physics, ids, pos, radius, mass, on_table, state, level,
                   max_candidates)
    return [_plan(ev, b, ev.scores[b]) for b in range(len(ev.cands))]


# The check under errors: the centre and one step either side in aim, then in speed. Each
# side step is the three-point Gauss-Hermite rule's (sqrt(3) sd, weight 1/6); the two rules
# share their centre, which keeps the rest (an additive sum of the two one-dimensional rules).
VERIFY_POINTS = ((0.0, 0.0, 1 / 3), (1.0, 0.0, 1 / 6), (-1.0, 0.0, 1 / 6),
                 (0.0, 1.0, 1 / 6), (0.0, -1.0, 1 / 6))


def _verify(ev: _Eval, state: State, table: Table, physics: Physics) -> tuple[int, float]:
    """The best of the top few candidates once the level's errors are taken into account.

    Each is simulated again at VERIFY_POINTS, aim and speed off by sqrt(3) of the level's
    error, all in one batch, and scored as played (a pot counts in full where it goes in).
    Returns (candidate, its expected score)."""
    c, lv = ev.cands, ev.lv
    top = [int(k) for k in np.argsort(-ev.scores, kind="stable")[:lv.verify]]
    sub = _Cands()
    da, dv = math.sqrt(3.0) * lv.aim_sd, math.sqrt(3.0) * lv.speed_sd
    for k in top:
        for fa, fv, _ in VERIFY_POINTS:
            sub.add(c.speed[k] * (1 + fv * dv), c.angle[k] + fa * da, c.side[k], c.top[k],
                    c.target[k], c.pocket[k], c.kind[k], 1.0, c.via[k], c.aim[k])
    eng = _simulate(ev.t, sub, table, physics)
    s, _, _ = _score(state, ev.targets, ev.t, sub, eng, table, ev.pockets, lv, sampled=True)
    n = len(VERIFY_POINTS)
    expect = sum(w * s[j::n] for j, (_, _, w) in enumerate(VERIFY_POINTS))
    best = int(np.argmax(expect))  # the first of equal scores
    return top[best], float(expect[best])


def choose_shot(table: Table, physics: Physics, ids: Sequence[str], pos, radius, mass,
                on_table, state: State, *, level: str = "normal", seed: int = 0,
                max_candidates: int = 256) -> Plan:
    """The computer's shot for the player `state.shooter` (see the module's docstring).

    `ids`, `pos` (N, 2), `radius`, `mass` (numbers or one per ball) describe the balls;
    `on_table` (N booleans) says which are on the table. The best few candidates of the
    batch are checked under the level's aim error and the best of them is returned, as meant
    (`as_struck` adds the level's errors in striking it). Deterministic.
    """
    _inputs(table, physics, ids, pos, radius, mass, on_table, state, level, seed)
    ev = _evaluate(table, physics, ids, pos, radius, mass, on_table, state, level,
                   max_candidates)
    if len(ev.cands) == 0:  # nothing to aim at: roll the cue ball up the table
        return Plan(1.0, 0.0, 0.0, 0.0, None, PASS, "no object ball on the table")
    if state.is_break:  # the break whose samples did best on average, as meant
        mean = ev.scores.reshape(-1, BREAK_SAMPLES).mean(axis=1)
        k = int(np.argmax(mean))
        speed, (side, top) = BREAK_SPEEDS[k // len(BREAK_SPINS)], BREAK_SPINS[k % len(BREAK_SPINS)]
        angle = (geo.deg(ev.t.pos[ev.cands.target[0]] - ev.t.pos[ev.t.cue]) + 180.0) % 360.0 \
            - 180.0
        return Plan(speed, angle, side, top, None, float(mean[k]), "break", "break")
    if ev.lv.verify == 0:
        best = int(np.argmax(ev.scores))
        score = float(ev.scores[best])
    else:
        best, score = _verify(ev, state, table, physics)
    return _plan(ev, best, score)


def as_struck(plan: Plan, level: str, seed: int = 0) -> Plan:
    """The plan as the level strikes it: its errors of aim, speed and tip position drawn
    (seeded) from normal distributions and added (the tip kept within the miscue limit). The
    physics is deterministic, so a plan that pots in the batch pots in play: these errors
    are what makes a level miss."""
    if level not in LEVELS:
        raise ValueError(f"level: must be one of {', '.join(LEVELS)}, not {level!r}")
    lv = LEVELS[level]
    return with_error(plan, lv.aim_sd, lv.speed_sd, seed, lv.tip_sd)


def choose_option(option: str) -> Choice:
    """The computer's answer to an option: it accepts the table after an illegal 8-ball break
    and shoots after a push-out."""
    if option not in tuple(Option):
        raise ValueError(f"option: must be one of {', '.join(Option)}, not {option!r}")
    return OPTION_ANSWERS[Option(option)]


def with_error(plan: Plan, aim_sd: float, speed_sd: float, seed: int = 0,
               tip_sd: float = 0.0) -> Plan:
    """The plan as a player with these errors would strike it: normal errors of sd `aim_sd`
    degrees, `speed_sd` of the speed and `tip_sd` radii of tip position (seeded)."""
    rng = np.random.default_rng(seed)
    e_aim, e_speed = rng.normal(0.0, 1.0, 2)  # always drawn: each error has its own draw
    e_side, e_top = rng.normal(0.0, 1.0, 2)
    angle = plan.angle + aim_sd * float(e_aim)
    speed = float(np.clip(plan.speed * (1 + speed_sd * float(e_speed)), 0.1, BREAK_SPEEDS[-1]))
    side, top = clamp_tip(plan.side + tip_sd * float(e_side), plan.top + tip_sd * float(e_top))
    return plan._replace(speed=speed, angle=(angle + 180.0) % 360.0 - 180.0, side=side,
                         top=top)


def _spot_ok(xy: np.ndarray, t: _Table, table: Table, area: str) -> np.ndarray:
    """Legal cue ball spots among xy (M, 2): on the table, no overlap, in the kitchen if asked."""
    r = float(t.radius[t.cue])
    x, y = xy[:, 0], xy[:, 1]
    margin = 1e-3
    ok = (x >= r + margin) & (x <= table.length - r - margin)
    ok &= (y >= r + margin) & (y <= table.width - r - margin)
    ok &= in_area(table, x, area)  # on or behind the head string, for the kitchen
    others = [k for k in range(len(t.ids)) if k != t.cue]
    if others:
        d = np.linalg.norm(xy[:, None] - t.pos[others][None], axis=-1)
        ok &= (d >= r + t.radius[others][None] + 2 * margin).all(axis=1)
    return ok


def _cue_in_hand(ids, pos, on_table, table: Table):
    """pos and on_table with the cue ball on the table at the head spot (bad shapes are
    passed on unchanged for _inputs to report)."""
    names = [str(b) for b in ids]
    try:
        p = np.array(pos, dtype=float)
        on = np.array(on_table)
    except (ValueError, TypeError):
        return pos, on_table
    n = len(names)
    if "cue" in names and p.shape == (n, 2) and on.shape == (n,) and on.dtype == bool:
        k = names.index("cue")
        p[k] = table.head_spot
        on[k] = True
        return p, on
    return pos, on_table


def _string_spot(t: _Table, table: Table, area: str, share: float) -> np.ndarray | None:
    """The free point of the head string nearest the one `share` of the width across."""
    hx, hy = head_string(table), share * table.width
    xy = np.array([[hx, hy + s * k * 0.01] for k in range(130) for s in (1, -1)])
    ok = np.nonzero(_spot_ok(xy, t, table, area))[0]
    return xy[ok[0]] if len(ok) else None


def _break_spot(t: _Table, table: Table, physics: Physics, state: State, area: str,
                lv: Level) -> np.ndarray:
    """Where the level breaks from: the free point of the head string nearest each of its
    break spots; with several, the one whose best break (`_break_cands`, all in one batch)
    scores best on average over its samples."""
    spots = [xy for f in lv.break_spots if (xy := _string_spot(t, table, area, f)) is not None]
    if not spots:
        raise ValueError(f"area: no free spot for the cue ball in the {area}")
    if len(spots) == 1:
        return spots[0]
    targets = legal_targets(state, t.ids)
    cands, cue_at = _Cands(), []
    for xy in spots:
        here = t._replace(pos=t.pos.copy())
        here.pos[t.cue] = xy
        one = _break_cands(here, targets, lv)
        cands.extend(one)
        cue_at += [xy] * len(one)
    if len(cands) == 0:
        return spots[0]
    eng = _simulate(t, cands, table, physics, np.array(cue_at))
    pockets = geo.pocket_geometry(table, float(t.radius[t.cue]))
    scores, _, _ = _score(state, targets, t, cands, eng, table, pockets, lv)
    mean = scores.reshape(len(spots), -1, BREAK_SAMPLES).mean(axis=2).max(axis=1)
    return spots[int(np.argmax(mean))]


def _spot_chances(t: _Table, table: Table, state: State, area: str, distances: int,
                  sigma: float) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Legal spots for the cue ball in hand (M, 2) and the pot chances (M, N, P) each leaves:
    spots behind the ghost ball of each pot at a few cut angles and `distances` distances,
    then a coarse grid of the area. Also returns the legal targets."""
    r = float(t.radius[t.cue])
    pockets = geo.pocket_geometry(table, r)
    targets = legal_targets(state, t.ids)
    spots = []
    dists = (0.3, 0.15, 0.5)[:distances]
    for b in targets:
        i = t.ids.index(b)
        for k in range(len(pockets.names)):
            u = pockets.aim[k] - t.pos[i]
            u = u / max(float(np.linalg.norm(u)), 1e-9)
            if float(np.dot(u, pockets.out[k])) <= pockets.cos_limit[k]:
                continue
            ghost = t.pos[i] - (r + t.radius[i]) * u
            for cut in (0.0, 15.0, -15.0, 30.0, -30.0):
                c = math.radians(cut)
                d = np.array([u[0] * math.cos(c) - u[1] * math.sin(c),
                              u[0] * math.sin(c) + u[1] * math.cos(c)])
                for s in dists:
                    spots.append(ghost - s * d)
    hi = head_string(table) if area == "kitchen" else table.length
    gx = np.linspace(0.05, hi - 0.02, 12)
    gy = np.linspace(0.05, table.width - 0.05, 8)
    spots += [np.array([x, y]) for x in gx for y in gy]
    xy = np.array(spots)
    xy = xy[_spot_ok(xy, t, table, area)]
    if len(xy) == 0:
        raise ValueError(f"area: no free spot for the cue ball in the {area}")
    M, n = len(xy), len(t.ids)
    balls = np.broadcast_to(t.pos, (M, n, 2)).copy()
    balls[:, t.cue] = xy
    tmask = np.broadcast_to(np.array([b in targets for b in t.ids]), (M, n))
    chance, _ = geo.pot_chances(xy, balls, np.ones((M, n), bool), tmask, t.radius, t.cue,
                                pockets, table, sigma)
    return xy, chance, targets


def choose_placement(table: Table, physics: Physics, ids: Sequence[str], pos, radius, mass,
                     on_table, state: State, area: str, *, level: str = "normal",
                     seed: int = 0) -> tuple[float, float]:
    """Where to put the cue ball in hand: `area` "anywhere" or "kitchen" (behind the head
    string, x <= length / 4). Spots behind the ghost ball of each pot at a few cut angles and
    distances, and a coarse grid as a fallback, are scored by the shots they leave. On a
    break, the level's break spot on the head string (`_break_spot`).

    The cue ball's entries in `pos` and `on_table` are ignored (it is being placed: after a
    scratch it is still in a pocket); it must be in `ids`.
    """
    if area not in AREAS:
        raise ValueError(f"area: must be one of {', '.join(AREAS)}, not {area!r}")
    pos, on_table = _cue_in_hand(ids, pos, on_table, table)
    t = _inputs(table, physics, ids, pos, radius, mass, on_table, state, level, seed)
    lv = LEVELS[level]
    if state.is_break:
        spot = _break_spot(t, table, physics, state, area, lv)
        return float(spot[0]), float(spot[1])
    xy, chance, targets = _spot_chances(t, table, state, area, lv.spots, LEAVE_SIGMA)
    value = geo.leave_value(chance)
    # Between spots of equal value (say, no pot anywhere), the one nearest a legal ball.
    legal = [k for k, b in enumerate(t.ids) if b in targets]
    if legal:
        near = np.linalg.norm(xy[:, None] - t.pos[legal][None], axis=-1).min(axis=1)
        value = value - 1e-3 * near / table.length
    best = int(np.argmax(value))
    spot = xy[best]
    if lv.spot_sd > 0:
        rng = np.random.default_rng(seed)
        moved = spot + rng.normal(0.0, lv.spot_sd, 2)
        if _spot_ok(moved[None], t, table, area)[0]:
            spot = moved
    return float(spot[0]), float(spot[1])


def best_chance(table: Table, physics: Physics, ids: Sequence[str], pos, radius, mass,
                on_table, state: State, *, area: str | None = None,
                sigma: float = LEAVE_SIGMA) -> float:
    """The best chance (0..1) of a straight pot for `state.shooter` under an aim error of
    `sigma` degrees: from where the cue ball lies, or with `area` ("anywhere", "kitchen") from
    the best spot for the cue ball in hand there. It measures what a shot leaves."""
    if area is not None and area not in AREAS:
        raise ValueError(f"area: must be one of {', '.join(AREAS)}, not {area!r}")
    if area is not None:
        pos, on_table = _cue_in_hand(ids, pos, on_table, table)
    t = _inputs(table, physics, ids, pos, radius, mass, on_table, state, "normal", 0)
    if area is not None:
        _, chance, _ = _spot_chances(t, table, state, area, 3, sigma)
        return float(chance.max(initial=0.0))
    pockets = geo.pocket_geometry(table, float(t.radius[t.cue]))
    targets = legal_targets(state, t.ids)
    tmask = np.array([[b in targets for b in t.ids]])
    chance, _ = geo.pot_chances(t.pos[t.cue][None], t.pos[None], np.ones((1, len(t.ids)), bool),
                                tmask, t.radius, t.cue, pockets, table, sigma)
    return float(chance.max(initial=0.0))


# ----------------------------------------------------------------------------- the player


@dataclass(frozen=True)
class Computer:
    """The computer as a player of a match (`game.players.Computer`): it answers options,
    places the cue ball in hand and plays its shots as its level does, seeded by the match's
    seed and the shot's number (the same match gives the same decisions)."""

    level: str = "normal"
    name: str = "Computer"
    candidates: int = 256  # the batch's budget (`choose_shot`'s max_candidates)

    def __post_init__(self) -> None:
        if self.level not in LEVELS:
            raise ValueError(f"level: must be one of {', '.join(LEVELS)}, not {self.level!r}")

    @staticmethod
    def seed(match) -> int:
        """The seed of the next decision in `match`."""
        return match.seed * 1000 + len(match.history)

    @staticmethod
    def _balls(match) -> tuple:
        return (match.table, match.physics, match.ids, match.pos, match.radius, match.mass,
                match.on_table, match.state)

    def answer(self, match) -> Choice:
        return choose_option(match.option)

    def place(self, match) -> tuple[float, float]:
        """Where it puts the cue ball in hand (`choose_placement`); should that ever be
        refused, where a scratched cue ball waits."""
        x, y = choose_placement(*self._balls(match), match.ball_in_hand, level=self.level,
                                seed=self.seed(match))
        return match.waiting_spot() if match.placement_error(x, y) else (x, y)

    def shot(self, match) -> Plan:
        """The shot it plays: `choose_shot`'s plan as it strikes it (`as_struck`)."""
        seed = self.seed(match)
        plan = choose_shot(*self._balls(match), level=self.level, seed=seed,
                           max_candidates=self.candidates)
        return as_struck(plan, self.level, seed)
