"""The game as its driver sees it: keys, mouse events and clock ticks in, screen cells out.

`App` holds the game's state (ui.state), hands each event to the update (ui.phases) and
draws the state with the view (ui.view). It never touches a terminal, so the same code runs
on a real terminal (``ui.term``), on a virtual screen from a key script (``ui.headless``)
and in tests. `dirty` says the screen may have changed since it was last drawn.
"""

from __future__ import annotations

from dataclasses import fields, replace

from termpool.game import Match
from termpool.ui import aid, phases
from termpool.ui.controls import AimControl, HoldRamp, KeyMap
from termpool.ui.output import resolve_depth
from termpool.ui.phases import turn
from termpool.ui.phases.place import PLACE_TAP
from termpool.ui.state import Controls, Files, Options, Seen, State
from termpool.ui.table_view import Geometry
from termpool.ui.view import draw

__all__ = ["App", "Options", "start"]


def start(opts: Options | None = None, keymap: KeyMap | None = None,
          input_mode: str = "release", env=None, files: Files | None = None,
          link=None) -> State:
    """The state a session starts in: the menu, or (with `opts.mode`) a match. `link`: the
    line to the lobby of the server the game runs under (ui.link), if it does."""
    opts = opts or Options()
    files = files or Files()
    keymap = keymap if keymap is not None else KeyMap()
    # Ball in hand: 1 cm a tap; held, from 0.25 to 1 m/s over a second from the press.
    controls = Controls(None, AimControl(keymap), HoldRamp(PLACE_TAP, 0.25, 1.0, 1.0,
                                                           from_press=True))
    s = State(opts=opts, keymap=keymap, controls=controls, env=env, files=files,
              depth=resolve_depth(opts.colors, env), link=link)
    s = turn.set_input_mode(s, input_mode)
    return turn.new_match(s, opts.mode, opts.opponent) if opts.mode is not None else s


def _changed(before: State, after: State) -> bool:
    """Whether anything but the clock is new (the update gives the same values where nothing
    happened)."""
    return any(getattr(before, f.name) is not getattr(after, f.name) for f in fields(State)
               if f.name != "now")


class App:
    def __init__(self, opts: Options | None = None, keymap: KeyMap | None = None,
                 input_mode: str = "release", env=None, *, prefs=None, history=None,
                 records=None, link=None) -> None:
        self.state = start(opts, keymap, input_mode, env, Files(prefs, history, records),
                           link)
        self.geometry = Geometry()  # this screen's table layout and background
        self.seen: Seen | None = None  # what this screen showed last (for the mouse)
        self.dirty = True

    # ------------------------------------------------------------- what the driver reads
    @property
    def done(self) -> bool:
        return self.state.done

    @property
    def depth(self) -> str:
        return self.state.depth

    @property
    def bells(self) -> int:
        """Bells to ring; the driver rings them and sets this back to 0."""
        return self.state.bells

    @bells.setter
    def bells(self, n: int) -> None:
        self.state = replace(self.state, bells=n)

    # ---------------------------------------------------------------------------- events
    def set_input_mode(self, mode: str) -> None:
        """How the terminal tells a held key, once the driver knows (see turn.set_input_mode)."""
        self.state = turn.set_input_mode(self.state, mode)
        self.dirty = True

    def key(self, key, t: float) -> None:
        self.state = phases.key(self.state, key, t, self.seen)
        self.dirty = True

    def mouse(self, ev, t: float) -> None:
        self.state = phases.mouse(self.state, ev, t, self.seen)
        self.dirty = True

    def tick(self, t: float) -> None:
        before = self.state
        self.state = s = phases.tick(before, t)
        if s.watch is not None:
            self.dirty = self.dirty or s.watch.dirty
        elif _changed(before, s) or phases.moving(s):
            self.dirty = True

    def wake_in(self, t: float) -> float | None:
        """Seconds until the app needs a tick (None: only on a key)."""
        return phases.wake_in(self.state, t)

    # ---------------------------------------------------------------------------- screen
    def cells(self, cols: int, rows: int):
        """The whole screen as (chars, fg, bg) cells (see ui.view)."""
        self.dirty = False
        if self.state.watch is not None:
            return self.state.watch.cells(cols, rows)
        self.state = aid.refresh(self.state)  # the aid catches up with the aim
        out, self.seen = draw(self.state, cols, rows, self.geometry)
        return out

    # --------------------------------------------------------------------------- leaving
    def record(self) -> Match | None:
        """The match to save (--record); a shot still rolling is played out first (see
        turn.record)."""
        self.state, match = turn.record(self.state)
        return match

    def leave(self) -> tuple[list[str], int]:
        """However the game ended: the match in play is saved (--record) and goes into the
        history; the lines left to say (notes, and where each record went) and the status
        (1 when a record could not go where asked)."""
        self.record()
        s = turn.log_match(self.state)
        records = s.files.records
        lines, status = records.finish(s.match) if records is not None else ([], 0)
        self.state = replace(s, notes=())
        return [*s.notes, *lines], status
