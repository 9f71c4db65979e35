"""The closed-form scenes of `termpool bench accuracy`: the classic shots whose answer the
model's equations give on paper (closed_form.py), each with the engine's tolerance on it.

Each `Case` is a scene (a scene dict, loaded like any other) with its answer under the
engine's model (`model`) and under the seed game's (`seed`), the figures the shot is known for
(`facts`, measured alike on the answer and on any run), and how far the engine may be off
(`tol_mm`, `tol_ms`) and why. The physics is chosen so that the answer is exact for the model:
a table without pockets, so big that no ball reaches a cushion; frictionless ball-ball contact
(no throw, no spin transfer) and, except in `draw_e95`, e_ball = 1 wherever balls meet.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from bench.closed_form import (
    Answer,
    Track,
    cradle,
    rolling_spin,
    shot,
)
from termpool.physics.params import BALL_RADIUS, Physics

R = BALL_RADIUS
TABLE = {"length": 50.0, "width": 30.0, "pockets": "none"}  # no ball reaches a cushion
Y = 15.0  # every scene runs along the table's middle
ELASTIC = {"e_ball": 1.0, "ball_ball": "frictionless"}
EXACT_MM = 1e-6  # 1 nm
EXACT_MS = 1e-6  # 1 ns
EXACT_WHY = ("exact inside every step: rounding, well under the engine's 1 nm contact "
             "tolerance (roots.TOUCH)")


@dataclass
class Fact:
    """A named figure of a scene, measured the same way on any run: `measure` takes the
    events (engine format), the start and the final positions."""

    label: str
    unit: str
    measure: Callable[[list[dict], np.ndarray, np.ndarray], float]


@dataclass
class Case:
    name: str
    description: str
    scene: dict
    model: Answer
    seed: Answer
    facts: list[Fact]
    tol_mm: float  # the engine's allowed error: positions
    tol_ms: float  # and event times
    tol_why: str


# ------------------------------------------------------------------------------ measuring


def event(evs: list[dict], kind: str, ids: list[int], n: int = 0) -> dict:
    """The n-th event of `kind` with exactly these ball ids."""
    hits = [ev for ev in evs if ev["type"] == kind and ev["i"] == ids]
    if len(hits) <= n:
        raise LookupError(f"no {kind} event {n} of balls {ids}")
    return hits[n]


def _after(evs: list[dict], kind: str, ball: int) -> dict:
    """The ball's first `kind` event after its first contact."""
    t = next(ev["t"] for ev in evs if ev["type"] == "ball_ball" and ball in ev["i"])
    return next(ev for ev in evs if ev["type"] == kind and ev["i"] == [ball] and ev["t"] > t)


def _speed(ev: dict, k: int = 0) -> float:
    b = ev["balls"][k]
    return math.hypot(b["vx"], b["vy"])


def _heading(ev: dict, k: int = 0) -> float:
    """Direction of travel in degrees from +x (positive towards +y)."""
    b = ev["balls"][k]
    return math.degrees(math.atan2(b["vy"], b["vx"]))


# ------------------------------------------------------------------------------ scenes


def _ball(x: float, v=(0.0, 0.0), w=(0.0, 0.0), bid: str | None = None, y: float = Y) -> dict:
    d = {"x": x, "y": y, "vx": float(v[0]), "vy": float(v[1]),
         "w": [float(w[0]), float(w[1]), 0.0]}
    if bid is not None:
        d["id"] = bid
    return d


def _scene(description: str, physics: dict, balls: list[dict]) -> dict:
    return {"description": description, "table": dict(TABLE), "physics": dict(physics),
            "balls": balls}


def _natural(v0: float) -> np.ndarray:
    return rolling_spin(np.array([v0, 0.0]))


def slide_roll(v0: float = 1.0) -> Case:
    ph, x0 = Physics(), 1.0
    desc = (f"Centre-struck ball at {v0:g} m/s: slides 12 v^2/(49 mu_s g) in 2 v/(7 mu_s g), "
            "rolls on at 5/7 v to a stop")
    model, seed = Track(), Track()
    model.roll_out(ph, 0.0, (x0, Y), (v0, 0.0), (0.0, 0.0))
    seed.coast(ph, 0.0, (x0, Y), (v0, 0.0))

    def slide_end(evs: list[dict]) -> dict:
        return event(evs, "slide_to_roll", [0])

    facts = [
        Fact("slide distance", "m", lambda evs, s, f: slide_end(evs)["balls"][0]["x"] - s[0, 0]),
        Fact("slide time", "s", lambda evs, s, f: slide_end(evs)["t"]),
        Fact("rolling speed / v", "", lambda evs, s, f: _speed(slide_end(evs)) / v0),
        Fact("stop distance", "m", lambda evs, s, f: f[0, 0] - s[0, 0]),
        Fact("stop time", "s", lambda evs, s, f: event(evs, "roll_to_stop", [0])["t"]),
    ]
    return Case("slide_roll", desc, _scene(desc, {}, [_ball(x0, (v0, 0.0), bid="cue")]),
                Answer([model], []), Answer([seed], []), facts, EXACT_MM, EXACT_MS, EXACT_WHY)


