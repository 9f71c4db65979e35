"""Headless play: the real app on a virtual screen, driven by a key script on a virtual clock.

`termpool play --headless --size 100x32 --keys FILE` feeds the script's keys at their times,
ticks the app at 60 frames per virtual second, lets whatever is still moving come to rest, and
returns the final screen as text (for bug reports, scripted tests and demos). Nothing waits on
the wall clock, so a 10 s script runs as fast as the physics allows and gives the same screen
every time.
"""

from __future__ import annotations

from collections.abc import Sequence

from termpool.ui.keys import Mouse
from termpool.ui.output import Screen

FPS = 60
SETTLE_S = 120.0  # after the last key, run at most this long for shots (and the CPU) to end


def screen_size(text: str) -> tuple[int, int]:
    """The columns and rows of a --size value such as "100x32" (ValueError naming --size)."""
    try:
        c, r = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise ValueError(f"--size: must look like 100x32, not '{text}'") from None
    if c < 1 or r < 1 or c > 1000 or r > 1000:
        raise ValueError(f"--size: {text} is out of range (1x1 to 1000x1000)")
    return c, r


def screen_text(chars) -> str:
    return "\n".join("".join(row).rstrip() for row in chars)


def play(app, events: Sequence[tuple[float, object]], cols: int, rows: int,
         frames_out: list | None = None) -> str:
    """Run `app` through `events` ((t, Key) in time order) on a cols x rows screen; the final
    screen as text. With `frames_out`, also collect the escape string of every frame drawn
    (what a terminal would have been sent)."""
    screen = Screen(cols, rows, app.depth) if frames_out is not None else None
    t, k = 0.0, 0
    frame = 1.0 / FPS
    last_key = events[-1][0] if events else 0.0
    cells = app.cells(cols, rows)  # the first frame: a layout exists before the first click
    if screen is not None:
        frames_out.append(screen.render(*cells))
    n = 0
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
            cells = app.cells(cols, rows)
            if screen is not None and screen.depth != app.depth:  # changed in the settings
                screen = Screen(cols, rows, app.depth)
            if screen is not None:
                frames_out.append(screen.render(*cells))
        if k >= len(events) and app.wake_in(t) is None:
            break
        if t > last_key + SETTLE_S:
            break
        wake = app.wake_in(t)
        if wake is not None and 0.0 < wake and t + wake < (n + 1) * frame:
            t += wake  # a wake the app asked for between frames (an inferred key release),
            continue  # as a terminal's loop honours it
        n += 1
        t = n * frame  # no drift from adding frame times
    return screen_text(cells[0])
