"""Closed-form motion: what the model's equations (docs/physics.md) give on paper for simple
shots, computed without the engine, as references the engine can be measured against.

An answer (`Answer`) is every ball's path as quadratic pieces between events (`Track`), the
contacts and transitions it passes through (named as the engine names its events), and the
final positions. Two models are derived:

- the engine's (`Track.roll_out`): sliding friction on the contact point's slip, rolling
  resistance, spin; with R the radius, g gravity and u = v + R z x w the slip, a sliding ball
  has a = -mu_s g u_hat and dw_xy/dt = (5 mu_s g / 2R) z x u_hat until u = 0 after
  |u| / (3.5 mu_s g), a rolling one a = -mu_r g v_hat until v = 0;
- the seed game's (`Track.coast`), which the naive baselines step: no spin and so no sliding;
  a ball's full speed falls at mu_r g.

Contacts are frictionless between equal balls: (1 + e)/2 of the closing speed moves along
the line of centres and spins are untouched. `shot` is one ball meeting a still one, `cradle`
a ball driven into a row of touching balls (and, under the engine's model, pushing the row on
with its top spin). The scenes built from them are in closed_cases.py.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from termpool.physics.params import BALL_RADIUS, Physics

Vec = Sequence[float] | np.ndarray  # a horizontal vector (x, y), or a spin's (wx, wy)
R = BALL_RADIUS
ROUNDING = 1e-12  # m/s: a slip or speed this small is the rounding of an exact zero
X_HAT = np.array([1.0, 0.0])
# The slip completion: a rolling ball given a small push slides for an instant and rolls on
# with 5/7 of it, so a push moves it as if it were this much heavier (docs/physics.md).
ROLLING_MASS = 7.0 / 5.0
_TRANSITIONS = {("slide", "roll"): "slide_to_roll", ("slide", "rest"): "slide_to_stop",
                ("roll", "rest"): "roll_to_stop"}


def _vec(x: Vec) -> np.ndarray:
    return np.array(x, dtype=float)


def _perp(v: np.ndarray) -> np.ndarray:
    """z x v for a horizontal vector (the xy part of z x w for a spin w)."""
    return np.array([-v[1], v[0]])


def slip(v: np.ndarray, w_xy: np.ndarray) -> np.ndarray:
    """The contact point's velocity u = v + R z x w."""
    return v + R * _perp(w_xy)


def rolling_spin(v: np.ndarray) -> np.ndarray:
    """The (wx, wy) that makes the slip zero: v = R (wy, -wx)."""
    return np.array([-v[1], v[0]]) / R


# ------------------------------------------------------------------------------ paths


