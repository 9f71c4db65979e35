"""Key scripts played through the game on a virtual clock, and what the screen did: the
regression snapshot of the game's screens (tests/test_ui_screens.py, tests/make_screens.py).

Each scenario is a game (`Options`) and a key script. `play` runs it the way `ui.headless`
does (keys at their times, a tick every 1/60 s, a frame drawn whenever the app says its
screen changed) and logs each drawn frame that differs from the last: the virtual time and a
digest of every cell (characters, and the colours where there are any). It logs the bells
rung the same way, and at the end a digest of the match (its shots, and where the balls
are). Only the driver's side of the app is used (`key`, `mouse`, `tick`, `cells`,
`dirty`, `done`, `bells`, `wake_in`, and `record()` for the match), so the same scenarios run
on any version of the app.
"""

from __future__ import annotations

import hashlib
import json

from termpool.ui.app import App, Options
from termpool.ui.keys import Mouse, legacy_events, parse_script

FPS = 60
SETTLE_S = 120.0  # as ui.headless: after the last key, shots (and the computer) may finish
NO_HISTORY = {"XDG_DATA_HOME": "/nonexistent/termpool-screens"}  # Stats: no history file
SIZES = ((80, 24), (120, 40))
DEPTHS = ("truecolor", "mono")

# name: (options, input mode, key script). The seeds pick racks that reach the boxes named.
SCENARIOS: dict[str, tuple[dict, str, str]] = {
    # The menu: moving, the help's pages, Settings (a change of colours too), Stats, quit.
    "menu": ({}, "release",
             "down down up h right right left esc 6 down right left down*2 right down right "
             "down*2 right esc 7 down esc 8 right esc down*4 up q"),
    # 8-ball against the computer: the stick, the spin, the aid's levels, digits and Esc,
    # the break, the computer's turns (thinking, aiming, its shots), help and pause boxes.
    "eight_cpu": ({"mode": "8ball", "opponent": "cpu", "seed": 2}, "release",
                  "enter left*2 right w w a d x g g g c 4 esc space-hold 1.3 wait 25 "
                  "p x h right esc shift+left*3 down up*2 s s space-hold 0.7 wait 9 q n "
                  "wait 1 q y"),
    # 9-ball, two players: a push-out, the answer box (pass), calls and practice-only keys.
    "nine_push": ({"mode": "9ball", "opponent": "human", "seed": 0}, "release",
                  "enter space-hold 1.3 wait 12 o o o c u n space-hold 0.3 wait 12 x p "
                  "wait 1 left*5 space-hold 0.9 f wait 12"),
    # 9-ball, the 9 on the break: game over, watching it (pause, steps, help), a new game.
    "nine_over": ({"mode": "9ball", "opponent": "human", "seed": 1}, "release",
                  "enter space-hold 1.3 wait 12 x w wait 1.5 space wait 0.5 space wait 2 "
                  "h right esc left wait 1 right f wait 3 q n b wait 0.5 q m"),
    # A race to two frames: the 9 on the break wins the first frame, not the match.
    "nine_frames": ({"mode": "9ball", "opponent": "human", "seed": 1, "frames": 2}, "release",
                    "enter space-hold 1.3 wait 12 enter space-hold 1.3 wait 12"),
    # Practice: ball in hand by arrows, Shift and the mouse, a refused place, fast forward,
    # take back, re-rack, aiming with the mouse.
    "practice": ({"mode": "practice", "seed": 4}, "release",
                 "left-hold 0.6 up*3 shift+down*2 click 20 8 click 60 11 click 30 12 enter "
                 "click 70 6 space-hold 1.0 f wait 10 u r b right*5 enter g space-hold 0.5 "
                 "wait 10 u wait 0.5 enter r wait 0.5 q n"),
    # An illegal 8-ball break: the other player re-racks, then accepts after a second one.
    "eight_option": ({"mode": "8ball", "opponent": "human", "seed": 5}, "release",
                     "enter space-hold 0.15 wait 12 x r wait 0.5 enter space-hold 0.15 "
                     "wait 12 a wait 1"),
    # The computer answers an illegal break.
    "cpu_option": ({"mode": "8ball", "opponent": "cpu", "seed": 5}, "release",
                   "enter space-hold 0.15 wait 4.8 q y"),
    # The computer answers a push-out, then plays on with the verdict and its answer in view.
    "cpu_push": ({"mode": "9ball", "opponent": "cpu", "seed": 5}, "release",
                 "enter space-hold 1.3 wait 10 o space-hold 0.2 wait 9 q y"),
    # Terminals without key releases: a hold inferred from repeats, a tap that falls back to
    # the meter; the classic meter.
    "legacy": ({"mode": "practice", "seed": 6}, "repeat",
               "enter space-hold 0.8 wait 12 space wait 1.0 space wait 12"),
    "classic": ({"mode": "8ball", "opponent": "human", "seed": 6, "power": "meter"}, "classic",
                "enter space wait 0.7 space wait 12 space esc space wait 1.5 space wait 12"),
    # Settings that shape play: digits, fast-forward always, the bell, names, no aid.
    "settings": ({"mode": "8ball", "opponent": "human", "seed": 7, "power": "digits",
                  "fast": "always", "bell": True, "player1": "Ann", "player2": "Bob",
                  "aid": "off", "frames": 3, "theme": "classic"}, "release",
                 "enter space wait 5 enter 7 space wait 6 p s down right esc esc wait 0.5 "
                 "9 space wait 6"),
}


