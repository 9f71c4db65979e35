"""The computer's turn: it shows that it is thinking, decides (an option's answer, where to
put the ball in hand, its shot), turns its stick onto its aim, holds it there with its plan
in words, then shoots. Any key makes it shoot at once."""

from __future__ import annotations

from dataclasses import replace

from termpool.ai import Plan
from termpool.rules import words
from termpool.rules.codes import Choice
from termpool.ui.phases.turn import shoot, start_turn
from termpool.ui.state import Aiming, Answering, State, Thinking

CPU_AIM_S = 0.6  # the computer turns its stick onto its aim over this long ...
CPU_SHOW_S = 1.2  # ... then holds it there, its aid and plan on show, this long before it
# shoots (a key shoots at once)
CPU_THINK_FRAME_S = 0.05  # show "thinking" for at least this long before blocking on the plan


def key(s: State, key, action: str | None, t: float) -> State:
    if key.kind == "press" and isinstance(s.part, Thinking | Aiming):
        s = replace(s, part=replace(s.part, skip=True))  # no more waiting for its shot
    if action == "shoot":
        s.controls.charge.observe(key, t)  # a key still held after the strike: its repeats
    return s


def tick(s: State, t: float) -> State:
    part = s.part
    if isinstance(part, Thinking):
        if part.since is None:  # draw "thinking" first, then block on the plan
            return replace(s, part=replace(part, since=t))
        if t - part.since < CPU_THINK_FRAME_S:
            return s
        s, decision = plan(s)
        if isinstance(decision, Choice):
            return replace(s, part=Answering(decision))
        # Its turn is timed from the first frame that shows the plan: `t` is from before
        # the plan, which takes a second of its own.
        return replace(s, part=Aiming(decision, s.stroke.angle, skip=part.skip))
    if isinstance(part, Answering):
        m = s.match
        line = (words.chose(m.players[m.shooter], part.choice), "turn")
        m.choose(part.choice)
        return start_turn(replace(s, message=(line,)))
    since = t if part.since is None else part.since
    elapsed = t - since
    f = 1.0 if part.skip else min(1.0, elapsed / CPU_AIM_S)
    p = part.plan
    turn = (p.angle - part.start + 180.0) % 360.0 - 180.0
    angle = p.angle if f >= 1.0 else (part.start + f * turn) % 360.0
    s = replace(s, part=replace(part, since=since),
                stroke=replace(s.stroke, angle=angle, side=p.side * f, top=p.top * f))
    if part.skip or elapsed >= CPU_AIM_S + CPU_SHOW_S:
        return shoot(s, p.speed, p.angle, p.side, p.top, p.called, keep_message=True)
    return s


def plan(s: State) -> tuple[State, Plan | Choice]:
    """The computer's decision (game.players.Computer): an option's answer, or a placement
    and then a shot (with its plan in words for the panel)."""
    m = s.match
    player = m.seats[m.shooter]
    if m.option is not None:
        return s, player.answer(m)
    if m.ball_in_hand:
        m.place_cue(*player.place(m))
    decision = player.shot(m)
    foresees = decision.sees in ("win", "loss", "foul")
    # A plan ("the 3 in the top-right corner pocket"), not the result it simulated.
    s = replace(s, cpu_plan=None if foresees else decision.note)
    # The verdict on the shot just played stays in view (the player's, or its own last one),
    # or, after an option, the answer given; not the plan of the shot it was about.
    last = tuple(x for x in s.message if x not in s.shot_note)[:2]
    return replace(s, message=last + s.cpu_note), decision
