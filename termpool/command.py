"""What termpool's command lines share (`termpool` and `termpool bench`): bad arguments are one
`termpool: ...` line on stderr and exit status 2, and numpy's BLAS starts with one thread.

Kept light (argparse, os and sys): the command line imports it before anything else.
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import NoReturn

from termpool.text import say


class Exit(Exception):
    """Leave the command with this exit status (raised by Parser instead of sys.exit)."""

    def __init__(self, code: int) -> None:
        self.code = code


class Parser(argparse.ArgumentParser):
    """argparse, but errors are one `termpool: ...` line on stderr and exit status 2."""

    def error(self, message: str) -> NoReturn:
        say(" ".join(message.split()))
        raise Exit(2)

    def exit(self, status: int = 0, message: str | None = None) -> NoReturn:
        if message:
            sys.stderr.write(message)
        raise Exit(status)


# The thread pools of the BLAS libraries numpy may be built with. termpool needs none: its
# engine writes out its small solves and products (only 4x4 eigenvalue problems reach LAPACK,
# on the calling thread), and a pool's idle workers spin for a while after it starts, which
# burns a second core while the game only waits.
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS",
                "BLIS_NUM_THREADS", "VECLIB_MAXIMUM_THREADS")


def one_blas_thread() -> None:
    """Have numpy's BLAS start with one thread in termpool's own processes, unless the user
    set a number. It must run before numpy is imported; a program that imports termpool as
    a library keeps its own settings."""
    if "numpy" not in sys.modules:
        for name in BLAS_THREADS:
            os.environ.setdefault(name, "1")
