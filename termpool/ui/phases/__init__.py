"""The app's update: a state and an event (a key, a mouse event, a clock tick) in, the next
state out. Each phase has its module (menu, aim, place, shot, cpu, answer: its keys and, where
time moves it, its tick); the boxes over any phase have theirs (boxes); `turn` holds the steps
they share. The driver (ui.app) tells each event the screen it came from (`Seen`), for the
mouse and the help's pages.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from termpool.ui import aid
from termpool.ui.phases import aim, answer, boxes, cpu, lobby, menu, place, remote, shot
from termpool.ui.state import Help, Pause, Phase, Quit, Run, Seen, State, shooter_is_remote

KEYS: dict[Phase, Callable] = {Phase.MENU: menu.key, Phase.AIM: aim.key, Phase.PLACE: place.key,
                               Phase.RUN: shot.key, Phase.CPU: cpu.key,
                               Phase.OPTION: answer.nothing, Phase.OVER: answer.nothing,
                               Phase.LOBBY: answer.nothing, Phase.REMOTE: answer.nothing}
TICKS: dict[Phase, Callable] = {Phase.AIM: aim.tick, Phase.RUN: shot.tick, Phase.CPU: cpu.tick,
                                Phase.LOBBY: lobby.tick, Phase.REMOTE: remote.tick}
ONLINE_POLL_S = 0.25  # an online match looks for the other player leaving this often
POINTS: dict[Phase, Callable] = {Phase.AIM: aim.point, Phase.PLACE: place.point}


def key(s: State, key, t: float, seen: Seen | None = None) -> State:
    s = replace(s, now=t)
    if s.watch is not None:
        s.watch.key(key, t)
        return replace(s, watch=None) if s.watch.done else s  # back to the match's end
    action = s.keymap.action(key)
    if key.kind == "release" and action != "shoot":
        s.controls.aim.step(key, t)  # a release ends an aim hold: the next press is a tap
        s.controls.place.release(key.name)  # ... and a ball-in-hand hold
        if s.controls.swallow is not None and key.name == s.controls.swallow[0]:
            return replace(s, controls=replace(s.controls, swallow=None))
        return s
    if s.box is not None:
        return boxes.key(s, key, action, seen)
    if s.phase is Phase.LOBBY:  # its letters (Y, N: a challenge's answer) come first
        answered = lobby.key(s, key, action, t)
        if answered is not None:
            return answered
    if s.phase in (Phase.OPTION, Phase.OVER) and key.kind == "press":
        answered = answer.key(s, key)
        if answered is not None:
            return answered  # their letters (P: pass, N: new game) come before the rest
    press = key.kind == "press"
    if action == "help" and press:
        return replace(s, box=Help())
    if action == "quit" and press:
        return replace(s, done=True) if s.phase is Phase.MENU else replace(s, box=Quit())
    if action == "pause" and press and s.phase is not Phase.MENU:
        return replace(s, box=Pause())
    if action == "bell" and press:
        bell = not s.opts.bell
        return replace(s, opts=replace(s.opts, bell=bell),
                       message=(("bell on" if bell else "bell off", "note"),))
    return KEYS[s.phase](s, key, action, t)


def mouse(s: State, ev, t: float, seen: Seen | None) -> State:
    """A left press or drag on the table aims at that point (or, with ball in hand, moves
    the cue ball there); the arrows then refine. `seen` is the screen it was on: a table not
    drawn yet there takes no clicks."""
    s = replace(s, now=t)
    if (s.box is not None or s.match is None or s.watch is not None or seen is None
            or seen.layout is None or seen.table is not s.match.table
            or s.phase not in POINTS or ev.button != 0 or ev.kind not in ("press", "drag")):
        return s
    point = seen.layout.to_table(ev.col, ev.row)
    return s if point is None else POINTS[s.phase](s, *point)


def tick(s: State, t: float) -> State:
    s = replace(s, now=t)
    if s.watch is not None:
        s.watch.tick(t)
        return s
    s = aid.advance(s)  # the aid fills in
    if s.remote:
        s = remote.check(s)
        if s.remote and not shooter_is_remote(s):
            remote.share(s, t)
    if s.box is not None:  # paused or asking: a shot waits
        return shot.pause(s) if isinstance(s.part, Run) else s
    if s.phase is Phase.MENU and s.link is not None and not s.link.closed:
        return lobby.menu_tick(s, t)
    step = TICKS.get(s.phase)
    return s if step is None else step(s, t)


def wake_in(s: State, t: float) -> float | None:
    """Seconds until the app needs a tick (None: only on a key)."""
    if s.watch is not None:
        return s.watch.wake_in(t)
    if s.box is not None:
        return None
    if s.phase in (Phase.RUN, Phase.CPU) or aid.running(s):
        return 0.0
    if s.phase is Phase.LOBBY or s.phase is Phase.MENU and s.link is not None \
            and not s.link.closed:  # the menu: a match to be back in may come
        return lobby.LOBBY_POLL_S
    if s.phase is Phase.REMOTE:
        return remote.REMOTE_POLL_S
    online = ONLINE_POLL_S if s.remote else None
    charge = s.controls.charge
    if charge.active:  # the meter moves; it stops, and an inferred release is due, at times
        due = charge.release_due()
        if due is None:
            return 0.0
        hold = charge.hold_at()  # (drawn then, the meter shows the power that will strike)
        return max(0.0, (hold if hold is not None and t < hold else due) - t)
    return online


def moving(s: State) -> bool:
    """Whether the screen changes with the clock alone: a charge or meter running."""
    return s.phase is Phase.AIM and s.controls.charge.active

