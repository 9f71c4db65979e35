"""Ball in hand: the arrows (and the mouse) move the cue ball, Enter puts it down."""

from __future__ import annotations

from dataclasses import replace

from termpool.game.layout import head_string
from termpool.ui.phases.aim import NO_PUSH_OUT, practice, take_stroke
from termpool.ui.phases.turn import own_move, tell
from termpool.ui.state import (
    Aim,
    Place,
    State,
    cue_index,
    lies_playable,
    nearest_angle,
    say,
    voice,
)

PLACE_TAP, PLACE_FINE = 0.01, 0.002  # m a tap moves the ball in hand (shift: fine)
ARROWS = {"left": (-1, 0), "right": (1, 0), "up": (0, 1), "down": (0, -1)}


def clamp(s: State, x: float, y: float) -> tuple[float, float]:
    """Keep the ball in hand on the cloth (and behind the head string when it must be)."""
    m = s.match
    r = float(m.radius[cue_index(s)])
    L, W = m.table.length, m.table.width
    right = head_string(m.table) if m.ball_in_hand == "kitchen" else L - r
    return min(right, max(r, x)), min(W - r, max(r, y))


def key(s: State, key, action: str | None, t: float) -> State:
    x, y = s.part.cursor
    if action == "cancel" and key.kind == "press":
        # Changed one's mind: the ball stays where it lies, as if put down there.
        here = lies_playable(s)
        if here is None:
            return say(s, "the cue ball is in hand: move it with the arrows, put it down "
                          "with Enter")
        return put_down(s, *here, key.name, t, held=False)
    if key.name in ARROWS and key.kind != "release":
        # 1 cm a tap; held, from 0.25 to 1 m/s over a second from the press; Shift: 2 mm.
        step = PLACE_FINE if key.shift else s.controls.place.step(key.name, key.kind, t)
        dx, dy = ARROWS[key.name]
        return replace(s, part=Place(clamp(s, x + dx * step, y + dy * step)))
    if action in ("confirm", "place", "shoot") and key.kind == "press":
        return put_down(s, x, y, key.name, t, held=action == "shoot")
    if key.kind != "press":
        return s
    if action == "push_out":
        return say(s, "put the cue ball down first (Enter), then push out"
                   if s.match.state.push_out == "available" else NO_PUSH_OUT)
    return practice(s, action)


def put_down(s: State, x: float, y: float, name: str, t: float, held: bool) -> State:
    """Put the ball in hand down at (x, y) and aim (or say why it may not go there). held:
    the key that did it is the shot's, whose repeats must not start a shot."""
    why = s.match.placement_error(x, y, voice(s))
    if why:
        return replace(s, message=((f"Can't place the cue ball there: {why}", "foul"),))
    at = own_move(s)
    s.match.place_cue(x, y)
    tell(s, at, kind="place", x=float(x), y=float(y))
    # Held, the key that put the ball down keeps coming (repeats; on terminals without
    # releases, as presses): none of it may start a shot.
    swallow = (name, t, False) if held else None
    again = s.part.again if isinstance(s.part, Place) and s.part.cursor == (x, y) else None
    s = replace(s, message=(), part=Aim(), controls=replace(s.controls, swallow=swallow))
    if again is not None:
        return take_stroke(s, again)
    return replace(s, stroke=replace(s.stroke, angle=nearest_angle(s)))


def point(s: State, x: float, y: float) -> State:
    """Put the ball in hand at the point (x, y) of the table (the mouse), or as near as it
    may go."""
    return replace(s, part=Place(clamp(s, x, y)))
