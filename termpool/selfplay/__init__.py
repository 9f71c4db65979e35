"""The computer against itself: `termpool selfplay`.

Above the computer opponent and the game, beside the command line: `games` plays one game
between two levels and pools the figures of many; `command` is the command (its arguments,
the parallel runs, the progress bar and the report).
"""

from termpool.selfplay.command import SelfplayError, add_arguments, run

__all__ = ["SelfplayError", "add_arguments", "run"]
