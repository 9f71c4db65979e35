"""`termpool bench`: benchmarks of the physics core, kept out of the installed game.

    termpool bench speed [--json] [--repeat N] [--batch B] [--dt S]
    termpool bench accuracy [--json] [--scenes DIR] [--closed NAMES] [--dts S ...]
                            [--schemes A,B] [--png PATH]
    termpool bench stability [--json] [--quick] [--case TEXT ...]

`speed` (speed.py) times the standard break, a batch of breaks and the import of the core.
`accuracy` (accuracy.py) runs a set of scenes (scenes/) with every stepping scheme at every dt
against the event-to-event reference, the seed game's scheme among them (naive.py); then every
scheme against closed-form answers derived from the model's equations (closed.py, with the
answers in closed_form.py and the scenes in closed_cases.py). `stability` (stability.py) runs
the stiff and extreme cases (stability_cases.py, shared with the tests) and prints PASS/FAIL.

This package sits beside `termpool` in a source checkout and is not installed with the game;
`termpool bench` finds it there. It imports only termpool's physics, scenes and rules (and the
small command and file helpers), never the game, the UI or the command line. This module is the
one dispatcher: SUBCOMMANDS maps a name to the module whose `main(argv)` runs it (imported only
when asked for, as numpy and the engine are).
"""

from __future__ import annotations

import importlib
import sys

from bench.common import PROG
from termpool.command import Exit, one_blas_thread
from termpool.text import say

SUBCOMMANDS = {
    "speed": ("bench.speed", "time the standard break, a batch of breaks and the core import"),
    "accuracy": ("bench.accuracy", "every stepping scheme against the event-to-event reference"),
    "stability": ("bench.stability",
                  "stiff and extreme cases: PASS/FAIL with the deciding figure"),
}

USAGE = f"usage: {PROG} {{{','.join(SUBCOMMANDS)}}} [options]   (try {PROG} SUBCOMMAND --help)\n"


def _help() -> str:
    lines = [USAGE.rstrip(), "", "benchmarks of the physics core:", ""]
    width = max(len(name) for name in SUBCOMMANDS)
    for name, (_, text) in SUBCOMMANDS.items():
        lines.append(f"  {name.ljust(width)}  {text}")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Entry point of `termpool bench`; argv is what follows `bench`. Returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    one_blas_thread()
    if not argv:
        say(f"bench: missing subcommand (use {', '.join(SUBCOMMANDS)})")
        return 2
    name, rest = argv[0], argv[1:]
    if name in ("-h", "--help"):
        sys.stdout.write(_help())
        return 0
    if name not in SUBCOMMANDS:
        say(f"bench: unknown subcommand '{name}' (use {', '.join(SUBCOMMANDS)})")
        return 2
    try:
        return importlib.import_module(SUBCOMMANDS[name][0]).main(rest)
    except Exit as e:
        return e.code
