"""The history of play: figures from a match's records, the file (appended, read, tolerated
when corrupt or unwritable), the summary, `termpool stats` and the Stats screen."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from datetime import UTC, datetime, timedelta
from pathlib import Path

import pytest
from unprivileged import as_nobody

from termpool.game import Match, Shot
from termpool.game import history as h
from termpool.ui.stats import chart_lines, stats_lines

ROOT = Path(__file__).resolve().parent.parent
WHEN = datetime(2026, 11, 27, 13, 8, tzinfo=UTC)


def rec(player: int, frame: int = 1, pots: int = 0, foul: bool = False, goes_on: bool = False,
        brk: bool = False, winner: int | None = None, push_out: bool = False) -> dict:
    """A shot record with what the figures read: who shot (and whether as a push-out), the
    balls it left pocketed (and one left on the table), the referee's verdict."""
    final = [{"id": "cue", "state": "pocketed" if foul else "stationary"},
             *({"id": str(k + 1), "state": "pocketed"} for k in range(pots)),
             {"id": "15", "state": "stationary"}]
    return {"player": player, "frame": frame, "final": final, "scene": {"game": {"break": brk}},
            "shot": {"push_out": push_out},
            "outcome": {"foul": "scratch" if foul else None, "continue_turn": goes_on,
                        "winner": winner}}


# ------------------------------------------------------------------------------ figures

def test_pots_count_only_object_balls_on_shots_without_a_foul() -> None:
    f = h.player_figures([rec(0, pots=2, goes_on=True), rec(0, pots=3, foul=True),
                          rec(1, pots=1)], 0)
    assert (f["shots"], f["pots"], f["potting_shots"], f["fouls"]) == (2, 2, 1, 1)


def test_balls_down_on_a_push_out_are_no_pots() -> None:
    """A push-out's pocketed balls stay down but are "not counted": the shot counts, they
    do not (nor start a run)."""
    f = h.player_figures([rec(0, pots=1, push_out=True), rec(0, pots=1, goes_on=True)], 0)
    assert (f["shots"], f["pots"], f["potting_shots"], f["longest_run"]) == (2, 1, 1, 1)


def test_a_run_is_the_balls_of_consecutive_potting_shots_within_a_frame() -> None:
    history = [rec(0, pots=2, goes_on=True, brk=True), rec(0, pots=1, goes_on=True),
               rec(0, pots=0),  # a miss ends it at 3
               rec(1, pots=1, goes_on=True), rec(1, pots=1, goes_on=True, winner=1),
               rec(1, frame=2, pots=1, goes_on=True, brk=True),  # a new frame: a new run
               rec(1, frame=2, pots=1, foul=True),  # balls on a foul are no part of it
               rec(0, frame=2, pots=1, goes_on=True), rec(0, frame=2, pots=2, goes_on=True),
               rec(0, frame=2, pots=1, winner=0)]
    assert h.player_figures(history, 0)["longest_run"] == 4
    assert h.player_figures(history, 1)["longest_run"] == 2


def test_a_practice_run_ends_at_a_shot_that_pots_nothing() -> None:
    history = [rec(0, pots=1, goes_on=True), rec(0, pots=1, goes_on=True),
               rec(0, pots=0, goes_on=True), rec(0, pots=1, goes_on=True)]
    assert h.player_figures(history, 0)["longest_run"] == 2


def test_a_break_and_run_is_a_frame_broken_and_won_with_no_shot_by_the_other() -> None:
    won = [rec(0, brk=True, pots=1, goes_on=True), rec(0, pots=1, winner=0)]
    assert h.player_figures(won, 0)["break_runs"] == 1
    assert h.player_figures([rec(0, brk=True, pots=1, winner=0)], 0)["break_runs"] == 1
    other_shot = [rec(0, brk=True), rec(1), rec(0, pots=1, winner=0)]
    assert h.player_figures(other_shot, 0)["break_runs"] == 0
    lost = [rec(0, brk=True, pots=1, goes_on=True), rec(0, pots=1, winner=1)]  # the 8 early
    assert h.player_figures(lost, 0)["break_runs"] == 0
    two_frames = [*won, *(dict(r, frame=2) for r in won)]
    assert h.player_figures(two_frames, 0)["break_runs"] == 2


