"""Choosing a shot: every candidate simulated in one batch and scored, the best few checked
under the level's errors; and how a level strikes what it chose."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from termpool.physics.cue import clamp_tip
from termpool.physics.params import Physics
from termpool.physics.table import Table
from termpool.rules.codes import Aim, Choice, Option, PlanNote
from termpool.rules.common import State, legal_targets

from . import geometry as geo
from .balls import OnTable, read_inputs
from .candidates import (
    BREAK_SAMPLES,
    BREAK_SPEEDS,
    BREAK_SPINS,
    Cands,
    break_cands,
    calibrate,
    combo_cands,
    pot_cands,
    safety_cands,
    simulate,
)
from .levels import LEVELS, Level
from .scoring import PASS, score_tables

MIN_CANDIDATES = 8
OPTION_ANSWERS = {Option.RERACK_OR_ACCEPT: Choice.ACCEPT, Option.SHOOT_OR_PASS: Choice.SHOOT}


class Plan(NamedTuple):
    """A shot to play: cue.strike's speed (m/s), angle (degrees), side and top (units of R)."""

    speed: float
    angle: float
    side: float
    top: float
    called: tuple[str, str] | None  # (ball, pocket name) when the rules need a call (the 8)
    score: float
    note: PlanNote  # why, as data for words.plan_note ("the 3 in the top-right corner pocket")
    kind: str = ""  # "break", "pot", "combo", "safety", "kick" ("": none of them)
    ball: str | None = None  # pots and combinations: the ball meant to drop ...
    pocket: str | None = None  # ... and the pocket it is sent to
    sees: str = ""  # what the batch saw the shot do: "win", "loss", "foul" (its note is then
    # the referee's verdict), "pot" (a pot that keeps the table) or "pass" ("": no batch)
    target: str | None = None  # the ball the cue ball is sent at first (None: the break, or
    # no ball on the table): the one ball its note and the screen's "aiming at" both name


class _Eval(NamedTuple):
    t: OnTable
    targets: list[str]
    pockets: geo.Pockets
    lv: Level
    cands: Cands
    scores: np.ndarray
    calls: list
    notes: list
    flukes: list


def _evaluate(table, physics, ids, pos, radius, mass, on_table, state, level,
              max_candidates) -> _Eval:
    if isinstance(max_candidates, bool) or not isinstance(max_candidates, (int, np.integer)) \
            or max_candidates < MIN_CANDIDATES:
        raise ValueError(f"max_candidates: must be an integer of at least {MIN_CANDIDATES}")
    t = read_inputs(table, physics, ids, pos, radius, mass, on_table, state, level, 0)
    lv = LEVELS[level]
    budget = max(int(max_candidates * lv.share), MIN_CANDIDATES)
    targets = legal_targets(state, t.ids)
    pockets = geo.pocket_geometry(table, float(t.radius[t.cue]))
    if state.is_break:
        cands = break_cands(t, targets, lv)
    else:
        reserve = min(budget // 3, 24 * max(len(targets), 1))
        cands = pot_cands(t, targets, pockets, table, physics, lv,
                           budget - reserve - lv.combos)
        cands.extend(combo_cands(t, targets, state.mode, pockets, physics, lv,
                                  min(lv.combos, budget - reserve - len(cands))))
        calibrate(t, cands, table, physics)
        # With a likely pot on the table the fallbacks get only their reserve; without one
        # they may fill the budget (a snooker needs many kicks).
        likely = any(c > 0.3 for c in cands.chance)
        cands.extend(safety_cands(t, targets, table, physics,
                                   reserve if likely else budget - len(cands)))
    if len(cands) == 0:
        return _Eval(t, targets, pockets, lv, cands, np.zeros(0), [], [], [])
    eng = simulate(t, cands, table, physics)
    scores, calls, notes, flukes = score_tables(state, targets, t, cands, eng, table, pockets,
                                                lv)
    return _Eval(t, targets, pockets, lv, cands, scores, calls, notes, flukes)


def _plan(ev: _Eval, b: int, score: float) -> Plan:
    c = ev.cands
    kind, ball, pocket = c.kind[b], None, None
    if kind in ("pot", "combo"):
        ball = ev.t.ids[c.via[b] if c.via[b] >= 0 else c.target[b]]
        pocket = ev.pockets.names[c.pocket[b]]
    if ev.flukes[b] is not None:  # played for the ball the batch saw drop: a pot, not a safety
        ball, pocket = ev.flukes[b]
        kind = "pot" if kind in ("safety", "kick") else kind
    target = ev.t.ids[c.target[b]] if c.target[b] >= 0 else None
    return Plan(c.speed[b], (c.angle[b] + 180.0) % 360.0 - 180.0, c.side[b], c.top[b],
                ev.calls[b], float(score), ev.notes[b][0], kind, ball, pocket,
                ev.notes[b][1], target)


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

    The best `verify` by the batch's score, and the best `verify // 2` safeties and kicks
    besides (pots found by chance score above every safety in the batch and would crowd them
    out), are each simulated again at VERIFY_POINTS, aim and speed off by sqrt(3) of the
    level's error, all in one batch, and scored as played: a pot aimed at counts in full
    where it goes in, a pot by chance (a kiss, a bank) at FLUKE as in the batch. The centre
    point is the batch's own table, which a pot by chance was picked for: counted in full, it
    alone was worth more than any safety. Returns (candidate, its expected score)."""
    c, lv = ev.cands, ev.lv
    order = [int(k) for k in np.argsort(-ev.scores, kind="stable")]
    top = order[:lv.verify]
    top += [k for k in order[lv.verify:] if c.kind[k] in ("safety", "kick")
            and ev.flukes[k] is None][:lv.verify // 2]
    sub = Cands()
    da, dv = math.sqrt(3.0) * lv.aim_sd, math.sqrt(3.0) * lv.speed_sd
    for k in top:
        for fa, fv, _ in VERIFY_POINTS:
            sub.add(c.speed[k] * (1 + fv * dv), c.angle[k] + fa * da, c.side[k], c.top[k],
                    c.target[k], c.pocket[k], c.kind[k], 1.0, c.via[k], c.aim[k])
    eng = simulate(ev.t, sub, table, physics)
    s, *_ = score_tables(state, ev.targets, ev.t, sub, eng, table, ev.pockets, lv,
                         sampled=True)
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
    read_inputs(table, physics, ids, pos, radius, mass, on_table, state, level, seed)
    ev = _evaluate(table, physics, ids, pos, radius, mass, on_table, state, level,
                   max_candidates)
    if len(ev.cands) == 0:  # nothing to aim at: roll the cue ball up the table
        return Plan(1.0, 0.0, 0.0, 0.0, None, PASS, PlanNote(Aim.NOTHING))
    if state.is_break:  # the break whose samples did best on average, as meant
        mean = ev.scores.reshape(-1, BREAK_SAMPLES).mean(axis=1)
        k = int(np.argmax(mean))
        speed, (side, top) = BREAK_SPEEDS[k // len(BREAK_SPINS)], BREAK_SPINS[k % len(BREAK_SPINS)]
        angle = (geo.deg(ev.t.pos[ev.cands.target[0]] - ev.t.pos[ev.t.cue]) + 180.0) % 360.0 \
            - 180.0
        return Plan(speed, angle, side, top, None, float(mean[k]), PlanNote(Aim.BREAK), "break")
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
