"""The computer's decision time, measured in whole games of `termpool selfplay`.

The benchmarks stay outside the game's runtime (they import no game, computer or UI code), so
the games run in a child process: `python -m termpool selfplay --levels hard,hard --json`.
Its figures for the decisions in play (every one but the break's) are processor time, which
the machine's other work does not stretch.
"""

from __future__ import annotations

import json
import subprocess
import sys

from bench.common import child_env

LEVEL = "hard"
SEED = 2026


def time_decisions(games: int, level: str = LEVEL, seed: int = SEED,
                   max_shots: int | None = None) -> dict:
    """Median and largest processor time of `level`'s decisions in play over `games` 8-ball
    games against itself (each cut at `max_shots`, if given), and how many that was."""
    env = child_env()
    p = subprocess.run(
        [sys.executable, "-m", "termpool", "selfplay", "--games", str(games), "--mode", "8ball",
         "--levels", f"{level},{level}", "--seed", str(seed), "--jobs", "1", "--json",
         *([] if max_shots is None else ["--max-shots", str(max_shots)])],
        env=env, capture_output=True, text=True, timeout=3600)
    if p.returncode != 0:
        last = (p.stderr.strip().splitlines() or ["no output"])[-1]
        raise RuntimeError(f"selfplay failed: {last}")
    r = json.loads(p.stdout)
    shots = r["shots_per_game"] * r["games"]
    return {
        "decision_level": level,
        "decision_games": r["games"],
        "decision_shots": shots,
        "decision_cpu_s": r["shot_decision_cpu_s"][level],
        "decision_cpu_s_max": r["shot_decision_cpu_s_max"][level],
    }