def play_out(m: Match, shot: Shot) -> None:
    if m.ball_in_hand:
        m.place_cue(*m.table.head_spot)
    m.begin(shot).finish()


def test_a_real_matchs_figures_agree_with_its_records() -> None:
    m = Match("8ball", seed=3, players=("Ann", "Bob"))
    for k in range(8):
        play_out(m, Shot(speed=7.0 if k == 0 else 2.5, angle=(37.0 * k) % 360.0))
    figures = [h.player_figures(m.history, p) for p in (0, 1)]
    assert sum(f["shots"] for f in figures) == len(m.history)
    assert sum(f["fouls"] for f in figures) == sum(r["outcome"]["foul"] is not None
                                                   for r in m.history)
    down = sum(not m.on_table[m.index(b)] for b in m.ids if b != "cue")
    legal = sum(f["pots"] for f in figures)
    assert legal <= down  # balls pocketed on fouls stay down but are nobody's pots
    assert figures[0]["shots"] >= 1 and figures[0]["longest_run"] <= legal


def test_match_lines_one_per_player_with_result_opponent_and_level() -> None:
    m = Match("9ball", seed=1, players=("You", "Computer"), frames=2)
    play_out(m, Shot(speed=8.0, angle=0.0))
    you, cpu = h.match_lines(m, (False, True), "hard", WHEN)
    assert you["player"] == "You" and you["opponent"] == "Computer" and not you["cpu"]
    assert cpu["player"] == "Computer" and cpu["opponent"] == "You" and cpu["cpu"]
    assert (you["side"], cpu["side"]) == (0, 1)
    assert you["level"] == cpu["level"] == "hard" and you["race"] == 2
    assert you["result"] == cpu["result"] == "unfinished"
    assert you["date"] == "2026-11-27T13:08:00+00:00" and you["shots"] == 1
    m.winner, m.scores = 1, [1, 2]
    you, cpu = h.match_lines(m, (False, False), "hard", WHEN)
    assert (you["result"], you["won"], you["lost"]) == ("lost", 1, 2)
    assert (cpu["result"], cpu["won"], cpu["lost"]) == ("won", 2, 1)
    assert you["level"] is None  # two players: no computer's level
    p = Match("practice", seed=1, players=("Ann", "Ann"))
    play_out(p, Shot(speed=3.0, angle=0.0))
    (only,) = h.match_lines(p, (False, False), "normal", WHEN)
    assert only["result"] == "practice" and only["opponent"] is None and only["level"] is None
    for line in (you, cpu, only):
        assert h.check_line(json.loads(json.dumps(line))) == line


# ------------------------------------------------------------------------------ the file

def line(**kw) -> dict:
    base = {"v": 1, "date": WHEN.isoformat(), "mode": "8ball", "player": "You", "side": 0,
            "cpu": False,
            "opponent": "Computer", "level": "normal", "race": 1, "won": 1, "lost": 0,
            "result": "won", "shots": 10, "pots": 5, "potting_shots": 4, "pot_rate": 0.4,
            "fouls": 1, "break_runs": 0, "longest_run": 3}
    return {**base, **kw}


def test_lines_are_appended_and_read_back_in_order(tmp_path) -> None:
    path = tmp_path / "deep" / "history.jsonl"  # the directory is made
    h.append_lines(path, [line(shots=1, potting_shots=1)])
    h.append_lines(path, [line(shots=2, potting_shots=1), line(player="Zoë", side=1)])
    lines, warning, ok = h.read_history(path)
    assert ok and warning is None
    assert [x["shots"] for x in lines] == [1, 2, 10] and lines[2]["player"] == "Zoë"
    assert path.read_bytes().isascii()


