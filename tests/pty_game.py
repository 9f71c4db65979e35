"""Run the real `termpool` in a pseudo-terminal and read its screen through pyte (test helper).

The child gets the pty as its controlling terminal (so resizes send it SIGWINCH and Ctrl-Z
stops it); the parent decodes everything it writes with pyte and can send keys and signals.
"""

from __future__ import annotations

import fcntl
import os
import pty
import select
import signal
import struct
import sys
import termios
import time
from pathlib import Path

import pyte

ROOT = Path(__file__).resolve().parent.parent


def set_size(fd: int, cols: int, rows: int) -> None:
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", rows, cols, 0, 0))


class PtyGame:
    def __init__(self, *args: str, cols: int = 100, rows: int = 32, env: dict | None = None,
                 python_args: bool = False, kitty: bool = False):
        e = dict(os.environ)
        e.update({"TERM": "xterm-256color", "PYTHONPATH": str(ROOT), "COLORTERM": "truecolor"})
        e.pop("NO_COLOR", None)
        e.update(env or {})
        self.cols, self.rows = cols, rows
        pid, fd = pty.fork()
        if pid == 0:  # the child: the pty is its terminal
            try:
                os.chdir(ROOT)
                argv = [*args] if python_args else ["-m", "termpool", *args]
                os.execve(sys.executable, [sys.executable, *argv], e)
            finally:
                os._exit(127)
        self.pid, self.fd = pid, fd
        set_size(fd, cols, rows)
        self.screen = pyte.Screen(cols, rows)
        self.stream = pyte.ByteStream(self.screen)
        self.raw = b""
        self.status: int | None = None
        self.kitty = kitty  # answer the kitty keyboard query as a kitty-protocol terminal would

    # -- reading
    def pump(self, seconds: float = 0.05) -> bytes:
        """Read whatever the child writes for `seconds`; returns the new bytes."""
        end = time.monotonic() + seconds
        got = b""
        while True:
            left = end - time.monotonic()
            if left <= 0:
                break
            r, _, _ = select.select([self.fd], [], [], left)
            if not r:
                break
            try:
                data = os.read(self.fd, 65536)
            except OSError:  # the child closed the pty
                break
            if not data:
                break
            got += data
        if self.kitty and b"\x1b[?u" in got:
            os.write(self.fd, b"\x1b[?0u\x1b[?62;22c")  # flags 0, then the DA1 reply
        self.raw += got
        if got:
            self.stream.feed(got)
        return got

    def wait_for(self, text: str, timeout: float = 20.0) -> bool:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if text in self.text():
                return True
            if self.exited():
                self.pump(0.1)
                return text in self.text()
            self.pump(0.1)
        return text in self.text()

    def wait_for_raw(self, data: bytes, timeout: float = 20.0) -> bool:
        """Read until the child has written `data` (True), or `timeout` s have passed."""
        end = time.monotonic() + timeout
        while data not in self.raw and time.monotonic() < end and not self.exited():
            self.pump(0.1)
        return data in self.raw

    def text(self) -> str:
        return "\n".join(self.screen.display)

    # -- writing
    def send(self, data: str | bytes, pause: float = 0.05) -> None:
        os.write(self.fd, data.encode() if isinstance(data, str) else data)
        self.pump(pause)

    def resize(self, cols: int, rows: int) -> None:
        self.cols, self.rows = cols, rows
        self.screen.resize(rows, cols)
        set_size(self.fd, cols, rows)  # the kernel sends SIGWINCH to the child

    def kill(self, sig: int) -> None:
        os.kill(self.pid, sig)

    # -- the end
    def exited(self) -> bool:
        if self.status is not None:
            return True
        pid, st = os.waitpid(self.pid, os.WNOHANG)
        if pid:
            self.status = os.waitstatus_to_exitcode(st)
            return True
        return False

    def wait(self, timeout: float = 20.0) -> int | None:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            self.pump(0.05)
            if self.exited():
                self.pump(0.1)
                return self.status
        return None

    def close(self) -> None:
        if not self.exited():
            os.kill(self.pid, signal.SIGKILL)
            os.waitpid(self.pid, 0)
        try:
            os.close(self.fd)
        except OSError:
            pass


def restored(raw: bytes) -> bool:
    """The child's last words put the terminal back: cursor shown, main screen, colours reset."""
    tail = raw[raw.rfind(b"\x1b[?1049h") + 1:] if b"\x1b[?1049h" in raw else raw
    return (b"\x1b[?1049l" in tail and b"\x1b[?25h" in tail
            and tail.rfind(b"\x1b[?1049l") > tail.rfind(b"\x1b[?25l"))
