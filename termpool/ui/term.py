"""Running an app on a real terminal: modes in and out, signals, resize, frame pacing.

The app itself (``termpool.ui.app.App``) never touches the terminal: it takes keys with their
times, advances on `tick(now)` and hands back cells. This module owns everything that must be
undone: the alternate screen, the hidden cursor, cbreak mode with flow control off (so Ctrl-S
cannot freeze the game), the kitty keyboard flags. They are restored on every way out (normal
exit, Ctrl-C, SIGTERM, SIGHUP, SIGQUIT from Ctrl-\\, exceptions) and around Ctrl-Z.

Start-up never waits on the terminal: the first frame is written before the one query we make
(kitty keyboard support, followed by a DA1 request that nearly every terminal answers), and
that wait is bounded by `query_timeout`, so a terminal that ignores queries costs a quarter of
a second after the table is already on screen. Input is read here and decoded by
``ui.keys.decode``; blessed supplies the terminal's own terminfo strings without probing it
(its start-up probes wait up to 5 s each on a silent terminal).
"""

from __future__ import annotations

import codecs
import io
import os
import re
import select
import signal
import sys
import termios
import time
import tty
from collections.abc import Callable
from contextlib import contextmanager
from typing import Protocol

from termpool.ui.keys import Mouse, decode_input
from termpool.ui.output import Screen

CLEAR = "\x1b[H\x1b[2J"  # cursor home, clear the screen
ENTER = "\x1b[?1049h\x1b[?25l" + CLEAR  # alternate screen, hide cursor, clear
LEAVE = "\x1b[0m\x1b[?2026l\x1b[?25h\x1b[?1049l"  # reset, end sync, show cursor, main screen
MOUSE_ON = "\x1b[?1002h\x1b[?1006h"  # report presses, drags and releases, in SGR form
MOUSE_OFF = "\x1b[?1006l\x1b[?1002l"
KITTY_QUERY = "\x1b[?u\x1b[c"  # kitty flags, then DA1 as the boundary every terminal answers
_KITTY_REPLY = re.compile(r"\x1b\[\?\d*u")
_DA1_REPLY = re.compile(r"\x1b\[\?[\d;]*c")
_CUT_OFF = re.compile(r"\x1b(\[[0-?]*[ -/]*|O|\x1b|\x1b\[[0-?]*)?$")  # a sequence still arriving
ESC_WAIT = 0.03  # s to wait for the rest of a sequence cut by a read
KITTY_FLAGS = 1 | 2 | 8  # disambiguate, report press/repeat/release, all keys as escapes
KITTY_PUSH = f"\x1b[>{KITTY_FLAGS}u"
KITTY_POP = "\x1b[<u"
FRAME_S = 1 / 60


class App(Protocol):
    done: bool
    dirty: bool  # something changed since the last `cells`

    def key(self, key, t: float) -> None: ...
    def mouse(self, ev, t: float) -> None: ...
    def tick(self, t: float) -> None: ...
    def cells(self, cols: int, rows: int): ...
    def wake_in(self, t: float) -> float | None: ...


STOP_SIGNALS = (signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


@contextmanager
def signals_held():
    """Ctrl-C and STOP_SIGNALS wait until the block ends, then act: what it does is done
    whole (a shot judged and recorded, a record saved) whatever arrives meanwhile."""
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, *STOP_SIGNALS})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


class Stop(Exception):
    """Raised from a signal handler (STOP_SIGNALS) to leave through the `finally`s."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


@contextmanager
def stoppable():
    """STOP_SIGNALS end the block the way Ctrl-C does, by an exception (Stop), so that the
    `finally`s run (a record is still saved)."""

    def stop(signum, frame):
        raise Stop(signum)

    old = {s: signal.signal(s, stop) for s in STOP_SIGNALS}
    try:
        yield
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)


def no_tty_message() -> str:
    return ("termpool: the game needs a terminal (stdin and stdout are not a tty); "
            "for headless runs use `termpool sim SCENE` or `termpool play --headless`")


class Terminal:
    """The terminal's modes: entered once, left exactly once, re-entered after a suspend."""

    def __init__(self, fd_in: int, out, mouse: bool = True) -> None:
        self.fd_in, self.out, self.mouse = fd_in, out, mouse
        self.saved = termios.tcgetattr(fd_in)
        self.kitty = False
        self.active = False
        self.enter_s, self.leave_s = _mode_strings()

    def write(self, s: str) -> None:
        try:
            self.out.write(s)
            self.out.flush()
        except OSError:  # the terminal went away (SIGHUP): nothing left to restore on it
            pass

    def enter(self) -> None:
        tty.setcbreak(self.fd_in, termios.TCSANOW)
        # Flow control off: Ctrl-S would stop our output until Ctrl-Q, and a game blocked on a
        # write answers nothing, not even SIGTERM. Ctrl-S and Ctrl-Q then arrive as keys.
        attrs = termios.tcgetattr(self.fd_in)
        attrs[0] &= ~termios.IXON
        termios.tcsetattr(self.fd_in, termios.TCSANOW, attrs)
        self.write(self.enter_s + (KITTY_PUSH if self.kitty else "")
                   + (MOUSE_ON if self.mouse else ""))
        self.active = True

    def leave(self) -> None:
        if not self.active:
            return
        self.active = False
        self.write((MOUSE_OFF if self.mouse else "") + (KITTY_POP if self.kitty else "")
                   + self.leave_s)
        try:
            termios.tcsetattr(self.fd_in, termios.TCSADRAIN, self.saved)
        except termios.error:
            pass


