"""The aim aid: the engine's own prediction of the shot about to be played.

`predict(match, shot)` plays the shot on a fresh engine built exactly as the match builds the
real one (the same scene through the same loader, so the same numbers bit for bit: spin,
throw, cushions and all) and stops at the events the aid shows: the cue ball's path to the
first ball it hits (through cushions), that ball's path to its next contact (a cushion, a
pocket, another ball) or to rest, and the cue ball's path from the hit through one cushion to
its next contact; after the hit a ball in a pocket's jaws is followed on through them, to the
pocket or out.
The engine is driven one event time at a time (`Engine.t_next`, `run_events(duration)`), so it
simulates only up to the last event the aid needs.

Between events every ball moves with a constant acceleration (sliding or rolling friction), so
each leg is rebuilt from the event log alone: a ball's position and velocity just after an
event and its position at its next event give the parabola between them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from termpool.game import record
from termpool.game.turn import Shot
from termpool.physics.cue import strike
from termpool.physics.engine import Engine

LEVELS = ("off", "ghost", "full")  # what the aid shows: nothing, the ghost ball, every path
MAX_CUSHIONS = 3  # the cue ball is followed through this many cushions to its first ball
# After the hit, a ball that meets a pocket's jaws is followed on through them (this many
# contacts at most): whether it rattles out or drops is what the shot comes to.
MAX_JAWS = 6
JAWS = ("jaw", "tip")  # the cushion features of a pocket's mouth (`Features.names`)
# After the hit the cue ball is followed through this many cushions (not the object ball):
# where it goes off its first rail is where a scratch most often comes from.
AFTER_CUSHIONS = 1
MAX_TIME = 30.0  # simulated seconds: the aid gives up on a shot still going after this
MAX_INSTANTS = 2000  # event times run; bounds the work of a pathological shot
BEND_M = 0.0005  # a leg's piece bending less than this off its chord is drawn straight
STEP_M = 0.01  # a bending piece is drawn with a point about every this many metres
TOUCH = ("ball_ball", "cushion", "pocket")  # events that end a leg
BIG_GROUP = 4  # a first ball frozen in a group this big (a rack) ends the aid at the hit
TOUCH_GAP = 1e-6  # m: balls this close count as touching
PEEK_S = 1e-9  # s: how long before an event the aid looks whether it is a hit on a rack


@dataclass(frozen=True)
class Leg:
    """A ball's path: points (K, 2) in metres from its start to where it ends, and why it
    ends: "ball" (meets a ball), "cushion", "pocket", "rest", or "open" (the aid stopped
    following it). `pocket` names the pocket for "pocket"."""

    points: np.ndarray
    end: str
    pocket: str | None = None


@dataclass(frozen=True)
class Prediction:
    """What the engine says the shot does: `cue` is the cue ball's path to its first ball
    (`ball`, an index into the match's balls, None if it meets none: then the path ends at
    its pocket, its rest, or its last cushion followed); `ghost` is the cue ball's centre at
    that contact; `object` the first ball's path from the contact to its next contact or
    rest; `after` the cue ball's from the contact, through AFTER_CUSHIONS cushions, to its
    next contact or rest."""

    cue: Leg
    ball: int | None = None
    ghost: tuple[float, float] | None = None
    object: Leg | None = None
    after: Leg | None = None


class _Track:
    """Knots (t, x, y, vx, vy) of one ball's leg, from its log."""

    def __init__(self, t: float, s: dict) -> None:
        self.knots = [(t, s["x"], s["y"], s["vx"], s["vy"])]
        self.end: str | None = None
        self.pocket: str | None = None

    def add(self, t: float, s: dict) -> None:
        self.knots.append((t, s["x"], s["y"], s["vx"], s["vy"]))

    def close(self, t: float, s: dict, why: str, pocket: str | None = None) -> None:
        self.add(t, s)
        self.end, self.pocket = why, pocket

    def leg(self) -> Leg:
        return Leg(_path(self.knots), self.end or "open", self.pocket)


def _path(knots: list[tuple]) -> np.ndarray:
    """The points of a leg through its knots, each piece the parabola of constant
    acceleration from the knot's position and velocity to the next knot's position."""
    pts = [knots[0][1:3]]
    for (ta, xa, ya, vxa, vya), (tb, xb, yb, _, _) in zip(knots, knots[1:], strict=False):
        T = tb - ta
        if T <= 1e-12:
            pts.append((xb, yb))
            continue
        ax = 2.0 * (xb - xa - vxa * T) / (T * T)
        ay = 2.0 * (yb - ya - vya * T) / (T * T)
        chord = math.hypot(xb - xa, yb - ya)
        # How far the parabola bows off its chord: the acceleration across the chord, T^2/8.
        across = abs(ax * (yb - ya) - ay * (xb - xa)) / chord if chord > 0 else 0.0
        if across * T * T / 8.0 > BEND_M:
            n = min(64, max(4, math.ceil(chord / STEP_M)))
            for tau in np.linspace(0.0, T, n + 1)[1:-1]:
                pts.append((xa + vxa * tau + 0.5 * ax * tau * tau,
                            ya + vya * tau + 0.5 * ay * tau * tau))
        pts.append((xb, yb))
    return np.asarray(pts, dtype=float)


