"""Rules of pool as pure functions: no terminal code, no physics (only its event dicts).

- `events`: `summarize(events, ids)` -> `ShotSummary` (first contact, cushions, pockets, ...).
- `common`: the game `State` before a shot and the `Outcome` of a shot.
- `eight`, `nine`, `practice`: ``judge(state, summary) -> (Outcome, new_state)`` per game.
- `referee`: a scene's `game` block plus a shot's events -> the outcome as JSON.
- `themes`: ball colours, standard (solids and stripes) and classic (reds and yellows).
"""

from termpool.rules.common import Outcome, State
from termpool.rules.events import ShotSummary, summarize

__all__ = ["Outcome", "ShotSummary", "State", "summarize"]
