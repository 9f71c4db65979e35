"""Rules of pool as pure functions: no terminal code, no physics (only its event dicts).

- `events`: `summarize(events, ids)` -> `ShotSummary` (first contact, cushions, pockets, ...).
- `common`: the game `State` before a shot and the `Outcome` of a shot.
- `codes`: fouls, options and their choices, and the reasons of a verdict, as codes.
- `eight`, `nine`, `practice`: ``judge(state, summary) -> (Outcome, new_state)`` per game.
- `referee`: a scene's `game` block plus a shot's events -> the outcome (and as JSON).
- `codec`: the game state as JSON, as a save keeps it and as a scene's `game` block.
- `words`: the codes in words, for people and for the record; the ball themes' names for the
  groups (their colours are the UI's); the rules page.
"""

from termpool.rules.common import Outcome, State
from termpool.rules.events import ShotSummary, summarize

__all__ = ["Outcome", "ShotSummary", "State", "summarize"]
