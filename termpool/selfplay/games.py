"""The computer against itself: one game between two levels, and the figures of many.

`play_game` plays one game of a `Match` between two levels of `termpool.ai` and returns a
tally per player, counted from what the shots did (the plan's kind and target, the engine's
pocket events, the referee's outcome), never from words. `figures` pools the tallies of many
games by level (a level that plays both sides is one level). No terminal code here: the
command (`termpool selfplay`) is in `termpool.selfplay.command`.

What is counted, per player and game:

- a *pot attempt* is a shot whose plan is a pot or a combination; it *dropped* when the ball
  it meant to sink went into the pocket it was sent to;
- a *foul* is a shot the referee calls a foul (counted by its name too); a *safety* is a
  shot planned as one (it chose not to pot), a *kick* one planned as a kick (no pot was on);
- a *break and run*: the breaker wins the game before the opponent has a shot;
- *after a pot*: pot attempts that follow the same player's pot that dropped (position play);
- around each safety and kick, the opponent's best chance of a straight pot (`ai.best_chance`,
  an aim error of CHANCE_SIGMA) on the table before it and on the table it leaves (with ball
  in hand after a foul, from the best spot), and whether it fouled;
- the wall time of each decision (placing the cue ball in hand, choosing the shot), and the
  processor time it took (what it would take on an idle machine: a shared one stretches the
  wall time), and apart from the breaks, the processor time of each decision in play.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from termpool import ai
from termpool.files import to_json, write_atomic
from termpool.game.match import Match
from termpool.game.turn import Shot
from termpool.rules.events import summarize

CHANCE_SIGMA = ai.LEAVE_SIGMA  # degrees: the aim error a safety's effect is measured with
MAX_SHOTS = 300  # a game still going after this many shots is stopped without a winner
DEFENCE = {"safety": "safety", "kick": "kick"}  # plans that try no pot: a safety by choice,
# a kick when no pot is on (snookered)


def game_seed(seed: int, index: int) -> int:
    """The seed of game `index` of a run: independent of the other games, so that games can
    be played in any order or process and give the same result."""
    return int(np.random.SeedSequence([seed, index]).generate_state(1, np.uint64)[0])


def _tally(level: str) -> dict:
    return {"level": level, "shots": 0, "pot_attempts": 0, "pots": 0, "fouls": 0,
            "safeties": 0, "breaks": 0, "runs": 0, "after_pot_attempts": 0,
            "after_pot_pots": 0, "decisions": [], "decisions_cpu": [], "shot_cpu": [], "kicks": 0,
            **{f"{d}_{k}": [] for d in DEFENCE for k in ("before", "after", "foul")},
            "foul_kinds": {}}


def players_for(levels: Sequence[str]) -> tuple[str, str]:
    """The players' names: the levels, told apart when one level plays both sides."""
    a, b = levels
    return (a, b) if a != b else (f"{a} 1", f"{b} 2")


def _args(m: Match) -> tuple:
    return (m.table, m.physics, m.ids, m.pos, m.radius, m.mass, m.on_table)


def _chance_for(m: Match, player: int, area: str | None) -> float:
    """The best straight pot `player` has on the match's table now (with ball in hand in
    `area`: from the best spot there)."""
    state = replace(m.state, shooter=player)
    return ai.best_chance(*_args(m), state, area=area, sigma=CHANCE_SIGMA)


def play_game(levels: Sequence[str], *, mode: str = "8ball", table: str = "9ft",
              seed: int = 0, candidates: int = 256, max_shots: int = MAX_SHOTS,
              record: str | Path | None = None, stop: Callable[[], bool] = lambda: False,
              clock: Callable[[], float] = time.perf_counter) -> dict:
    """One game: `levels[0]` is player 0 and breaks. Returns {"seed", "levels", "winner"
    (0, 1 or None when stopped), "finished", "shots", "tallies" (one per player)}.

    `record` is a file the match is written to (atomically) when the game ends, however it
    ends; `stop()` is asked before every shot, and True ends the game there, unfinished.
    """
    levels = tuple(levels)
    players = tuple(ai.Computer(lv, name, candidates)
                    for lv, name in zip(levels, players_for(levels), strict=True))
    m = Match(mode, table=table, players=players, seed=seed)
    tallies = [_tally(levels[0]), _tally(levels[1])]
    # (player, dropped) of the last shot: a pot attempt right after one's own pot that
    # dropped is a test of position.
    last: tuple[int, bool] | None = None
    opponent_shot = False
    finished = False
    try:
        while m.winner is None and len(m.history) < max_shots:
            if stop():
                break
            me = m.shooter
            player, mine = m.seats[me], tallies[me]
            if m.option is not None:
                m.choose(player.answer(m))
                continue
            t0, c0 = clock(), time.process_time()
            if m.ball_in_hand:
                m.place_cue(*player.place(m))
            struck = player.shot(m)  # as struck; its kind and target as meant
            mine["decisions"].append(clock() - t0)
            mine["decisions_cpu"].append(time.process_time() - c0)
            is_break = m.state.is_break
            if not is_break:
                mine["shot_cpu"].append(mine["decisions_cpu"][-1])
            defence = DEFENCE.get(struck.kind)
            before = _chance_for(m, 1 - me, None) if defence else None
            run = m.begin(Shot(struck.speed, struck.angle, struck.side, struck.top,
                               called=struck.called))
            out = run.finish()
            summary = summarize(run.engine.log[0], run.ids, is_break=is_break)
            mine["shots"] += 1
            opponent_shot |= me != m.breaker
            mine["breaks"] += is_break
            mine["fouls"] += out.foul is not None
            if out.foul is not None:
                kinds = mine["foul_kinds"]
                kinds[out.foul] = kinds.get(out.foul, 0) + 1
            dropped = False
            if struck.kind in ("pot", "combo"):
                dropped = summary.pocketed.get(struck.ball) == struck.pocket
                mine["pot_attempts"] += 1
                mine["pots"] += dropped
                if last == (me, True):
                    mine["after_pot_attempts"] += 1
                    mine["after_pot_pots"] += dropped
            last = (me, dropped and out.continue_turn)
            if defence:
                mine["safeties" if defence == "safety" else "kicks"] += 1
                # A shot that ends the game or keeps the turn (it potted) denies nothing.
                if m.winner is None and m.shooter != me:
                    mine[f"{defence}_before"].append(before)
                    mine[f"{defence}_after"].append(_chance_for(m, m.shooter, m.ball_in_hand))
                    mine[f"{defence}_foul"].append(out.foul is not None)
        finished = m.winner is not None or len(m.history) >= max_shots
    finally:
        if record is not None:
            if m.running is not None:  # stopped mid-shot: the match as it was before it
                m.abandon(m.running)
            write_atomic(record, to_json(m.to_json(), indent=1) + "\n")
    if m.winner is not None and m.winner == m.breaker and not opponent_shot:
        tallies[m.breaker]["runs"] += 1
    return {"seed": seed, "levels": list(levels), "winner": m.winner, "finished": finished,
            "shots": len(m.history), "tallies": tallies}