CHUNK = 20  # log entries per digest in the stored snapshot


def digest(cells) -> str:
    """A digest of every cell: the characters, and the colours where there are any."""
    h = hashlib.sha256()
    for a in cells:
        h.update(b"-" if a is None else a.tobytes())
    return h.hexdigest()[:20]


def events_of(script: str, input_mode: str) -> list:
    events = parse_script(script)
    return events if input_mode == "release" else legacy_events(events)


def new_app(options: dict, input_mode: str, colors: str) -> App:
    return App(Options(colors=colors, **options), input_mode=input_mode, env=NO_HISTORY)


def play(app, events, cols: int, rows: int, frames: list | None = None) -> list:
    """Run the scenario; the log: ["screen", t, digest] for each drawn frame that differs
    from the last, ["bell", t, n] for bells rung, and at the end ["match", digest] of each
    match played (its record). With `frames`, the cells of each logged frame go there."""
    log: list = []
    last = None
    t, k, n = 0.0, 0, 0
    frame = 1.0 / FPS
    last_key = events[-1][0] if events else 0.0

    def draw() -> None:
        nonlocal last
        cells = app.cells(cols, rows)
        d = digest(cells)
        if d != last:
            log.append(["screen", round(t, 9), d])
            if frames is not None:
                frames.append((round(t, 9), [None if a is None else a.copy() for a in cells]))
            last = d
        if app.bells:
            log.append(["bell", round(t, 9), app.bells])
            app.bells = 0

    draw()
    while not app.done:
        while k < len(events) and events[k][0] <= t + 1e-12:
            ev = events[k][1]
            if isinstance(ev, Mouse):
                app.mouse(ev, events[k][0])
            else:
                app.key(ev, events[k][0])
            k += 1
        app.tick(t)
        if app.dirty:
            draw()
        if k >= len(events) and app.wake_in(t) is None:
            break
        if t > last_key + SETTLE_S:
            break
        wake = app.wake_in(t)
        if wake is not None and 0.0 < wake and t + wake < (n + 1) * frame:
            t += wake
            continue
        n += 1
        t = n * frame
    m = app.record()
    if m is not None and m.history:
        data = m.to_json()
        played = {"shots": [rec["shot"] for rec in data["shots"]],
                  "balls": data["current"]["balls"]}
        text = json.dumps(played, sort_keys=True)
        log.append(["match", hashlib.sha256(text.encode()).hexdigest()[:20]])
    return log


def run(name: str, cols: int, rows: int, colors: str, frames: list | None = None) -> list:
    options, input_mode, script = SCENARIOS[name]
    app = new_app(options, input_mode, colors)
    return play(app, events_of(script, input_mode), cols, rows, frames)


def chunks(log: list) -> list:
    """The log as stored: [time of its first entry, digest] for each CHUNK entries."""
    out = []
    for k in range(0, len(log), CHUNK):
        part = log[k:k + CHUNK]
        text = json.dumps(part)
        out.append([part[0][1], hashlib.sha256(text.encode()).hexdigest()[:16]])
    return out
