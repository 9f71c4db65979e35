"""The history of play in words: what the Stats screen shows and `termpool stats` prints.

`stats_lines(summary)` (a `game.history.summary`) gives the text, at most WIDTH columns: the
totals, the totals per opponent (the computer's level, a second player, practice), a chart of
the pot rate over the last matches, and those matches one a line.
"""

from __future__ import annotations

import textwrap
from typing import Any

from termpool.game.history import group_of

WIDTH = 74  # what the Stats box holds on an 80-column terminal
MATCH_COLS = 23  # the last matches' "match" column: "You v Computer (normal)"
GROUP_WORDS = {"easy": "computer, easy", "normal": "computer, normal", "hard": "computer, hard",
               "pro": "computer, pro", "player": "a second player", "online": "someone online",
               "practice": "practice"}
GROUP_MARK = {"easy": "e", "normal": "n", "hard": "h", "pro": "P", "player": "p",
              "online": "o", "practice": "·"}
CHART_ROWS = 4
BLOCKS = " ▁▂▃▄▅▆▇█"
GAMES = {"8ball": "8-ball", "9ball": "9-ball", "practice": "practice"}


# What the chart's marks mean, for the groups it shows (in GROUP_MARK's order).
LEGEND = (({"easy", "normal", "hard", "pro"}, "the computer's level"),
          ({"player"}, "a second player"), ({"online"}, "online"), ({"practice"}, "practice"))


def legend(groups: set[str]) -> str:
    """The chart's key for the marks of `groups` only: a chart of games against the computer
    has no word for online ones."""
    parts = []
    for members, words in LEGEND:
        marks = " ".join(GROUP_MARK[g] for g in GROUP_MARK if g in members and g in groups)
        if marks:
            parts.append(f"{marks}: {words}")
    return ", ".join(parts)


def pct(rate: float) -> str:
    return f"{round(100 * rate)}%"


def _cut(text: str, width: int) -> str:
    return text if len(text) <= width else text[:width - 1] + "…"


def _plural(n: int, word: str, words: str | None = None) -> str:
    return f"{n} {word if n == 1 else words or word + 's'}"


def chart_lines(rates: list[float], marks: list[str], rows: int = CHART_ROWS) -> list[str]:
    """A bar chart of rates in [0, 1], one two-cell column each, oldest left: `rows` rows of
    eighth blocks with a 0-100% axis, and the marks under the bars."""
    out = []
    for r in range(rows, 0, -1):  # row r holds rates from (r - 1) / rows to r / rows
        label = f"{100 * r // rows:>3}%" if r in (rows, rows // 2) else "    "
        cells = []
        for rate in rates:
            eighths = round(rate * rows * 8) - (r - 1) * 8
            cells.append(BLOCKS[max(0, min(8, eighths))])
        out.append(f"{label} ┤" + "".join(f" {c}" for c in cells).rstrip())
    out.append("  0% └" + "─" * (2 * len(rates) + 1))
    out.append("      " + "".join(f" {m}" for m in marks))
    return out


def _totals_row(label: str, t: dict[str, Any], practice: bool = False) -> str:
    won_lost = "-" if practice else f"{t['won']}-{t['lost']}"
    frames = "-" if practice else f"{t['frames_won']}-{t['frames_lost']}"
    bnr = "-" if practice else str(t["break_runs"])
    return (f"{_cut(label, 16):<16} {t['matches']:>7} {won_lost:>8} {frames:>7} "
            f"{t['shots']:>6} {pct(t['pot_rate']):>8} {t['fouls']:>5} {bnr:>3} "
            f"{t['longest_run']:>4}")


def _match_row(line: dict[str, Any]) -> str:
    if line["mode"] == "practice":
        who, result = line["player"], "-"
    else:
        them = line["opponent"]
        if line["level"] is not None and not line["cpu"]:
            them = f"{them} ({line['level']})"
        # The player is the same on every row (this screen's); the opponent and the
        # computer's level are what tell the rows apart, so the player's name gives way first.
        who = f"{_cut(line['player'], max(MATCH_COLS - 3 - len(them), 2))} v {them}"
        word = {"won": "won", "lost": "lost", "unfinished": "left"}[line["result"]]
        result = f"{word} {line['won']}-{line['lost']}"
    who = _cut(who, MATCH_COLS)
    return (f"{line['date'][:10]:<10} {GAMES[line['mode']]:<8} {who:<{MATCH_COLS}} "
            f"{result:<9} {line['shots']:>5} {pct(line['pot_rate']):>4} {line['fouls']:>5} "
            f"{line['longest_run']:>3}")


def stats_lines(summary: dict[str, Any]) -> list[str]:
    """The text of the stats (see the module docstring); one line when there is none."""
    a = summary["all"]
    if not a["matches"]:
        return ["No matches played yet: a match is added here when it ends or is left."]
    practice = summary["per_opponent"].get("practice", {"matches": 0})["matches"]
    head = (f"{_plural(a['matches'], 'match', 'matches')}: won {a['won']}, lost {a['lost']}, "
            f"left {a['unfinished']}, practice {practice}; frames {a['frames_won']}-"
            f"{a['frames_lost']}. {_plural(a['shots'], 'shot')}, {_plural(a['pots'], 'pot')}, "
            f"pot rate {pct(a['pot_rate'])} (the shots that pocketed a ball); "
            f"{_plural(a['fouls'], 'foul')}, "
            f"{_plural(a['break_runs'], 'break-and-run')}, longest run {a['longest_run']}.")
    out = [*textwrap.wrap(head, WIDTH, break_on_hyphens=False), "",
           f"{'against':<16} {'matches':>7} {'won-lost':>8} {'frames':>7} {'shots':>6} "
           f"{'pot rate':>8} {'fouls':>5} {'B&R':>3} {'run':>4}"]
    for group, t in summary["per_opponent"].items():
        out.append(_totals_row(GROUP_WORDS[group], t, group == "practice"))
    last = summary["last"]
    chart_head = (f"Pot rate, the last {_plural(len(last), 'match', 'matches')} (oldest left; "
                  f"{legend({group_of(line) for line in last})})")
    out += ["", *textwrap.wrap(chart_head, WIDTH)]
    out += chart_lines([line["pot_rate"] for line in last],
                       [GROUP_MARK[group_of(line)] for line in last])
    out += ["", f"{'date':<10} {'game':<8} {'match':<{MATCH_COLS}} {'result':<9} {'shots':>5} "
                f"{'pot':>4} {'fouls':>5} {'run':>3}"]
    out += [_match_row(line) for line in reversed(last)]  # the newest first
    return out

