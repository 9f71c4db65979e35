"""What the rules need to know about one shot, read from the engine's events.

The engine logs, per table, typed events in time order (`termpool.physics.events.Event`, its
`log`), and gives them as dicts as well (`Event.to_json`, its `events`): ``{"t", "type", "i",
...}`` where ``i`` holds ball indices into the scene's ids. Either form is read. The rules use
three types:

- ``ball_ball`` (``i`` = the two balls, then any other balls of a touching cluster that the
  contact set moving),
- ``cushion`` (``i`` = one ball, ``feature`` = ``"rail"``, ``"jaw"`` or ``"tip"``; a jaw or a
  jaw tip is part of the cushion, so each counts as a ball driven to a rail),
- ``pocket`` (``i`` = one ball, ``pocket`` = the pocket's name, e.g. ``"foot_left"``).

Events as printed by ``termpool sim`` (with ``ids`` instead of ``i``) are read as well.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from termpool.physics.events import Event, EventKind


@dataclass(frozen=True)
class ShotSummary:
    """One shot as the referee sees it. Ball ids are strings ("cue", "1".."15")."""

    first_contact: str | None = None
    """The first ball the cue ball touched, or None when it touched no ball."""
    cushions_after_contact: int = 0
    """Cushion contacts (rail, jaw or jaw tip, any ball) after the first contact."""
    rail_balls: tuple[str, ...] = ()
    """Distinct balls (the cue ball included) that touched a cushion after the first contact,
    in the order of their first such touch."""
    pocketed: dict[str, str] = field(default_factory=dict)
    """Ball id -> pocket name for every ball pocketed, in the order they dropped (cue included)."""
    scratch: bool = False
    """The cue ball was pocketed."""
    off_table: tuple[str, ...] = ()
    """Balls that left the table (jumped over a rail). The physics core never lets a ball leave
    the table, so `summarize` always leaves this empty; it is kept so the rules for balls off
    the table are complete and can be tested, and so a future engine (or a hand-made summary)
    can report them."""
    is_break: bool = False
    """The shot was a break shot."""
    cue_id: str = "cue"

    @property
    def object_pocketed(self) -> list[str]:
        """Pocketed balls other than the cue ball, in order."""
        return [b for b in self.pocketed if b != self.cue_id]

    @property
    def object_rail_balls(self) -> list[str]:
        """Distinct object balls that touched a cushion after the first contact."""
        return [b for b in self.rail_balls if b != self.cue_id]

    @property
    def cue_off_table(self) -> bool:
        return self.cue_id in self.off_table


def _ball_ids(ev: dict, ids: Sequence[str]) -> list[str]:
    if "i" in ev:
        return [ids[int(k)] for k in ev["i"]]
    return [str(b) for b in ev["ids"]]


def _read(ev: Event | dict, ids: Sequence[str]) -> tuple[str, list[str], str | None]:
    """An event's type, ball ids and pocket name, from either form."""
    if isinstance(ev, Event):
        pocket = ev.pocket if ev.kind is EventKind.POCKET else None
        return ev.kind.value, [ids[k] for k in ev.balls], pocket
    kind = ev["type"]
    return kind, _ball_ids(ev, ids), ev["pocket"] if kind == "pocket" else None


def summarize(
    events: Iterable[Event | dict],
    ids: Sequence[str],
    cue_id: str = "cue",
    is_break: bool = False,
) -> ShotSummary:
    """Summarize one shot from its events (the engine's, typed or as dicts, or `termpool sim`
    output events)."""
    evs = sorted(events, key=lambda e: e.t if isinstance(e, Event) else e["t"])  # stable
    first: str | None = None
    cushions = 0
    rail: dict[str, None] = {}
    pocketed: dict[str, str] = {}
    for ev in evs:
        kind, balls, pocket = _read(ev, ids)
        if kind == "ball_ball":
            pair = balls[:2]  # further ids are other balls of a touching cluster
            if first is None and cue_id in pair:
                others = [b for b in pair if b != cue_id]
                first = others[0] if others else None
        elif kind == "cushion":
            if first is not None:
                cushions += 1
                rail.setdefault(balls[0], None)
        elif kind == "pocket":
            pocketed.setdefault(balls[0], str(pocket))
    return ShotSummary(
        first_contact=first,
        cushions_after_contact=cushions,
        rail_balls=tuple(rail),
        pocketed=pocketed,
        scratch=cue_id in pocketed,
        off_table=(),
        is_break=is_break,
        cue_id=cue_id,
    )