def roll_stop(v0: float = 1.0) -> Case:
    ph, x0, w = Physics(), 1.0, _natural(v0)
    desc = (f"Natural roll at {v0:g} m/s: stops after v^2/(2 mu_r g) in v/(mu_r g) (the seed "
            "model's law too)")
    model, seed = Track(), Track()
    model.roll_out(ph, 0.0, (x0, Y), (v0, 0.0), w)
    seed.coast(ph, 0.0, (x0, Y), (v0, 0.0))
    facts = [
        Fact("stop distance", "m", lambda evs, s, f: f[0, 0] - s[0, 0]),
        Fact("stop time", "s", lambda evs, s, f: event(evs, "roll_to_stop", [0])["t"]),
    ]
    return Case("roll_stop", desc, _scene(desc, {}, [_ball(x0, (v0, 0.0), w, bid="cue")]),
                Answer([model], []), Answer([seed], []), facts, EXACT_MM, EXACT_MS, EXACT_WHY)


def stun_spin(ph: Physics, v0: float, gap: float) -> float:
    """The back spin wy that sliding friction wears off exactly as the ball, sliding from
    speed v0 along +x, has covered `gap`: R wy grows at 2.5 mu_s g while the ball slows at
    mu_s g, reaching gap at t = 2 gap / (v0 + sqrt(v0^2 - 2 mu_s g gap))."""
    k = ph.mu_slide * ph.g
    t = 2.0 * gap / (v0 + math.sqrt(v0 * v0 - 2.0 * k * gap))
    return -2.5 * k * t / R


def _two_ball(name: str, desc: str, physics: dict, v0: float, w, gap: float, cut_deg: float,
              facts: list[Fact]) -> Case:
    """A ball along +x meeting a still one at a cut angle after `gap` of travel."""
    ph = Physics.from_dict(physics)
    c = math.radians(cut_deg)
    n = np.array([math.cos(c), math.sin(c)])
    target = np.array([3.0, Y])
    meet = target - 2 * R * n
    start = (float(meet[0]) - gap, float(meet[1]))
    scene = _scene(desc, physics, [_ball(start[0], (v0, 0.0), w, bid="cue", y=start[1]),
                                   _ball(float(target[0]), bid="1")])
    return Case(name, desc, scene, shot(ph, start, (v0, 0.0), w, target, n, seed=False),
                shot(ph, start, (v0, 0.0), w, target, n, seed=True), facts, EXACT_MM,
                EXACT_MS, EXACT_WHY)


def stun(v0: float = 2.0, gap: float = 0.5) -> Case:
    wy = stun_spin(Physics.from_dict(ELASTIC), v0, gap)
    facts = [
        Fact("cue ball's travel after contact", "m",
             lambda evs, s, f: f[0, 0] - event(evs, "ball_ball", [0, 1])["balls"][0]["x"]),
        Fact("object ball's speed after contact", "m/s",
             lambda evs, s, f: _speed(event(evs, "ball_ball", [0, 1]), 1)),
        Fact("object ball's stop distance", "m", lambda evs, s, f: f[1, 0] - s[1, 0]),
    ]
    return _two_ball(
        "stun", f"Stun shot at {v0:g} m/s, straight, e = 1: back spin worn off exactly at "
        "contact, so the cue ball stops dead", ELASTIC, v0, (0.0, wy), gap, 0.0, facts)


def thirty(v0: float = 1.5, gap: float = 0.3, cut_deg: float = 30.0) -> Case:
    facts = [
        Fact("cue ball's final deflection", "deg",
             lambda evs, s, f: -_heading(_after(evs, "slide_to_roll", 0))),
        Fact("object ball's direction", "deg",
             lambda evs, s, f: _heading(event(evs, "ball_ball", [0, 1]), 1)),
    ]
    return _two_ball(
        "thirty", f"The 30 deg rule: natural roll at {v0:g} m/s, cut {cut_deg:g} deg (a "
        "half-ball hit at 30), frictionless e = 1: the cue ball ends atan(sin c cos c / "
        "(sin^2 c + 2/5)) off its line", ELASTIC, v0, _natural(v0), gap, cut_deg, facts)