def test_a_torn_last_line_is_one_corrupt_line_and_the_next_lines_stay_whole(tmp_path) -> None:
    path = tmp_path / "history.jsonl"
    h.append_lines(path, [line(shots=1, potting_shots=1)])
    with open(path, "ab") as f:
        f.write(json.dumps(line(shots=2)).encode()[:40])  # a crash mid-write
    h.append_lines(path, [line(shots=3, potting_shots=1)])
    lines, warning, ok = h.read_history(path)
    assert [x["shots"] for x in lines] == [1, 3]
    assert warning == f"history '{path}': 1 corrupt line skipped (line 2)"


@pytest.mark.parametrize("bad", [
    "{not json", "[1, 2]", "null", json.dumps(line(v=2)), json.dumps(line(mode="snooker")),
    json.dumps({k: v for k, v in line().items() if k != "fouls"}),
    json.dumps(line(shots=-1)), json.dumps(line(shots=True)), json.dumps(line(pot_rate=1.5)),
    json.dumps(line(level="expert")), json.dumps(line(result="drawn")),
    json.dumps(line(player="a\x1b[2Jb")), json.dumps(line(player="")),
    json.dumps(line(potting_shots=11)), json.dumps(line(side=2)), "\xff\xfe",
    json.dumps(line(online=True, match=7)), json.dumps(line(online=True, match="")),
    json.dumps(line(forfeit=False)),
])
def test_corrupt_lines_are_skipped_with_one_warning(tmp_path, bad) -> None:
    path = tmp_path / "history.jsonl"
    path.write_bytes(b"\n".join([json.dumps(line()).encode(),
                                 bad.encode("latin-1" if bad == "\xff\xfe" else "utf-8"),
                                 json.dumps(line()).encode(), b""]))
    lines, warning, ok = h.read_history(path)
    assert ok and len(lines) == 2
    assert warning == f"history '{path}': 1 corrupt line skipped (line 2)"


def test_many_corrupt_lines_are_still_one_warning(tmp_path) -> None:
    path = tmp_path / "history.jsonl"
    path.write_text("x\n" + json.dumps(line()) + "\ny\nz\n")
    lines, warning, _ = h.read_history(path)
    assert len(lines) == 1 and "\n" not in warning
    assert warning.endswith("3 corrupt lines skipped (line 1 first)")


def test_a_history_beyond_the_limit_is_read_from_its_end(tmp_path, monkeypatch) -> None:
    path = tmp_path / "history.jsonl"
    h.append_lines(path, [line(shots=k + 1, potting_shots=0) for k in range(100)])
    one = len(json.dumps(line(shots=50, potting_shots=0))) + 1
    monkeypatch.setattr(h, "MAX_READ", 10 * one + 5)
    lines, warning, ok = h.read_history(path)
    assert ok and [x["shots"] for x in lines] == list(range(91, 101))
    assert "only its last" in warning and "corrupt" not in warning


def test_no_file_is_an_empty_history_and_an_unreadable_one_a_warning(tmp_path) -> None:
    assert h.read_history(tmp_path / "none.jsonl") == ([], None, True)
    (tmp_path / "dir.jsonl").mkdir()
    lines, warning, ok = h.read_history(tmp_path / "dir.jsonl")
    assert lines == [] and not ok and warning.startswith("cannot read the history")


def finished_match() -> Match:
    m = Match("8ball", seed=2, players=("You", "Computer"))
    play_out(m, Shot(speed=7.0, angle=0.0))
    return m


def test_the_recorder_adds_a_match_once_and_not_one_without_shots(tmp_path) -> None:
    r = h.Recorder(tmp_path / "history.jsonl")
    m = finished_match()
    assert r.add(Match("8ball"), (False, True), "easy") is None
    assert not r.path.exists()
    assert r.add(m, (False, True), "easy", WHEN) is None
    assert r.add(m, (False, True), "easy", WHEN) is None
    lines, _, _ = h.read_history(r.path)
    assert [x["player"] for x in lines] == ["You", "Computer"]


