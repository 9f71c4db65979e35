"""Run a function as an unprivileged user (test helper): root reads and writes anywhere, so
permission errors can only be seen by someone else."""

from __future__ import annotations

import os
from collections.abc import Callable

NOBODY = 65534


def as_nobody(fn: Callable[[], object]) -> str:
    """repr(fn()) computed in a forked child that runs as `nobody` when we are root (as
    ourselves otherwise). The code is already loaded, so the child needs no file to run."""
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:
        try:
            os.close(r)
            if os.geteuid() == 0:
                os.setgid(NOBODY)
                os.setuid(NOBODY)
            os.write(w, repr(fn()).encode())
        finally:
            os._exit(0)
    os.close(w)
    with os.fdopen(r) as f:
        out = f.read()
    os.waitpid(pid, 0)
    return out
