"""What the benchmarks share: their parser, argument types, the engine for a scene, and the
machine they ran on (printed under every report)."""

from __future__ import annotations

import argparse
import math
import os
import platform
from datetime import datetime
from fractions import Fraction
from typing import NoReturn

from termpool.command import Exit, Parser
from termpool.text import say

PROG = "termpool bench"


class BenchParser(Parser):
    """The command line's parser (one `termpool: ...` line and exit status 2 on errors),
    naming the bench subcommand in its messages."""

    def error(self, message: str) -> NoReturn:
        say(f"bench {self.prog.split()[-1]}: {message}")
        raise Exit(2)


def positive_int(text: str) -> int:
    try:
        val = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: '{text}'") from None
    if val <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive integer, not '{text}'")
    return val


def seconds(text: str) -> float:
    """A positive finite number of seconds; fractions such as 1/60 are accepted."""
    try:
        val = float(Fraction(text.strip())) if "/" in text else float(text)
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"not a number: '{text}'") from None
    if not math.isfinite(val) or val <= 0:
        raise argparse.ArgumentTypeError(f"must be positive and finite, not '{text}'")
    return val


def child_env() -> dict:
    """This process's environment with the checkout that holds termpool first on PYTHONPATH,
    for a child interpreter that must run the same code."""
    import termpool

    root = os.path.dirname(os.path.dirname(os.path.abspath(termpool.__file__)))
    env = dict(os.environ)
    env["PYTHONPATH"] = root + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


def make_engine(scene, pos=None, vel=None, w=None, record: bool = False):
    """An Engine of `scene`, with other starting positions and velocities if given."""
    from termpool.physics.engine import Engine

    return Engine(
        scene.table,
        scene.physics,
        scene.pos if pos is None else pos,
        scene.vel if vel is None else vel,
        scene.w if w is None else w,
        scene.radius,
        scene.mass,
        record=record,
    )


def machine_info() -> dict:
    import numpy as np

    info = {
        "platform": platform.platform(),
        "machine": platform.machine(),
        "cpu": _cpu_model(),
        "cpu_count": os.cpu_count(),
        "python": f"{platform.python_implementation()} {platform.python_version()}",
        "numpy": np.__version__,
        "date": datetime.now().astimezone().isoformat(timespec="seconds"),
    }
    return info


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def machine_lines(m: dict) -> list[str]:
    """The machine and date lines every benchmark prints under its figures."""
    return [
        f"machine: {m['platform']}; {m['cpu']} ({m['cpu_count']} cpus)",
        f"python {m['python']}, numpy {m['numpy']}; {m['date']}",
    ]