def test_an_unwritable_history_is_one_warning_for_the_session(tmp_path) -> None:
    (tmp_path / "data").write_text("a file where the directory should be")
    r = h.Recorder(env={"XDG_DATA_HOME": str(tmp_path / "data")})
    first = r.add(finished_match(), (False, True), "easy")
    assert first is not None and "\n" not in first and "cannot add the match" in first
    assert r.add(finished_match(), (False, True), "easy") is None  # said once


def test_a_read_only_data_directory_costs_one_warning(tmp_path) -> None:
    d = tmp_path / "termpool"
    d.mkdir()
    os.chmod(d, 0o555)
    m = finished_match()
    try:
        said = as_nobody(lambda: h.Recorder(d / "history.jsonl").add(m, (False, True), "easy"))
    finally:
        os.chmod(d, 0o755)
    assert "cannot add the match" in said and "Permission denied" in said


# ------------------------------------------------------------------------------ summing up

def test_the_summary_counts_player_1_once_a_match_per_opponent() -> None:
    lines = [line(level="easy", won=2, lost=1, race=2),
             line(player="Computer", side=1, cpu=True, opponent="You", result="lost",
                  shots=50, potting_shots=40, pots=40),
             line(player="Bob", side=1, level=None, opponent="You", result="lost", shots=50),
             line(level="hard", result="lost", won=0, lost=1, shots=20, potting_shots=2,
                  pots=2, longest_run=7),
             line(level=None, opponent="Bob", result="unfinished", won=0, lost=0),
             line(mode="practice", level=None, opponent=None, result="practice", won=0,
                  lost=0, shots=30, potting_shots=15, pots=20)]
    s = h.summary(lines)
    a = s["all"]
    assert (a["matches"], a["won"], a["lost"], a["unfinished"]) == (4, 1, 1, 1)
    assert (a["shots"], a["potting_shots"]) == (70, 25) and a["pot_rate"] == round(25 / 70, 4)
    assert a["longest_run"] == 7 and (a["frames_won"], a["frames_lost"]) == (2, 2)
    assert list(s["per_opponent"]) == ["easy", "hard", "player", "practice"]
    assert s["per_opponent"]["hard"]["pot_rate"] == 0.1
    assert len(s["last"]) == 4 and all(x["side"] == 0 for x in s["last"])


def test_an_online_match_played_on_after_a_drop_counts_once_by_its_last_line() -> None:
    def online(match: str, **kw) -> dict:
        return line(level=None, opponent="Bob", online=True, match=match, **kw)

    lines = [online("1a", result="unfinished", won=0, lost=0, shots=4, potting_shots=1,
                    pots=1),
             online("2b", result="lost", won=0, lost=1),  # another match, between them
             online("1a", result="won", won=1, lost=0, shots=9, potting_shots=3, pots=3)]
    s = h.summary(lines)
    assert (s["all"]["matches"], s["all"]["won"], s["all"]["unfinished"]) == (2, 1, 0)
    assert s["all"]["shots"] == 10 + 9
    assert s["last"] == [lines[1], lines[2]]


def test_the_summary_lists_the_last_twenty_oldest_first() -> None:
    lines = [line(shots=k + 1, potting_shots=0) for k in range(25)]
    assert [x["shots"] for x in h.summary(lines)["last"]] == list(range(6, 26))