_STOPPED = ("stationary", "spinning")


def _frozen_groups(pos: np.ndarray, radius: np.ndarray, skip: int) -> np.ndarray:
    """Which balls lie in a group of at least BIG_GROUP balls touching one another (a rack)."""
    d = np.hypot(*(pos[:, None, :] - pos[None, :, :]).transpose(2, 0, 1))
    touch = d <= radius[:, None] + radius[None, :] + TOUCH_GAP
    touch[skip, :] = touch[:, skip] = False
    label = np.arange(len(pos))
    for _ in range(len(pos)):  # spread the smallest label through each group
        new = np.where(touch, label[None, :], label[:, None]).min(axis=1)
        if (new == label).all():
            break
        label = new
    sizes = np.bincount(label, minlength=len(pos))
    return sizes[label] >= BIG_GROUP


class Predictor:
    """Predictions from one layout of the table (the match as it stands between shots):
    the scene is loaded once; each shot then costs only its own simulation."""

    def __init__(self, match) -> None:
        self.scene = record.shot_scene(match.scene_dict(), Shot(0.0, 0.0).to_json())
        ids = list(self.scene.ids)
        self.rows = [match.ids.index(b) for b in ids]
        self.cue = ids.index("cue") if "cue" in ids else None
        self.frozen = (_frozen_groups(self.scene.pos, self.scene.radius, self.cue)
                       if self.cue is not None else None)

    def start(self, shot: Shot) -> Job | None:
        """A prediction of `shot` to run (None when the strike is refused: a miscue)."""
        c, sc = self.cue, self.scene
        if c is None:
            return None
        try:
            (vx, vy), w = strike(shot.speed, shot.angle, shot.side, shot.top,
                                 float(sc.radius[c]))
        except ValueError:
            return None
        vel, spin = sc.vel.copy(), sc.w.copy()
        vel[c], spin[c] = (vx, vy), w
        # As record.start_engine builds the shot's engine from its scene: the same numbers.
        eng = Engine(sc.table, sc.physics, sc.pos, vel, spin, sc.radius, sc.mass, record=True)
        start = {"x": float(sc.pos[c, 0]), "y": float(sc.pos[c, 1]), "vx": vx, "vy": vy}
        return Job(eng, c, start, self.frozen, self.rows)

    def shot(self, shot: Shot) -> Prediction | None:
        """The whole prediction of `shot`, at once."""
        job = self.start(shot)
        if job is None:
            return None
        job.run()
        return job.result()


def predict(match, shot: Shot) -> Prediction | None:
    """The engine's prediction of `shot` from the match's table now (see `Predictor`)."""
    return Predictor(match).shot(shot)