# ------------------------------------------------------------------------------ figures


def _share(num: float, den: float) -> float | None:
    return None if den == 0 else num / den


def _mean(xs: list[float]) -> float | None:
    return None if not xs else statistics.fmean(xs)


def figures(games: Sequence[dict], levels: Sequence[str]) -> dict:
    """The figures of finished games (see `play_game`), pooled by level: for each level its
    wins, pot rate, fouls and safeties per game it played (a level on both sides counts two
    player-games a game), break-and-run rate (of its breaks), median and slowest decision
    (and the median processor time of one; and of the decisions in play, not on a break, the
    median and the largest processor time);
    then shots per game, games without a winner, the pot rate after a pot (position) and the
    opponent's best chance before and after its safeties."""
    names = list(dict.fromkeys(levels))
    pool: dict[str, dict] = {lv: _tally(lv) | {"games": 0, "wins": 0} for lv in names}
    shots = undecided = 0
    for g in games:
        shots += g["shots"]
        undecided += g["winner"] is None
        for player, t in enumerate(g["tallies"]):
            p = pool[t["level"]]
            p["games"] += 1
            p["wins"] += g["winner"] == player
            for k, v in t.items():
                if isinstance(v, list):
                    p[k].extend(v)
                elif isinstance(v, dict):
                    for name, count in v.items():
                        p[k][name] = p[k].get(name, 0) + count
                elif k != "level":
                    p[k] += v
    n = len(games)

    def per(key: str, fn: Callable[[dict], Any]) -> dict:
        return {lv: fn(pool[lv]) for lv in names}

    def effect(p: dict, d: str) -> dict:
        """What the safeties (or kicks) left the opponent, before and after."""
        rows = list(zip(p[f"{d}_before"], p[f"{d}_after"], p[f"{d}_foul"], strict=True))
        clean = [(b, a) for b, a, f in rows if not f]
        return {"count": len(rows), "fouls": sum(f for _, _, f in rows),
                "opponent_chance_before": _mean([b for b, _, _ in rows]),
                "opponent_chance_after": _mean([a for _, a, _ in rows]),
                "lowered": _share(sum(a < b for b, a, _ in rows), len(rows)),
                "lowered_without_foul": _share(sum(a < b for b, a in clean), len(clean))}

    return {
        "games": n,
        "levels": list(levels),
        "wins": per("wins", lambda p: p["wins"]),
        "pot_rate": per("pot_rate", lambda p: _share(p["pots"], p["pot_attempts"])),
        "fouls_per_game": per("fouls", lambda p: _share(p["fouls"], p["games"])),
        "break_and_run_rate": per("runs", lambda p: _share(p["runs"], p["breaks"])),
        "safeties_per_game": per("safeties", lambda p: _share(p["safeties"], p["games"])),
        "shots_per_game": _share(shots, n),
        "decision_s": per("d", lambda p: statistics.median(p["decisions"])
                          if p["decisions"] else None),
        "decision_s_max": per("d", lambda p: max(p["decisions"], default=None)),
        "decision_cpu_s": per("c", lambda p: statistics.median(p["decisions_cpu"])
                              if p["decisions_cpu"] else None),
        "shot_decision_cpu_s": per("c", lambda p: statistics.median(p["shot_cpu"])
                                   if p["shot_cpu"] else None),
        "shot_decision_cpu_s_max": per("c", lambda p: max(p["shot_cpu"], default=None)),
        "undecided": undecided,
        "pot_attempts": per("a", lambda p: p["pot_attempts"]),
        "foul_kinds": per("f", lambda p: dict(sorted(p["foul_kinds"].items()))),
        "pot_rate_after_pot": per("ap", lambda p: _share(p["after_pot_pots"],
                                                         p["after_pot_attempts"])),
        "kicks_per_game": per("k", lambda p: _share(p["kicks"], p["games"])),
        "safeties": per("s", lambda p: effect(p, "safety")),
        "kicks": per("k", lambda p: effect(p, "kick")),
    }


def rounded(x: Any, digits: int = 4) -> Any:
    """Figures for printing: floats to `digits` places, inside dicts and lists too."""
    if isinstance(x, float):
        return round(x, digits) if math.isfinite(x) else None
    if isinstance(x, dict):
        return {k: rounded(v, digits) for k, v in x.items()}
    if isinstance(x, list):
        return [rounded(v, digits) for v in x]
    return x
