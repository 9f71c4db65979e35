"""Running an app on a real terminal: modes in and out, signals, resize, frame pacing.

The app itself (``termpool.ui.app.App``) never touches the terminal: it takes keys with their
times, advances on `tick(now)` and hands back cells. This module owns everything that must be
undone: the alternate screen, the hidden cursor, cbreak mode, the kitty keyboard flags. They are
restored on every way out (normal exit, Ctrl-C, SIGTERM, SIGHUP, exceptions) and around Ctrl-Z.

Start-up never waits on the terminal: the first frame is written before any query (blessed's
start-up probes and ours for the kitty keyboard protocol), and every query is bounded by
`query_timeout`, so a terminal that ignores them all costs well under a second, after the
table is already on screen.
"""

from __future__ import annotations

import os
import signal
import sys
import termios
import time
import tty
from collections.abc import Callable
from typing import Protocol

from termpool.ui.output import Screen

ENTER = "\x1b[?1049h\x1b[?25l\x1b[H\x1b[2J"  # alternate screen, hide cursor, clear
LEAVE = "\x1b[0m\x1b[?2026l\x1b[?25h\x1b[?1049l"  # reset, end sync, show cursor, main screen
KITTY_FLAGS = 1 | 2 | 8  # disambiguate, report press/repeat/release, all keys as escapes
KITTY_PUSH = f"\x1b[>{KITTY_FLAGS}u"
KITTY_POP = "\x1b[<u"
FRAME_S = 1 / 60


class App(Protocol):
    done: bool
    dirty: bool  # something changed since the last `cells`

    def key(self, key, t: float) -> None: ...
    def tick(self, t: float) -> None: ...
    def cells(self, cols: int, rows: int): ...
    def wake_in(self, t: float) -> float | None: ...


class Stop(Exception):
    """Raised from a signal handler (SIGTERM, SIGHUP) to leave through the `finally`s."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def no_tty_message() -> str:
    return ("termpool: the game needs a terminal (stdin and stdout are not a tty); "
            "for headless runs use `termpool sim SCENE` or `termpool play --headless`")


class Terminal:
    """The terminal's modes: entered once, left exactly once, re-entered after a suspend."""

    def __init__(self, fd_in: int, out) -> None:
        self.fd_in, self.out = fd_in, out
        self.saved = termios.tcgetattr(fd_in)
        self.kitty = False
        self.active = False

    def write(self, s: str) -> None:
        try:
            self.out.write(s)
            self.out.flush()
        except OSError:  # the terminal went away (SIGHUP): nothing left to restore on it
            pass

    def enter(self) -> None:
        tty.setcbreak(self.fd_in, termios.TCSANOW)
        self.write(ENTER + (KITTY_PUSH if self.kitty else ""))
        self.active = True

    def leave(self) -> None:
        if not self.active:
            return
        self.active = False
        self.write((KITTY_POP if self.kitty else "") + LEAVE)
        try:
            termios.tcsetattr(self.fd_in, termios.TCSADRAIN, self.saved)
        except termios.error:
            pass


def _size(out) -> tuple[int, int]:
    try:
        s = os.get_terminal_size(out.fileno())
        return s.columns, s.lines
    except OSError:
        return 80, 24


def run(app: App, depth: str, *, kitty: bool = True, query_timeout: float = 0.25,
        set_input_mode: Callable[[str], None] | None = None) -> int:
    """Run `app` on the process's terminal until it is done. Returns the exit status."""
    from termpool.ui.keys import from_keystroke

    out = sys.stdout
    term = Terminal(sys.stdin.fileno(), out)
    cols, rows = _size(out)
    screen = Screen(cols, rows, depth, sync=True)
    flags = {"resized": False, "suspend": False}

    def on_winch(signum, frame):
        flags["resized"] = True

    def on_stop(signum, frame):
        raise Stop(signum)

    def on_tstp(signum, frame):
        flags["suspend"] = True

    old = {s: signal.getsignal(s) for s in (signal.SIGWINCH, signal.SIGTERM, signal.SIGHUP,
                                            signal.SIGTSTP)}
    signal.signal(signal.SIGWINCH, on_winch)
    signal.signal(signal.SIGTERM, on_stop)
    signal.signal(signal.SIGHUP, on_stop)
    signal.signal(signal.SIGTSTP, on_tstp)

    def suspend() -> None:
        # Put the terminal back, stop for real, and come back to a full redraw.
        term.leave()
        signal.signal(signal.SIGTSTP, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGTSTP)
        signal.signal(signal.SIGTSTP, on_tstp)
        term.enter()
        screen.invalidate()

    def draw(now: float) -> None:
        nonlocal cols, rows
        if flags["resized"]:
            flags["resized"] = False
            cols, rows = _size(out)
            screen.resize(cols, rows)
            term.write("\x1b[H\x1b[2J")
        s = screen.render(*app.cells(cols, rows))
        if getattr(app, "bells", 0):
            s += "\a"
            app.bells = 0
        if s:
            term.write(s)

    try:
        term.enter()
        now = time.monotonic()
        app.tick(now)
        draw(now)  # the first frame goes out before any query
        # blessed probes the terminal when it starts (XTGETTCAP, XTVERSION), waiting 5 s per
        # query by default: a terminal that ignores queries would hang us for seconds.
        os.environ.setdefault("BLESSED_QUERY_TIMEOUT_SECONDS", str(query_timeout))
        import blessed

        bt = blessed.Terminal()
        if kitty:
            with bt.cbreak():
                state = bt.get_kitty_keyboard_state(timeout=query_timeout)
            if state is not None:
                term.kitty = True
                term.write(KITTY_PUSH)
        if set_input_mode is not None:
            set_input_mode("release" if term.kitty else "repeat")
        next_frame = time.monotonic()
        while not app.done:
            if flags["suspend"]:
                flags["suspend"] = False
                suspend()
            now = time.monotonic()
            wake = app.wake_in(now)
            timeout = 0.5 if wake is None else max(0.0, min(wake, next_frame - now, 0.5))
            ks = bt.inkey(timeout=timeout)
            while ks:
                now = time.monotonic()
                key = from_keystroke(ks)
                if key is not None:
                    if key.ctrl and key.name == "z":  # kitty mode reports Ctrl-Z as a key
                        if key.kind == "press":
                            suspend()
                    elif key.ctrl and key.name == "c":
                        if key.kind == "press":
                            raise KeyboardInterrupt
                    else:
                        app.key(key, now)
                ks = bt.inkey(timeout=0)
            now = time.monotonic()
            app.tick(now)
            if (now >= next_frame and app.dirty) or flags["resized"]:
                draw(now)
                next_frame = max(next_frame + FRAME_S, now)
        return 0
    except KeyboardInterrupt:
        return 130
    except Stop as e:
        return 128 + e.signum
    finally:
        term.leave()
        for s, h in old.items():
            signal.signal(s, h)