def ninety(v0: float = 2.0, gap: float = 0.5, cut_deg: float = 30.0) -> Case:
    wy = stun_spin(Physics.from_dict(ELASTIC), v0, gap)

    def split(evs: list[dict], s: np.ndarray, f: np.ndarray) -> float:
        hit = event(evs, "ball_ball", [0, 1])
        return _heading(hit, 1) - _heading(hit, 0)

    facts = [
        Fact("angle between the paths after contact", "deg", split),
        Fact("cue ball's final direction", "deg",
             lambda evs, s, f: _heading(_after(evs, "slide_to_roll", 0))),
    ]
    return _two_ball(
        "ninety", f"The 90 deg rule: stun shot at {v0:g} m/s (no spin at contact), cut "
        f"{cut_deg:g} deg, frictionless e = 1: the balls part at a right angle and the cue "
        "ball keeps to the tangent line", ELASTIC, v0, (0.0, wy), gap, cut_deg, facts)


def _spin_facts() -> list[Fact]:
    def ratio(evs: list[dict], s: np.ndarray, f: np.ndarray) -> float:
        rw = R * event(evs, "ball_ball", [0, 1])["balls"][0]["w"][1]
        return _after(evs, "slide_to_roll", 0)["balls"][0]["vx"] / rw

    return [
        Fact("final speed / R w at contact", "", ratio),
        Fact("cue ball's travel after contact", "m",
             lambda evs, s, f: f[0, 0] - event(evs, "ball_ball", [0, 1])["balls"][0]["x"]),
    ]


def follow(v0: float = 1.5, gap: float = 0.3) -> Case:
    return _two_ball(
        "follow", f"Follow: natural roll at {v0:g} m/s, straight, frictionless e = 1: the cue "
        "ball stops, then its top spin carries it on at 2/7 of R w", ELASTIC, v0, _natural(v0),
        gap, 0.0, _spin_facts())


def draw(v0: float = 2.0, top: float = -0.4, gap: float = 0.3, e: float = 1.0) -> Case:
    w = (0.0, 2.5 * v0 * top / R)  # the cue strike's spin (physics/cue.py)
    name = "draw" if e == 1.0 else f"draw_e{round(100 * e)}"
    rule = ("stops, then its back spin draws it back at 2/7 of R w" if e == 1.0 else
            "keeps (1 - e)/2 of its speed v, then draws back at 2/7 R w + 5/7 (1 - e)/2 v")
    return _two_ball(
        name, f"Draw: {v0:g} m/s with back spin (tip {top:g} R), straight, frictionless "
        f"e = {e:g}: the cue ball {rule}", {**ELASTIC, "e_ball": e}, v0, w, gap, 0.0,
        _spin_facts())


def _cradle(name: str, desc: str, v0: float, w) -> Case:
    ph = Physics.from_dict(ELASTIC)
    start, row_x, row = (0.8, Y), 1.2, 5
    balls = [_ball(start[0], (v0, 0.0), w, bid="cue")]
    balls += [_ball(row_x + 2 * R * k, bid=str(k + 1)) for k in range(row)]
    model = cradle(ph, start, (v0, 0.0), w, row_x, row, seed=False)
    seed = cradle(ph, start, (v0, 0.0), w, row_x, row, seed=True)
    facts = [
        Fact("pushed balls' travel", "mm", lambda evs, s, f: 1e3 * (f[1, 0] - s[1, 0])),
        Fact("pushed balls stop at", "s", lambda evs, s, f: event(evs, "roll_to_stop", [1])["t"]),
        Fact("cue ball's slip ends at", "s",
             lambda evs, s, f: _after(evs, "slide_to_roll", 0)["t"]),
        Fact("last ball's travel", "m", lambda evs, s, f: f[row, 0] - s[row, 0]),
    ]
    return Case(name, desc, _scene(desc, ELASTIC, balls), model, seed, facts,
                EXACT_MM, EXACT_MS, EXACT_WHY)


def cradles() -> list[Case]:
    return [
        _cradle("cradle", "Newton's cradle: centre-struck at 3 m/s into five touching balls, "
                "frictionless e = 1: the last ball leaves, then the cue ball's top spin pushes "
                "the other four as one body", 3.0, (0.0, 0.0)),
        _cradle("cradle_roll", "The same cradle with the cue ball in natural roll at 3 m/s: "
                "more top spin, a longer push", 3.0, _natural(3.0)),
    ]


def cases() -> list[Case]:
    """Every closed-form case, in the report's order (the names are NAMES)."""
    return [slide_roll(), roll_stop(), stun(), thirty(), ninety(), follow(), draw(),
            draw(e=0.95), *cradles()]


NAMES = ("slide_roll", "roll_stop", "stun", "thirty", "ninety", "follow", "draw", "draw_e95",
         "cradle", "cradle_roll")
