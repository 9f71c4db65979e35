"""The history of play: after each match, one line per player in `history.jsonl`, in the data
directory (where a record that cannot be saved goes too).

A line is one JSON object (ASCII; a name's other characters are escaped)::

    {"v": 1, "date": "2026-11-27T13:08:12+00:00", "mode": "8ball", "player": "You",
     "side": 0, "cpu": false, "opponent": "Computer", "level": "normal", "race": 3,
     "won": 2, "lost": 1, "result": "won", "shots": 31, "pots": 12, "potting_shots": 10,
     "pot_rate": 0.3226, "fouls": 2, "break_runs": 0, "longest_run": 4}

`side`: the player's number in the match (0: player 1, who is you against the computer and in
practice); `cpu`: this line's player is the computer; `level`: the computer's level when it
played, else null; `opponent`: null in practice; `race`: frames to win; `won`, `lost`: frames;
`result`: "won", "lost", "unfinished" (left before the end) or "practice"; `online`: present
and true on the line of a match played against someone on another screen (`termpool serve`),
where the file holds only this player's line, whichever side they were; `match`: such a
match's id (its seed, in hex), so that a match left by a dropped connection ("unfinished")
and played on when the player came back counts once, as its last line says; `forfeit`:
present and true when the match was won or lost by a player leaving it before its end.

Every figure comes from the match's shot records (the engine's final ball states and the
referee's outcomes), never from its words:

- `shots`: the player's shots, breaks and push-outs included; `fouls`: those called fouls.
- `pots`: object balls the player pocketed on shots that were neither a foul nor a push-out;
  `potting_shots`: such shots that pocketed at least one; `pot_rate` = potting_shots / shots.
- `break_runs`: frames the player broke and won without the opponent taking a shot.
- `longest_run`: the most object balls pocketed in one run: shots in a row, each after one
  that pocketed a ball and kept the player at the table, within a frame.

Appending is safe: the lines of a match go in one write at the end of the file, under a lock,
and a last line left torn by a crash is first ended, so that it stays one corrupt line (which a
reader skips) and the new lines stay whole.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from datetime import datetime
from pathlib import Path
from typing import Any

from termpool.files import MiB, data_dir, to_json

from .players import LEVELS

FILE_NAME = "history.jsonl"
VERSION = 1
MAX_READ = 16 * MiB  # a longer history is read from its end (some 50,000 matches back)
RESULTS = ("won", "lost", "unfinished", "practice")
COUNTS = ("race", "won", "lost", "shots", "pots", "potting_shots", "fouls", "break_runs",
          "longest_run")
MAX_COUNT = 10 ** 9


def history_path(env: Mapping[str, str] | None = None) -> Path:
    return data_dir(env) / FILE_NAME


# ------------------------------------------------------------------------- from a match


def _pocketed(rec: dict) -> int:
    """Object balls the shot pocketed (the engine's final states)."""
    return sum(1 for b in rec["final"] if b["id"] != "cue" and b.get("state") == "pocketed")


def player_figures(history: list[dict], player: int) -> dict[str, int]:
    """shots, pots, potting_shots, fouls, break_runs and longest_run of one player, from a
    match's shot records (`Match.history`)."""
    out = dict.fromkeys(("shots", "pots", "potting_shots", "fouls", "break_runs",
                         "longest_run"), 0)
    run = 0
    prev = None
    for rec in history:
        outcome = rec["outcome"]
        foul = outcome["foul"] is not None
        # Balls down on a push-out stay down but are not the player's pots (9-ball).
        pots = 0 if foul or rec["shot"].get("push_out") else _pocketed(rec)
        if rec["player"] == player:
            goes_on = (prev is not None and prev["player"] == player
                       and prev["frame"] == rec["frame"] and prev["outcome"]["continue_turn"]
                       and _pocketed(prev) and prev["outcome"]["foul"] is None)
            run = run + pots if goes_on else pots
            out["longest_run"] = max(out["longest_run"], run)
            out["shots"] += 1
            out["fouls"] += foul
            out["pots"] += pots
            out["potting_shots"] += pots > 0
        prev = rec
    for frame in sorted({rec["frame"] for rec in history}):
        recs = [r for r in history if r["frame"] == frame]
        if (recs[0]["scene"]["game"].get("break") and recs[-1]["outcome"]["winner"] == player
                and all(r["player"] == player for r in recs)):
            out["break_runs"] += 1
    return out


def match_lines(match, cpu: tuple[bool, bool], level: str | None,
                when: datetime | None = None, sides: tuple[int, ...] = (0, 1),
                online: bool = False) -> list[dict[str, Any]]:
    """The history lines of a match: one per player of `sides` (one in practice). `cpu`:
    which players are the computer; `level`: its level. (An online match keeps only the
    side of this screen's player: the other's is in their own history.)"""
    when = datetime.now().astimezone() if when is None else when
    practice = match.mode == "practice"
    lines = []
    for p in (0,) if practice else sides:
        figures = player_figures(match.history, p)
        if practice:
            result = "practice"
        elif match.winner is None:
            result = "unfinished"
        else:
            result = "won" if match.winner == p else "lost"
        shots = figures["shots"]
        lines.append({
            "v": VERSION, "date": when.isoformat(timespec="seconds"), "mode": match.mode,
            "player": match.players[p], "side": p, "cpu": bool(cpu[p]),
            "opponent": None if practice else match.players[1 - p],
            "level": level if any(cpu) and not practice else None,
            "race": match.frames, "won": 0 if practice else match.scores[p],
            "lost": 0 if practice else match.scores[1 - p], "result": result, **figures,
            "pot_rate": round(figures["potting_shots"] / shots, 4) if shots else 0.0,
            **({"online": True, "match": f"{match.seed:x}"} if online and not practice
               else {}),
            **({"forfeit": True} if match.conceded is not None else {}),
        })
    return lines


# ------------------------------------------------------------------------------- writing


def append_lines(path: Path, lines: list[dict]) -> None:
    """Append `lines` to the history file (created, with its directory, if need be) in one
    write under a lock; a torn last line is ended first. Raises OSError."""
    import fcntl

    data = "".join(to_json(line) + "\n" for line in lines).encode("ascii")
    path.parent.mkdir(parents=True, exist_ok=True)
    fd = os.open(path, os.O_RDWR | os.O_APPEND | os.O_CREAT, 0o666)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
        except OSError:
            pass  # a file system without locks: the single append below still holds
        size = os.fstat(fd).st_size
        if size and os.pread(fd, 1, size - 1) != b"\n":
            data = b"\n" + data
        while data:
            data = data[os.write(fd, data):]
        os.fsync(fd)
    finally:
        os.close(fd)


class Recorder:
    """Adds each match to the history once, when it ends or is left. A write that fails is
    one warning line for the whole session; the game goes on."""

    def __init__(self, path: Path | None = None, env: Mapping[str, str] | None = None) -> None:
        self.path = history_path(env) if path is None else Path(path)
        self._added: list = []  # the matches already added (kept, so ids are not reused)
        self._warned = False

    def add(self, match, cpu: tuple[bool, bool], level: str | None,
            when: datetime | None = None, sides: tuple[int, ...] = (0, 1),
            online: bool = False) -> str | None:
        """Add `match` (nothing for one without shots, or already added), the lines of its
        players of `sides`; the warning line when the file cannot be written and none was
        given yet, else None."""
        if match is None or not match.history or any(m is match for m in self._added):
            return None
        self._added.append(match)
        try:
            append_lines(self.path, match_lines(match, cpu, level, when, sides, online))
        except OSError as e:
            if self._warned:
                return None
            self._warned = True
            return (f"cannot add the match to the history '{self.path}': "
                    f"{e.strerror or e}; the game goes on without it")
        return None


# ------------------------------------------------------------------------------- reading


def _name(v: Any) -> bool:
    return isinstance(v, str) and 0 < len(v) <= 64 and v.isprintable()


def check_line(d: Any) -> dict:
    """A parsed history line, checked; ValueError naming the first field that is wrong."""
    if not isinstance(d, dict):
        raise ValueError("not an object")
    if d.get("v") != VERSION:
        raise ValueError("v: not a version this termpool reads")
    from termpool.rules.common import MODES

    checks = {
        "date": lambda v: isinstance(v, str) and len(v) <= 40,
        "mode": lambda v: v in MODES,
        "player": _name,
        "side": lambda v: type(v) is int and v in (0, 1),
        "cpu": lambda v: isinstance(v, bool),
        "opponent": lambda v: v is None or _name(v),
        "level": lambda v: v is None or v in LEVELS,
        "result": lambda v: v in RESULTS,
        "pot_rate": lambda v: type(v) in (int, float) and 0 <= v <= 1,
        **{k: (lambda v: type(v) is int and 0 <= v <= MAX_COUNT) for k in COUNTS},
    }
    if "online" in d and d["online"] is not True:
        raise ValueError("online: not a valid value")
    if "match" in d and not (isinstance(d["match"], str) and 0 < len(d["match"]) <= 32):
        raise ValueError("match: not a valid value")
    if "forfeit" in d and d["forfeit"] is not True:
        raise ValueError("forfeit: not a valid value")
    for key, ok in checks.items():
        if key not in d:
            raise ValueError(f"missing '{key}'")
        if not ok(d[key]):
            raise ValueError(f"{key}: not a valid value")
    if d["potting_shots"] > d["shots"] or d["fouls"] > d["shots"] or d["pots"] < \
            d["potting_shots"]:
        raise ValueError("shots, pots and fouls do not add up")
    return d


def read_history(path: Path) -> tuple[list[dict], str | None, bool]:
    """The history's lines, oldest first, one warning line (None: nothing to say), and
    whether the file could be read. A missing file is an empty history; corrupt lines are
    skipped and counted; a file that cannot be read is an empty history and the warning; one
    larger than MAX_READ is read from its end."""
    try:
        with open(path, "rb") as f:
            size = os.fstat(f.fileno()).st_size
            cut = size > MAX_READ
            if cut:
                f.seek(size - MAX_READ)
            data = f.read(MAX_READ)
    except FileNotFoundError:
        return [], None, True
    except OSError as e:
        return [], f"cannot read the history '{path}': {e.strerror or e}", False
    raw_lines = data.split(b"\n")
    if cut:
        raw_lines = raw_lines[1:]  # the first is what is left of a line cut by the seek
    lines, bad = [], []
    for n, raw in enumerate(raw_lines, 1):
        if not raw.strip():
            continue
        try:
            lines.append(check_line(json.loads(raw.decode("utf-8"))))
        except (ValueError, RecursionError):
            bad.append(n)
    notes = []
    if cut:
        notes.append(f"larger than {MAX_READ // MiB} MiB: only its last {MAX_READ // MiB} MiB "
                     "is counted")
    if bad:
        where = "" if cut else f" (line {bad[0]}{' first' if len(bad) > 1 else ''})"
        notes.append(f"{len(bad)} corrupt {'line' if len(bad) == 1 else 'lines'} "
                     f"skipped{where}")
    return lines, (f"history '{path}': {'; '.join(notes)}" if notes else None), True


# ------------------------------------------------------------------------------ summing up

GROUPS = (*LEVELS, "player", "online", "practice")  # whom the player played
LAST = 20  # matches listed (and charted) in the summary


def group_of(line: dict) -> str:
    """Whom a line's player played: the computer's level, "player" (at the same keyboard),
    "online" or "practice"."""
    if line["mode"] == "practice":
        return "practice"
    if line.get("online"):
        return "online"
    return line["level"] if line["level"] is not None else "player"


def totals(lines: list[dict]) -> dict[str, Any]:
    """Matches, results, frames and the figures summed over `lines` (the longest run: the
    longest of them); pot_rate over all their shots."""
    out: dict[str, Any] = {"matches": len(lines)}
    for r in ("won", "lost", "unfinished"):
        out[r] = sum(line["result"] == r for line in lines)
    out["frames_won"] = sum(line["won"] for line in lines)
    out["frames_lost"] = sum(line["lost"] for line in lines)
    for k in ("shots", "pots", "potting_shots", "fouls", "break_runs"):
        out[k] = sum(line[k] for line in lines)
    out["longest_run"] = max((line["longest_run"] for line in lines), default=0)
    out["pot_rate"] = round(out["potting_shots"] / out["shots"], 4) if out["shots"] else 0.0
    return out


def summary(lines: list[dict]) -> dict[str, Any]:
    """What the Stats screen and `termpool stats` show: player 1's lines (you, against the
    computer and in practice; the first player of a two-player game) and the lines of matches
    played online (the file's only line of such a match, either side), so that each match
    counts once (a match played on after a dropped connection: its last line); the other
    player's lines are in the file, for the record. In all, per
    opponent (GROUPS: only those played), and the last LAST matches, oldest first."""
    mine = [line for line in lines
            if not line["cpu"] and (line["side"] == 0 or line.get("online"))]
    last = {line["match"]: k for k, line in enumerate(mine) if "match" in line}
    mine = [line for k, line in enumerate(mine) if last.get(line.get("match"), k) == k]
    per = {g: totals([ln for ln in mine if group_of(ln) == g]) for g in GROUPS}
    return {"all": totals(mine), "per_opponent": {g: t for g, t in per.items() if t["matches"]},
            "last": mine[-LAST:]}