def test_the_chart_draws_each_rate_in_eighths_of_a_row() -> None:
    chart = chart_lines([1.0, 0.0, 0.5, 0.3], ["e", "n", "h", "p"], rows=4)
    bars = [row[6:] for row in chart[:4]]  # top row first, after the axis
    cols = ["".join(r[1 + 2 * k] if len(r) > 1 + 2 * k else " " for r in bars)
            for k in range(4)]
    assert cols[0] == "████" and cols[1] == "    "
    assert cols[2] == "  ██"  # half: the two lower rows
    assert cols[3] == "  ▂█"  # 0.3 of 4 rows: one full row and 2 eighths (1.2 rows)
    assert chart[0].startswith("100%") and chart[2].startswith(" 50%")
    assert chart[-1].split() == ["e", "n", "h", "p"]


def test_the_stats_text_fits_the_box_and_names_every_opponent() -> None:
    lines = [line(level=lv, date=(WHEN + timedelta(days=k)).isoformat())
             for k, lv in enumerate(["easy", "normal", "hard", None] * 6)]
    text = stats_lines(h.summary(lines))
    assert max(len(x) for x in text) <= 74
    body = "\n".join(text)
    for words in ("computer, easy", "computer, normal", "computer, hard", "a second player"):
        assert words in body
    assert "24 matches: won 24" in body and "the last 20 matches" in body
    # what the pot rate counts is said where it is first given
    assert "pot rate 40% (the shots that pocketed a ball)" in " ".join(text)
    assert stats_lines(h.summary([])) == [stats_lines(h.summary([]))[0]]


def test_a_long_name_gives_way_to_the_opponent_and_level_in_the_last_matches() -> None:
    for level in ("hard", "normal"):
        text = stats_lines(h.summary([line(player="Bartholomew Q. L", level=level)]))
        row = next(x for x in text if x.startswith(WHEN.isoformat()[:10]))
        assert f"… v Computer ({level})" in row and " Ba" in row, row
    text = stats_lines(h.summary([line(player="Ann", level="hard")]))
    assert any("Ann v Computer (hard)" in x for x in text)


def test_the_chart_s_key_names_only_the_marks_it_shows() -> None:
    """Games against the computer alone: no word of online games or a second player; an
    online one added: its mark is explained."""
    against = [line(level=lv, date=(WHEN + timedelta(days=k)).isoformat())
               for k, lv in enumerate(["easy", "hard", "easy"])]
    body = " ".join(stats_lines(h.summary(against)))  # (the key may wrap)
    assert "e h: the computer's level)" in body
    assert "online" not in body and "second player" not in body
    online = line(level=None, online=True, date=(WHEN + timedelta(days=9)).isoformat())
    body = " ".join(stats_lines(h.summary([*against, online])))
    assert "e h: the computer's level, o: online)" in body


# --------------------------------------------------------------------- the command, the game

def stats_cli(*args: str, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "termpool", "stats", *args],
                          capture_output=True, text=True, cwd=ROOT, timeout=60,
                          env={**os.environ, "PYTHONPATH": str(ROOT), **(env or {})})


def test_termpool_stats_prints_the_screens_text_and_json() -> None:
    path = h.history_path()
    h.append_lines(path, [line(level="hard"), line(player="Computer", side=1, cpu=True),
                          line(mode="9ball", level="easy", result="lost", won=0, lost=1)])
    with open(path, "ab") as f:
        f.write(b"torn")
    p = stats_cli()
    assert p.returncode == 0
    assert p.stdout.splitlines() == stats_lines(h.summary(h.read_history(path)[0]))
    assert p.stderr == (f"termpool: warning: history '{path}': 1 corrupt line skipped "
                        "(line 4)\n")
    p = stats_cli("--json")
    data = json.loads(p.stdout)
    assert data["file"] == str(path)
    assert data["all"]["matches"] == 2 and list(data["per_opponent"]) == ["easy", "hard"]


def test_termpool_stats_without_a_history_and_with_an_unreadable_one(tmp_path) -> None:
    p = stats_cli()
    assert p.returncode == 0 and p.stdout.startswith("No matches played yet") and not p.stderr
    h.history_path().parent.mkdir(parents=True)
    h.history_path().mkdir()
    p = stats_cli()
    assert p.returncode == 1 and p.stderr.count("\n") == 1 and "cannot read" in p.stderr


