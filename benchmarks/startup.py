"""How fast `termpool` shows its first frame, on a terminal that answers no queries.

python benchmarks/startup.py [--runs N]

Starts `python -m termpool play --mode 8ball` in a pseudo-terminal (which, like a silent
terminal over SSH, answers nothing), and measures from the fork to the first byte of output, to
the end of the first full frame (the panel's help line is its last text) and to the moment the
game has given up waiting for a reply to its kitty keyboard query. Also the `menu` (no
arguments). Prints medians and maxima; no thresholds (the target, from the developers' guide:
the first frame in well under a second).
"""

from __future__ import annotations

import argparse
import os
import platform
import pty
import select
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
QUERY = b"\x1b[?u"


def one(args: list[str], last_text: bytes) -> tuple[float, float, float]:
    env = dict(os.environ, TERM="xterm-256color", COLORTERM="truecolor", PYTHONPATH=str(ROOT))
    t0 = time.perf_counter()
    pid, fd = pty.fork()
    if pid == 0:
        os.execve(sys.executable, [sys.executable, "-m", "termpool", *args], env)
    import fcntl
    import struct
    import termios

    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 32, 100, 0, 0))
    raw = b""
    first = frame = asked = None
    while time.perf_counter() - t0 < 10:
        r, _, _ = select.select([fd], [], [], 0.01)
        now = time.perf_counter() - t0
        if r:
            try:
                raw += os.read(fd, 65536)
            except OSError:
                break
            if first is None and raw:
                first = now
            if frame is None and last_text in raw:
                frame = now
            if asked is None and QUERY in raw:
                asked = now
        if asked is not None and now > asked + 0.6:
            break
    os.write(fd, b"qy" if args else b"q")
    os.waitpid(pid, 0)
    os.close(fd)
    return first or 0.0, frame or 0.0, (asked or 0.0) + 0.25  # the query's bounded wait


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=7)
    a = ap.parse_args()
    print(f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}, {time.strftime('%Y-%m-%d %H:%M %Z')}")
    print("first output / first frame complete / input ready (after the 0.25 s query bound), s")
    for label, args, text in (("play --mode 8ball", ["play", "--mode", "8ball"], b"Q quit"),
                              ("menu (no arguments)", [], b"Enter start")):
        runs = [one(args, text) for _ in range(a.runs)]
        cols = list(zip(*runs, strict=True))
        print(f"  {label:<22}" + "".join(
            f"  {statistics.median(c):5.2f} (max {max(c):4.2f})" for c in cols))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
