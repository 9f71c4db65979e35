"""A player aims: the stick, the cue tip, the power (held, a meter or set with a digit), the
call for the 8, a push-out, the aid's level, and practice's take-back and re-rack."""

from __future__ import annotations

import math
from dataclasses import replace

from termpool.physics.cue import clamp_tip
from termpool.physics.table import POCKET_NAMES
from termpool.ui import aid
from termpool.ui.help import pretty
from termpool.ui.phases.turn import shoot_human, start_turn
from termpool.ui.predict import LEVELS
from termpool.ui.state import (
    Phase,
    Place,
    State,
    cue_index,
    in_the_way,
    next_ball_angle,
    say,
    targets,
    voice,
)

SPIN_STEP = 0.1  # tip offset per key, in units of R
SPIN_KEYS = {"spin_up": (0, 1), "spin_down": (0, -1), "spin_left": (-1, 0), "spin_right": (1, 0)}
AIM_KEYS = ("aim_ccw", "aim_cw", "aim_fine_ccw", "aim_fine_cw")
AID_WORDS = {"full": "aim aid: every path (G: ghost ball only)",
             "ghost": "aim aid: the ghost ball only (G: off)", "off": "aim aid off (G: on)"}


def power_digit(key) -> float | None:
    """The power a digit key sets (1-9: 10-90%, 0: 100%), or None for any other key."""
    if key.kind != "press" or key.digit is None:
        return None
    return (int(key.digit) or 10) / 10


def strike(s: State, level: float) -> State:
    """The player's shot at power `level`, with the 8's call when one is needed."""
    called = None
    if s.match.needs_call():
        s = aid.refresh(s)
        called = aid.called(s)
    return shoot_human(s, level, called)


def answered(s: State) -> State:
    """The notes that answered the keys before ("power: hold space again", "no other ball
    to aim at") gone, now that the aim or the charge has moved on; the verdicts stay."""
    if any(tone == "note" for _, tone in s.message):
        return replace(s, message=tuple(m for m in s.message if m[1] != "note"))
    return s


def key(s: State, key, action: str | None, t: float) -> State:
    swallow = s.controls.swallow
    if swallow is not None and key.name == swallow[0]:
        name, last, repeating = swallow
        # Auto-repeat starts up to 0.75 s after the press, then comes every 20-100 ms.
        if key.kind == "repeat" or (key.kind == "press"
                                    and t - last <= (0.15 if repeating else 0.75)):
            return replace(s, controls=replace(s.controls, swallow=(name, t, True)))
        s = replace(s, controls=replace(s.controls, swallow=None))
        if key.kind == "release":
            return s
    charge = s.controls.charge
    if action == "shoot":
        level = charge.key(key, t)
        if level is not None:
            return strike(s, level)
        return answered(s) if charge.active else s
    if key.kind == "release":
        return s
    m, st = s.match, s.stroke
    if action in AIM_KEYS:
        angle = (st.angle + s.controls.aim.step(key, t)) % 360.0
        # A pocket picked with C stays called as the aim moves (the aid warns of an 8
        # heading elsewhere); until then the call follows the aim.
        return replace(answered(s), stroke=replace(st, angle=angle))
    if action in ("next_ball", "previous_ball"):
        angle = next_ball_angle(s, action == "next_ball")
        if angle == st.angle:  # (9-ball: the one ball on, already aimed at)
            way = in_the_way(s)
            if way is None and len(targets(s)) > 1:  # the others are all behind balls
                return say(s, "no other ball you may hit has a clear path: the aim is at the "
                              "only one that has")
            if way is None:
                return say(s, "no other ball to aim at: the aim is at the only one you may hit")
            ids, v = s.match.ids, voice(s)
            return say(s, f"{v.ball(ids[way])} is in the way of {v.ball(ids[targets(s)[0]])}, "
                          "the only ball you may hit: a cushion first?")
        return replace(answered(s), stroke=replace(st, angle=angle))
    if action in SPIN_KEYS:
        dx, dy = SPIN_KEYS[action]
        # Rounded so that ten steps make 1.0, then kept on the ball: past the miscue limit
        # the tip slides along it.
        side, top = clamp_tip(round(st.side + dx * SPIN_STEP, 6), round(st.top + dy * SPIN_STEP, 6))
        return replace(s, stroke=replace(st, side=side, top=top))
    if action == "spin_reset":
        return replace(s, stroke=replace(st, side=0.0, top=0.0))
    if action == "cancel":
        if charge.active:
            charge.cancel()
        elif charge.preset_level is not None and s.opts.power != "digits":
            charge.preset(None)
            again = (f"hold {charge.key_label}" if charge.way == "hold" else
                     f"the meter ({charge.key_label} starts it)")
            return say(s, f"power: {again} again")
        return s
    if action is None and power_digit(key) is not None:
        charge.preset(power_digit(key))
        return s
    if action == "aim_aid":
        level = LEVELS[(LEVELS.index(s.opts.aid) - 1) % len(LEVELS)]
        return say(replace(s, opts=replace(s.opts, aid=level)), AID_WORDS[level])
    if action == "call_pocket":
        if m.needs_call():
            if st.call_picked:
                start = st.called_k
            else:
                s = aid.refresh(s)
                start = aid.aimed_pocket(s)
            return replace(s, stroke=replace(st, called_k=(start + 1) % len(POCKET_NAMES),
                                             call_picked=True))
        if m.state.mode == "8ball":
            return say(s, "no call needed: only the 8 is called, once your group is down")
        return say(s, "no calls in this game")
    if action == "push_out":
        if m.state.push_out == "available":
            return replace(s, stroke=replace(st, push_out=not st.push_out))
        return say(s, NO_PUSH_OUT)
    if action == "place":
        if m.ball_in_hand:
            x, y = m.pos[cue_index(s)]
            return replace(s, part=Place((float(x), float(y))))
        return say(s, "no ball in hand: the cue ball is played from where it lies")
    return practice(s, action)