@dataclass
class Piece:
    """p(t) = p0 + v0 d + a d^2 / 2 and w_xy(t) = w0 + alpha d, d = t - t0, from t0 on."""

    kind: str  # "slide", "roll" or "rest"
    t0: float
    p0: np.ndarray
    v0: np.ndarray
    a: np.ndarray
    w0: np.ndarray
    alpha: np.ndarray

    def state(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        d = t - self.t0
        return self.p0 + (self.v0 + 0.5 * self.a * d) * d, self.v0 + self.a * d, \
            self.w0 + self.alpha * d


@dataclass
class Track:
    """One ball's closed-form motion: pieces in time order (each lasts until the next one
    starts, the last for ever) and the transitions between them, as (time, engine event)."""

    pieces: list[Piece] = field(default_factory=list)
    events: list[tuple[float, str]] = field(default_factory=list)

    def add(self, kind: str, t0: float, p: Vec, v: Vec, a: Vec, w: Vec, alpha: Vec,
            contact: bool = False) -> None:
        """Start a piece at t0. The change of state is a transition event unless a contact
        caused it (`contact`): the engine logs that as the contact."""
        if self.pieces and not contact and self.pieces[-1].kind != kind:
            self.events.append((t0, _TRANSITIONS[(self.pieces[-1].kind, kind)]))
        self.pieces.append(Piece(kind, t0, _vec(p), _vec(v), _vec(a), _vec(w), _vec(alpha)))

    def rest(self, t0: float, p: Vec, contact: bool = False) -> None:
        z = np.zeros(2)
        self.add("rest", t0, p, z, z, z, z, contact)

    def cut(self, t: float) -> None:
        """Forget everything from time t on (a contact changes the motion there)."""
        self.pieces = [self.pieces[0]] + [pc for pc in self.pieces[1:] if pc.t0 < t]
        self.events = [e for e in self.events if e[0] < t]

    def state(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity and (wx, wy) at t, just after anything that happens at t."""
        piece = [pc for pc in self.pieces if pc.t0 <= t][-1]
        return piece.state(t)

    def positions(self, ts: np.ndarray) -> np.ndarray:
        out = np.empty((len(ts), 2))
        for pc in self.pieces:
            now = ts >= pc.t0
            d = (ts[now] - pc.t0)[:, None]
            out[now] = pc.p0 + (pc.v0 + 0.5 * pc.a * d) * d
        return out

    def roll_out(self, ph: Physics, t: float, p: Vec, v: Vec, w: Vec,
                 contact: bool = False) -> None:
        """Nothing left to meet: the ball slides while its contact point slips, then rolls,
        then rests."""
        g, p, v, w = ph.g, _vec(p), _vec(v), _vec(w)
        u = slip(v, w)
        us = float(np.hypot(*u))
        if us > ROUNDING:
            uh = u / us
            a = -ph.mu_slide * g * uh
            alpha = 2.5 * ph.mu_slide * g / R * _perp(uh)
            self.add("slide", t, p, v, a, w, alpha, contact)
            contact = False
            ts = us / (3.5 * ph.mu_slide * g)
            t, (p, v, w) = t + ts, self.pieces[-1].state(t + ts)
        vs = float(np.hypot(*v))
        if vs > ROUNDING:
            a = -ph.mu_roll * g * v / vs
            self.add("roll", t, p, v, a, rolling_spin(v), rolling_spin(a), contact)
            contact = False
            tr = vs / (ph.mu_roll * g)
            t, p = t + tr, self.pieces[-1].state(t + tr)[0]
        self.rest(t, p, contact)

    def coast(self, ph: Physics, t: float, p: Vec, v: Vec, contact: bool = False) -> None:
        """The seed game's model: no spin, the speed falls at mu_roll g to rest."""
        p, v = _vec(p), _vec(v)
        vs = float(np.hypot(*v))
        if vs > ROUNDING:
            a = -ph.mu_roll * ph.g * v / vs
            self.add("roll", t, p, v, a, np.zeros(2), np.zeros(2), contact)
            contact = False
            tr = vs / (ph.mu_roll * ph.g)
            t, p = t + tr, self.pieces[-1].state(t + tr)[0]
        self.rest(t, p, contact)

    def reach(self, e: np.ndarray, s: float) -> float:
        """The first time the ball is s metres along the straight line e from its start."""
        x0 = float(self.pieces[0].p0 @ e)
        for k, pc in enumerate(self.pieces):
            end = self.pieces[k + 1].t0 if k + 1 < len(self.pieces) else math.inf
            # x(d) = x(t0) + (v0.e) d + (a.e) d^2 / 2 = x0 + s
            d = _first_root(0.5 * float(pc.a @ e), float(pc.v0 @ e),
                            float(pc.p0 @ e) - x0 - s, end - pc.t0)
            if d is not None:
                return pc.t0 + d
        raise ValueError("the ball never gets that far")


def _first_root(a: float, b: float, c: float, span: float) -> float | None:
    """The smallest root of a d^2 + b d + c = 0 in [0, span], or None."""
    if a == 0.0:
        roots = [-c / b] if b != 0.0 else []
    else:
        disc = b * b - 4.0 * a * c
        if disc < 0.0:
            return None
        q = -0.5 * (b + math.copysign(math.sqrt(disc), b))  # without cancellation
        roots = [q / a] + ([c / q] if q != 0.0 else [])
    ok = [d for d in roots if 0.0 <= d <= span]
    return min(ok) if ok else None


def collide(vi: np.ndarray, vj: np.ndarray, n: np.ndarray,
            e: float) -> tuple[np.ndarray, np.ndarray]:
    """Frictionless contact of equal balls, n from i to j: (1 + e)/2 of the closing speed
    moves along n; spins are untouched."""
    jn = 0.5 * (1.0 + e) * float((vi - vj) @ n)
    return vi - jn * n, vj + jn * n


# ------------------------------------------------------------------------------ answers


@dataclass
class Answer:
    """A scene's closed-form answer under one model: a track per ball and the contacts."""

    tracks: list[Track]
    contacts: list[tuple[float, list[int]]]

    def positions(self, ts: np.ndarray) -> np.ndarray:
        """(len(ts), N, 2) positions at times ts."""
        return np.stack([tr.positions(ts) for tr in self.tracks], axis=1)

    @property
    def start(self) -> np.ndarray:
        return np.array([tr.pieces[0].p0 for tr in self.tracks])

    @property
    def final(self) -> np.ndarray:
        return np.array([tr.pieces[-1].p0 for tr in self.tracks])

    @property
    def events(self) -> list[dict]:
        """Contacts and transitions as the engine logs them (type, ball ids, time and the
        balls' states just after)."""
        out = [(t, "ball_ball", ids) for t, ids in self.contacts]
        out += [(t, kind, [i]) for i, tr in enumerate(self.tracks) for t, kind in tr.events]
        out.sort(key=lambda e: e[0])
        evs = []
        for t, kind, ids in out:
            balls = []
            for i in ids:
                p, v, w = self.tracks[i].state(t)
                balls.append({"x": float(p[0]), "y": float(p[1]), "vx": float(v[0]),
                              "vy": float(v[1]), "w": [float(w[0]), float(w[1]), 0.0]})
            evs.append({"t": t, "type": kind, "i": list(ids), "balls": balls})
        return evs


def shot(ph: Physics, start: Vec, v: Vec, w: Vec, target: Vec, n: Vec, seed: bool) -> Answer:
    """A ball from `start` moving along +x with velocity v and spin w (wx, wy) meets a ball
    resting at `target`, the line of centres at contact being n: the contact is where the
    mover's centre is at target - 2R n."""
    mover, still = Track(), Track()
    if seed:
        mover.coast(ph, 0.0, start, v)
    else:
        mover.roll_out(ph, 0.0, start, v, w)
    still.rest(0.0, target)
    meet = _vec(target) - 2 * R * _vec(n)
    tc = mover.reach(X_HAT, float(meet[0] - start[0]))
    _, vc, wc = mover.state(tc)
    mover.cut(tc)
    still.cut(tc)
    va, vb = collide(vc, np.zeros(2), _vec(n), ph.e_ball)
    if seed:
        mover.coast(ph, tc, meet, va, contact=True)
        still.coast(ph, tc, target, vb, contact=True)
    else:
        mover.roll_out(ph, tc, meet, va, wc, contact=True)
        still.roll_out(ph, tc, target, vb, np.zeros(2), contact=True)
    return Answer([mover, still], [(tc, [0, 1])])


def group_push(ph: Physics, pushed: int) -> float:
    """Acceleration of a sliding ball with top spin pushing `pushed` touching balls ahead of
    it, all moving as one body: friction drives the slipping pusher (mu_s g on its mass), each
    pushed ball rolls (a push counts ROLLING_MASS times its mass, and rolling resistance takes
    mu_r g of its speed): a = g (mu_s - k n mu_r) / (1 + k n), k = ROLLING_MASS."""
    kn = ROLLING_MASS * pushed
    return ph.g * (ph.mu_slide - kn * ph.mu_roll) / (1.0 + kn)


def cradle(ph: Physics, start: Vec, v: Vec, w: Vec, row_x: float, row: int,
           seed: bool) -> Answer:
    """A ball from `start` along +x into a row of `row` touching balls from x = row_x. The
    wave passes pair by pair (e = 1: each ball stops and the next takes its speed) and the
    last ball leaves; under the engine's model the first ball's top spin then drives it into
    the others and they move as one body (`group_push`) until its slip is gone, then all roll
    to a stop together."""
    tracks = [Track() for _ in range(row + 1)]
    first = tracks[0]
    if seed:
        first.coast(ph, 0.0, start, v)
    else:
        first.roll_out(ph, 0.0, start, v, w)
    at = [np.array([row_x + 2 * R * k, start[1]]) for k in range(-1, row)]
    for k in range(1, row + 1):
        tracks[k].rest(0.0, at[k])
    tc = first.reach(X_HAT, float(at[0][0] - start[0]))
    _, vc, wc = first.state(tc)
    first.cut(tc)
    vel = [vc] + [np.zeros(2)] * row
    contacts = []
    for k in range(row):
        vel[k], vel[k + 1] = collide(vel[k], vel[k + 1], X_HAT, ph.e_ball)
        contacts.append((tc, [k, k + 1]))
    for k in range(1, row + 1):
        tracks[k].cut(tc)
    if seed:
        for k in range(row + 1):
            tracks[k].coast(ph, tc, at[k], vel[k], contact=True)
        return Answer(tracks, contacts)
    if ph.e_ball != 1.0:
        raise ValueError("the group push is derived for e_ball = 1 only")
    last = tracks[row]
    last.roll_out(ph, tc, at[row], vel[row], np.zeros(2), contact=True)
    # The others are still; the first ball's slip u = -R wy x_hat (top spin) drives it.
    u = slip(vel[0], wc)
    if not (u @ X_HAT < 0 and abs(u[1]) <= ROUNDING):
        raise ValueError("the group push needs top spin about the row's line")
    a = group_push(ph, row - 1)
    t1 = float(np.hypot(*u)) / (a + 2.5 * ph.mu_slide * ph.g)
    acc = a * X_HAT
    first.add("slide", tc, at[0], np.zeros(2), acc, wc,
              2.5 * ph.mu_slide * ph.g / R * _perp(-X_HAT), contact=True)
    for k in range(1, row):
        tracks[k].add("roll", tc, at[k], np.zeros(2), acc, np.zeros(2), rolling_spin(acc),
                      contact=True)
    for k in range(row):
        p, v1, _ = tracks[k].state(tc + t1)
        # Slip gone: the body rolls on, every ball slowing at mu_r g, so nothing pushes.
        tracks[k].roll_out(ph, tc + t1, p, v1, rolling_spin(v1))
    return Answer(tracks, contacts)