def headless(*args: str, keys: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "termpool", "play", "--headless", "--keys",
                           "-", *args], input=keys, capture_output=True, text=True, cwd=ROOT,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=120)


def test_a_game_left_mid_match_is_in_the_history() -> None:
    p = headless("--mode", "practice", "--seed", "4", keys="enter space-hold 0.8 wait 20 q y")
    # (the one line said: where its record went)
    assert p.returncode == 0 and p.stderr.startswith("termpool: record saved to ")
    assert p.stderr.count("\n") == 1
    (only,) = h.read_history(h.history_path())[0]
    assert only["mode"] == "practice" and only["shots"] == 1 and only["result"] == "practice"


def test_an_unwritable_history_costs_the_player_one_line(tmp_path) -> None:
    data = tmp_path / "data"
    data.write_text("not a directory")
    p = subprocess.run([sys.executable, "-m", "termpool", "play", "--headless", "--keys", "-",
                        "--mode", "practice", "--seed", "4", "--no-record"],  # (its own line)
                       input="enter space-hold 0.8 wait 20 q y", capture_output=True, text=True,
                       cwd=ROOT, timeout=120,
                       env={**os.environ, "PYTHONPATH": str(ROOT), "XDG_DATA_HOME": str(data)})
    assert p.returncode == 0, p.stderr
    assert p.stderr.count("\n") == 1 and "cannot add the match to the history" in p.stderr
    assert "You to shoot" in p.stdout or "ball in hand" in p.stdout  # the game went on


def test_the_end_of_a_match_adds_it_and_the_menu_shows_it() -> None:
    from termpool.ui.app import App, Options
    from termpool.ui.headless import screen_text
    from termpool.ui.keys import Key
    from termpool.ui.phases.turn import shoot, start_turn
    from termpool.ui.state import Phase, menu_entries

    app = App(Options(mode="9ball", opponent="human", colors="mono", seed=0),
              history=h.Recorder())
    m = app.state.match
    m.ball_in_hand = None
    nine = m.index("9")
    for k, b in enumerate(m.ids):  # the 9 alone, straight in front of the cue ball
        m.on_table[k] = b in ("cue", "9")
    m.state = m.state.__class__(mode="9ball", shooter=0, pocketed=tuple("12345678"))
    c = m.index("cue")
    m.pos[nine] = (m.table.length - 0.3, m.table.width - 0.3)
    m.pos[c] = (m.table.length - 0.8, m.table.width - 0.8)
    app.state = start_turn(app.state)
    # With draw: the cue ball stays out of the pocket.
    app.state = shoot(app.state, 2.5, 45.0, 0.0, -0.4)
    while app.state.phase is Phase.RUN:
        app.tick(app.state.now + 1.0)
    assert app.state.phase is Phase.OVER and m.winner == 0
    lines = h.read_history(h.history_path())[0]
    assert [(x["player"], x["result"]) for x in lines] == [("Player 1", "won"),
                                                           ("Player 2", "lost")]
    app.key(Key("m"), 100.0)  # to the menu: not added again
    assert len(h.read_history(h.history_path())[0]) == 2
    app.key(Key(str([x[0] for x in menu_entries(app.state)].index("Stats") + 1)), 101.0)
    text = screen_text(app.cells(80, 24)[0])
    assert "1 match: won 1" in text and "a second player" in text
    app.key(Key("x"), 102.0)
    assert app.state.box is None


def test_every_level_of_the_computer_is_a_history_line_and_a_stats_row() -> None:
    from termpool.game.players import LEVELS

    lines = [h.check_line(line(level=lv)) for lv in LEVELS]
    text = "\n".join(stats_lines(h.summary(lines)))
    for lv in LEVELS:
        assert f"computer, {lv}" in text