class Job:
    """One prediction, run an event time at a time (`run(n)`), so that a frame can take a
    bounded share of it; `result()` is the prediction so far (legs still being followed end
    where their ball is now, "open"), and the whole one once `done`."""

    def __init__(self, eng: Engine, c: int, start: dict, frozen: np.ndarray,
                 rows: list[int]) -> None:
        self.eng, self.c, self.frozen, self.rows = eng, c, frozen, rows
        self.cue = _Track(0.0, start)
        self.hit: dict = {}  # after the first hit: "ball", "ghost", "object", "after" tracks
        self.cushions = 0
        self.jaws = {"object": 0, "after": 0}  # jaw contacts followed through, by leg
        self.rails_after = 0  # the cue ball's cushions followed through after the hit
        self.seen = 0
        self.instants = 0
        self.done = False
        self._rack: int | None = None  # the first ball hit, when it is in a frozen group

    def run(self, n: int | None = None) -> bool:
        """Run up to n more event times (all that are needed with None); True when done."""
        eng, c = self.eng, self.c
        k = 0
        while not self.done and (n is None or k < n):
            k += 1
            self.instants += 1
            if (eng.at_rest()[0] or float(eng.t_next[0]) > MAX_TIME
                    or self.instants > MAX_INSTANTS):
                self._finish()
                break
            t_next = float(eng.t_next[0])
            if self.frozen.any() and not self.hit and t_next > PEEK_S:
                ball = _about_to_meet(eng, c, t_next - PEEK_S, self.frozen)
                if ball is not None:  # a rack: its contacts all come at once, at a great
                    s = _state(eng, c)  # cost, and none of them is a path to aim by
                    self.cue.close(eng.time, s, "ball")
                    self._rack = ball
                    self.done = True
                    break
            eng.run_events(duration=t_next)
            self._read()
            h = self.hit
            if self.cue.end is not None and (not h or (h["object"].end and h["after"].end)):
                self.done = True
        return self.done

    def _read(self) -> None:
        """Take the new events of the log into the legs."""
        c, log = self.c, self.eng.events[0]
        for ev in log[self.seen:]:
            t, kind, who = ev["t"], ev["type"], ev["i"]
            states = dict(zip(who, ev["balls"], strict=True))
            if not self.hit:
                if c not in states:
                    continue
                s = states[c]
                if kind == "ball_ball":
                    other = who[1] if who[0] == c else who[0]
                    self.cue.close(t, s, "ball")
                    self.hit = {"ball": other, "ghost": (s["x"], s["y"]),
                                "after": _Track(t, s), "object": _Track(t, states[other])}
                elif kind == "pocket":
                    self.cue.close(t, s, "pocket", ev.get("pocket"))
                elif kind == "cushion":
                    self.cushions += 1
                    if self.cushions > MAX_CUSHIONS:
                        self.cue.close(t, s, "cushion")
                    else:
                        self.cue.add(t, s)
                elif s["state"] in _STOPPED:
                    self.cue.close(t, s, "rest")
                else:
                    self.cue.add(t, s)
                continue
            for key, k in (("object", self.hit["ball"]), ("after", c)):
                tr = self.hit[key]
                if tr.end is not None or k not in states:
                    continue
                s = states[k]
                if kind == "cushion" and ev.get("feature") in JAWS and self.jaws[key] < MAX_JAWS:
                    self.jaws[key] += 1
                    tr.add(t, s)
                elif (kind == "cushion" and key == "after" and ev.get("feature") not in JAWS
                      and self.rails_after < AFTER_CUSHIONS):
                    self.rails_after += 1
                    tr.add(t, s)
                elif kind in TOUCH:
                    tr.close(t, s, kind if kind != "ball_ball" else "ball", ev.get("pocket"))
                elif s["state"] in _STOPPED:
                    tr.close(t, s, "rest")
                else:
                    tr.add(t, s)
        self.seen = len(log)

    def _finish(self) -> None:
        """The table is at rest (or the aid gives up): close the legs where the balls are."""
        h = self.hit
        for tr, k in ((self.cue, self.c), *(((h["object"], h["ball"]), (h["after"], self.c))
                                            if h else ())):
            if tr.end is None:
                tr.close(self.eng.time, _state(self.eng, k),
                         "rest" if bool(self.eng.at_rest()[0]) else "open")
        self.done = True

    def result(self) -> Prediction:
        """The prediction so far: unfinished legs end where their ball is now ("open")."""
        h = self.hit
        legs = [self.cue, *((h["object"], h["after"]) if h else ())]
        ks = [self.c, *((h["ball"], self.c) if h else ())]
        out = [tr.leg() if tr.end is not None else _open(tr, self.eng, k)
               for tr, k in zip(legs, ks, strict=True)]
        if self._rack is not None:
            g = out[0].points[-1]
            return Prediction(out[0], self.rows[self._rack], (float(g[0]), float(g[1])))
        if not h:
            return Prediction(out[0])
        return Prediction(out[0], self.rows[h["ball"]], h["ghost"], out[1], out[2])


def _open(tr: _Track, eng: Engine, k: int) -> Leg:
    s = _state(eng, k)
    return Leg(_path([*tr.knots, (eng.time, s["x"], s["y"], s["vx"], s["vy"])]), "open")


def _state(eng: Engine, k: int) -> dict:
    p, v = eng.pos[0][k], eng.vel[0][k]
    return {"x": float(p[0]), "y": float(p[1]), "vx": float(v[0]), "vy": float(v[1])}


def _about_to_meet(eng: Engine, c: int, t: float, frozen: np.ndarray) -> int | None:
    """Run to time t (just before the next event) and name the ball of a frozen group the
    cue ball is then touching and closing on, if any: that event is the hit."""
    eng.run_events(duration=t)
    p, v = eng.pos[0], eng.vel[0]
    d = p - p[c]
    gap = np.hypot(d[:, 0], d[:, 1]) - eng.radius[0] - eng.radius[0, c]
    closing = d @ v[c] > 0.0
    near = np.flatnonzero(frozen & closing & (gap <= TOUCH_GAP))
    return int(near[np.argmin(gap[near])]) if near.size else None