def _mode_strings(kind: str | None = None) -> tuple[str, str]:
    """Enter/leave strings from the terminal's terminfo entry (through blessed, given a
    non-tty stream so it probes nothing; `kind` overrides $TERM), falling back to the xterm
    sequences. A terminal without an alternate screen (the Linux console, TERM=linux) keeps
    the game's last frame when it leaves: there leaving clears the screen and homes the
    cursor, so the shell's prompt comes back on a clean screen."""
    try:
        import blessed

        bt = blessed.Terminal(kind=kind, stream=io.StringIO(), force_styling=True)
        enter = bt.enter_fullscreen + bt.hide_cursor
        leave = bt.normal_cursor + bt.exit_fullscreen
        if "\x1b" in enter and "\x1b" in leave:
            clear = "" if bt.enter_fullscreen else CLEAR
            return enter + CLEAR, "\x1b[0m\x1b[?2026l" + clear + leave
    except Exception:  # a broken terminfo entry must not keep anyone from playing
        pass
    return ENTER, LEAVE


def _size(out) -> tuple[int, int]:
    try:
        s = os.get_terminal_size(out.fileno())
        return s.columns, s.lines
    except OSError:
        return 80, 24


class Input:
    """Bytes from the terminal -> keys, waiting briefly for sequences cut by a read."""

    def __init__(self, fd: int) -> None:
        self.fd = fd
        self.utf8 = codecs.getincrementaldecoder("utf-8")("replace")
        self.pending = ""  # text read but not yet decoded (e.g. during the kitty query)
        self.closed = False

    def _read(self, timeout: float) -> str:
        r, _, _ = select.select([self.fd], [], [], timeout)
        if not r:
            return ""
        try:
            data = os.read(self.fd, 4096)
        except OSError:
            data = b""
        if not data:
            self.closed = True  # the terminal is gone
        return self.utf8.decode(data)

    def keys(self, timeout: float) -> list:
        """Keys and mouse reports that arrived within `timeout` seconds."""
        text = self.pending + ("" if self.pending else self._read(timeout))
        self.pending = ""
        while text and _CUT_OFF.search(text) and not self.closed:
            more = self._read(ESC_WAIT)
            if not more:
                break
            text += more
        return decode_input(text) if text else []

    def ask_kitty(self, term: Terminal, timeout: float) -> bool:
        """Does the terminal speak the kitty keyboard protocol? Keys typed meanwhile are kept."""
        term.write(KITTY_QUERY)
        text = ""
        end = time.monotonic() + timeout
        while not _DA1_REPLY.search(text) and not self.closed:
            left = end - time.monotonic()
            if left <= 0:
                break
            text += self._read(left)
        ok = _KITTY_REPLY.search(text) is not None
        self.pending += _DA1_REPLY.sub("", _KITTY_REPLY.sub("", text))
        return ok


def run(app: App, depth: str, *, kitty: bool = True, query_timeout: float = 0.25,
        set_input_mode: Callable[[str], None] | None = None, mouse: bool = True,
        idle: float = 0.5) -> int:
    """Run `app` on the process's terminal until it is done. Returns the exit status.
    `idle`: the longest wait for input when nothing moves (signals are checked after it)."""
    out = sys.stdout
    term = Terminal(sys.stdin.fileno(), out, mouse)
    keys_in = Input(sys.stdin.fileno())
    cols, rows = _size(out)
    screen = Screen(cols, rows, depth, sync=True)
    flags = {"resized": False, "suspend": False}

    def on_winch(signum, frame):
        flags["resized"] = True

    def on_stop(signum, frame):
        raise Stop(signum)

    def on_tstp(signum, frame):
        flags["suspend"] = True

    old = {s: signal.getsignal(s) for s in (signal.SIGWINCH, signal.SIGTSTP, *STOP_SIGNALS)}
    signal.signal(signal.SIGWINCH, on_winch)
    for sig in STOP_SIGNALS:
        signal.signal(sig, on_stop)
    signal.signal(signal.SIGTSTP, on_tstp)

    def suspend() -> None:
        # Put the terminal back, stop for real, and come back to a full redraw.
        term.leave()
        signal.signal(signal.SIGTSTP, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGTSTP)
        signal.signal(signal.SIGTSTP, on_tstp)
        term.enter()
        screen.invalidate()
        flags["resized"] = True  # the size may have changed while we were away

    def draw() -> None:
        nonlocal cols, rows, screen
        if getattr(app, "depth", depth) != screen.depth:  # changed in the settings
            screen = Screen(cols, rows, app.depth, sync=True)
            flags["resized"] = True  # a full redraw in the new colours
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
        app.tick(time.monotonic())
        draw()  # the first frame goes out before the query
        if kitty and keys_in.ask_kitty(term, query_timeout):
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
            if app.dirty:  # a change not drawn yet (a key came just after a frame)
                wake = 0.0
            # (The next frame's time matters only to a change not drawn yet: once past, it
            # must not turn an app's timed wake, such as a lobby's poll, into a spin.)
            timeout = idle if wake is None else max(0.0, min(wake, idle))
            if flags["resized"]:
                timeout = 0.0
            for key in keys_in.keys(timeout):
                now = time.monotonic()
                if isinstance(key, Mouse):
                    app.mouse(key, now)
                elif key.ctrl and key.name == "z":  # kitty mode reports Ctrl-Z as a key
                    if key.kind == "press":
                        suspend()
                elif key.ctrl and key.name == "c":
                    if key.kind == "press":
                        raise KeyboardInterrupt
                elif key.ctrl and key.name == "\\":  # kitty mode: Ctrl-\ is a key, no SIGQUIT
                    if key.kind == "press":
                        raise Stop(signal.SIGQUIT)
                else:
                    app.key(key, now)
            if keys_in.closed:
                raise Stop(signal.SIGHUP)
            now = time.monotonic()
            app.tick(now)
            if (now >= next_frame and app.dirty) or flags["resized"]:
                draw()
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
