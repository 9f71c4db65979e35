"""A match's settings, checked once: each bad one is a ValueError naming it."""

from __future__ import annotations

from typing import NamedTuple

from termpool.physics.params import Physics
from termpool.physics.table import PRESETS, Table
from termpool.rules.common import EIGHT_BREAKS, MODES
from termpool.rules.words import THEMES

from . import record
from .players import Player, check_players


class Settings(NamedTuple):
    mode: str
    table: Table
    frames: int
    players: tuple[Player, Player]
    seed: int
    physics: Physics
    three_foul: bool
    theme: str
    dt: float
    eight_break: str


def check_settings(mode: str, table: str | Table, frames: int, players, seed: int,
                   physics: Physics | None, three_foul: bool, theme: str, dt: float,
                   eight_break: str) -> Settings:
    """The settings of `Match`, checked (a table preset's name becomes its Table)."""
    if mode not in MODES:
        raise ValueError(f"mode: must be one of {', '.join(MODES)}, not {mode!r}")
    if isinstance(table, str):
        if table not in PRESETS:
            raise ValueError(f"table: unknown preset {table!r} (use {', '.join(PRESETS)})")
        table = Table.preset(table)
    if not isinstance(table, Table) or table.pockets != "standard":
        raise ValueError("table: must be a preset name or a Table with pockets")
    if type(frames) is not int or frames < 1:
        raise ValueError(f"frames: must be a whole number >= 1, not {frames!r}")
    players = check_players(players)
    if type(seed) is not int:
        raise ValueError(f"seed: must be a whole number, not {seed!r}")
    physics = Physics() if physics is None else physics
    for k in record.NEVER_STOP:
        if not getattr(physics, k) > 0:
            raise ValueError(f"physics.{k}: must be positive in a match (else the balls "
                             "never stop)")
    if three_foul and mode != "9ball":
        raise ValueError("three_foul: only for mode '9ball'")
    if eight_break not in EIGHT_BREAKS:
        raise ValueError(f"eight_break: must be one of {', '.join(EIGHT_BREAKS)}, "
                         f"not {eight_break!r}")
    if theme not in THEMES:
        raise ValueError(f"theme: must be one of {', '.join(THEMES)}, not {theme!r}")
    if not (isinstance(dt, float) and record.DT_RANGE[0] <= dt <= record.DT_RANGE[1]):
        raise ValueError(f"dt: must be from {record.DT_RANGE[0]:g} to "
                         f"{record.DT_RANGE[1]:g} seconds (what a replay accepts)")
    return Settings(mode, table, frames, players, seed, physics, bool(three_foul), theme, dt,
                    eight_break)