NO_PUSH_OUT = "a push-out is only for the shot right after a 9-ball break"


def practice(s: State, action: str | None) -> State:
    """Practice's take-back and re-rack (elsewhere, a word on why they do nothing)."""
    m = s.match
    if action in ("undo", "rerack") and m.state.mode != "practice":
        return say(s, "take back and re-rack are for practice")
    if action == "undo":
        shot = m.history[-1]["shot"] if m.history else None
        try:
            undid = m.take_back()
        except ValueError:
            return start_turn(say(s, "nothing to take back"))
        if undid == "rerack":
            return start_turn(say(s, "the re-rack taken back: the balls as they were"))
        s = start_turn(say(s, "took the last shot back"))
        if shot is None:
            return s
        # The stick as it was for that shot (aim and tip), to play it again or nudge it;
        # from ball in hand, once the ball goes down where it was.
        again = (shot["angle"] % 360.0, shot["side"], shot["top"])
        if s.phase is Phase.PLACE:
            return replace(s, part=replace(s.part, again=again))
        return take_stroke(s, again) if s.phase is Phase.AIM else s
    if action == "rerack":
        m.rerack()
        undo = s.keymap.keys_for("undo")
        return start_turn(say(s, f"re-racked ({pretty(undo[0])} puts the balls back)" if undo
                              else "re-racked"))
    return s


def take_stroke(s: State, stroke: tuple[float, float, float]) -> State:
    """Aim with the stick at (angle, side, top)."""
    angle, side, top = stroke
    return replace(s, stroke=replace(s.stroke, angle=angle, side=side, top=top))


def tick(s: State, t: float) -> State:
    """A charge running: the meter moves, and a release inferred (or the meter's end) may
    strike."""
    charge = s.controls.charge
    if charge.active:
        level = charge.poll(t)
        if level is not None:
            return strike(s, level)
    return s


def point(s: State, x: float, y: float) -> State:
    """Aim at the point (x, y) of the table (the mouse)."""
    cx, cy = s.match.pos[cue_index(s)]
    if math.hypot(x - cx, y - cy) < 1e-9:
        return s
    angle = math.degrees(math.atan2(y - cy, x - cx)) % 360.0
    return replace(s, stroke=replace(s.stroke, angle=angle))
