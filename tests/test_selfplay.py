"""`termpool selfplay`: the figures, their keys, determinism, --jobs, records, Ctrl-C, errors.

Games here are tiny (9-ball, a few shots each, a small candidate budget): the figures of
real games are measured with the command itself (docs/ai.md)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from termpool import ai
from termpool.cli import main
from termpool.game import Match, replay
from termpool.rules.events import summarize
from termpool.selfplay import games as sp

ROOT = Path(__file__).resolve().parent.parent
TINY = ("--mode", "9ball", "--candidates", "8", "--max-shots", "4", "--seed", "5")
KEYS = {"games", "mode", "levels", "wins", "pot_rate", "fouls_per_game", "break_and_run_rate",
        "safeties_per_game", "shots_per_game", "decision_s", "decision_s_max", "wall_s"}
PER_LEVEL = ("wins", "pot_rate", "fouls_per_game", "break_and_run_rate", "safeties_per_game",
             "decision_s", "decision_s_max")
TIMES = ("decision_s", "decision_s_max", "decision_cpu_s", "shot_decision_cpu_s",
         "shot_decision_cpu_s_max", "wall_s", "jobs")


def env() -> dict:
    e = dict(os.environ)
    e["PYTHONPATH"] = str(ROOT) + os.pathsep + e.get("PYTHONPATH", "")
    return e


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "termpool", "selfplay", *args], cwd=ROOT,
                          env=env(), capture_output=True, text=True, timeout=600)


def figures(*args: str) -> dict:
    p = cli(*TINY, "--json", *args)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


def untimed(r: dict) -> dict:
    return {k: v for k, v in r.items() if k not in TIMES}


def test_json_has_every_figure_per_level():
    r = figures("--games", "2", "--levels", "easy,normal", "--jobs", "1")
    assert KEYS <= set(r)
    assert r["games"] == 2 and r["mode"] == "9ball" and r["levels"] == ["easy", "normal"]
    for k in PER_LEVEL:
        assert set(r[k]) == {"easy", "normal"}, k
    assert sum(r["wins"].values()) + r["undecided"] == 2
    assert 0 < r["shots_per_game"] <= 4
    for lv in ("easy", "normal"):
        assert 0 <= r["decision_s"][lv] <= r["decision_s_max"][lv]
        assert r["pot_rate"][lv] is None or 0 <= r["pot_rate"][lv] <= 1
    assert r["wall_s"] > 0 and r["interrupted"] is False


def test_same_seed_same_figures_and_jobs_do_not_change_them():
    args = ("--games", "2", "--levels", "hard,easy")
    one = figures(*args, "--jobs", "1")
    assert untimed(figures(*args, "--jobs", "1")) == untimed(one)
    assert untimed(figures(*args, "--jobs", "2")) == untimed(one)
    other = figures(*args, "--jobs", "1", "--seed", "6")
    assert untimed(other) != untimed(one)  # the seed matters (racks, errors)


def test_one_level_on_both_sides_is_pooled():
    r = figures("--games", "1", "--levels", "easy,easy", "--jobs", "1")
    assert r["levels"] == ["easy", "easy"]
    for k in PER_LEVEL:
        assert list(r[k]) == ["easy"], k


def test_the_table_names_the_levels_and_the_progress_bar_goes_to_stderr():
    p = cli(*TINY, "--games", "2", "--levels", "pro,easy", "--jobs", "1")
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[1].split() == ["pro", "easy"]
    assert any(line.startswith("pot rate ") for line in lines)
    assert "selfplay [" in p.stderr and "2/2 games" in p.stderr
    assert "selfplay [" not in p.stdout


def test_record_dir_keeps_every_game_as_a_replayable_match(tmp_path):
    out = tmp_path / "games"
    r = figures("--games", "2", "--levels", "normal,easy", "--jobs", "2", "--record-dir",
                str(out))
    files = sorted(out.iterdir())
    assert [f.name for f in files] == ["game-001.json", "game-002.json"]
    shots = 0
    for k, f in enumerate(files):
        data = json.loads(f.read_text())
        # The break alternates: the first level breaks the even games (player 0 breaks).
        assert data["match"]["levels"] == (["normal", "easy"] if k == 0 else ["easy", "normal"])
        assert all(s["ok"] for s in replay(data))
        assert Match.from_json(data).winner is None or data["current"]["winner"] in (0, 1)
        shots += len(data["shots"])
    assert shots == r["shots_per_game"] * 2
    # A second run into the same directory is refused unless --force.
    p = cli(*TINY, "--games", "1", "--record-dir", str(out))
    assert p.returncode == 2 and p.stderr.count("\n") == 1 and "--force" in p.stderr
    assert cli(*TINY, "--games", "1", "--record-dir", str(out), "--force").returncode == 0


@pytest.mark.parametrize("args, words", [
    (("--levels", "easy,expert"), "--levels: 'expert' is not a level"),
    (("--levels", "easy"), "--levels: must be two levels"),
    (("--levels", "easy,normal,hard"), "--levels: must be two levels"),
    (("--games", "0"), "--games"),
    (("--games", "many"), "--games"),
    (("--jobs", "0"), "--jobs"),
    (("--candidates", "4"), "--candidates"),
    (("--mode", "practice"), "--mode"),
    (("--table", "12ft"), "--table"),
    (("--seed", "-1"), "--seed"),
    (("--record-dir", "/dev/null"), "--record-dir"),
])
def test_bad_arguments_get_one_line_and_status_2(args, words, capsys):
    assert main(["selfplay", "--games", "1", *args]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("termpool: ") and words in err, err


@pytest.mark.parametrize("sig, jobs", [(signal.SIGINT, "1"), (signal.SIGINT, "2"),
                                       (signal.SIGTERM, "2")])
def test_ctrl_c_prints_the_figures_so_far(sig, jobs, tmp_path):
    p = subprocess.Popen([sys.executable, "-m", "termpool", "selfplay", *TINY, "--games",
                          "200", "--levels", "easy,normal", "--json", "--jobs", jobs,
                          "--record-dir", str(tmp_path)],
                         cwd=ROOT, env=env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    err = ""
    deadline = time.monotonic() + 300
    while "1/200 games" not in err and time.monotonic() < deadline:
        line = p.stderr.readline()
        assert line, "selfplay ended before a game was finished"
        err += line
    p.send_signal(sig)
    out, rest = p.communicate(timeout=300)
    assert p.returncode == 128 + sig, rest
    r = json.loads(out)
    assert r["interrupted"] is True
    assert 1 <= r["games"] < 200
    assert sum(r["wins"].values()) + r["undecided"] == r["games"]
    # Every game begun has its record, the unfinished ones too; the finished ones are counted.
    records = [json.loads(f.read_text()) for f in sorted(tmp_path.iterdir())]
    assert len(records) >= r["games"]
    time.sleep(3)  # no game process goes on alone: no new game file
    assert len(list(tmp_path.iterdir())) == len(records)
    for data in records:
        assert all(s["ok"] for s in replay(data))


# ---------------------------------------------------------------------------- counting


def test_a_game_s_tallies_match_its_record(monkeypatch):
    plans = []
    choose = ai.choose_shot

    def spy(*a, **k):
        plans.append(choose(*a, **k))
        return plans[-1]

    monkeypatch.setattr(ai.shots, "choose_shot", spy)
    g = sp.play_game(("easy", "normal"), mode="9ball", seed=11, candidates=8, max_shots=12)
    assert g["shots"] == len(plans) <= 12
    assert sum(t["shots"] for t in g["tallies"]) == g["shots"]
    assert [t["breaks"] for t in g["tallies"]] == [1, 0]  # player 0 breaks
    for t in g["tallies"]:
        assert len(t["decisions"]) == t["shots"]
        # The decisions in play are every one but the break's.
        assert len(t["shot_cpu"]) == t["shots"] - t["breaks"]
        assert t["pots"] <= t["pot_attempts"]


def test_pots_fouls_and_breaks_are_counted_from_the_record(monkeypatch, tmp_path):
    plans = []
    choose = ai.choose_shot

    def spy(*a, **k):
        plans.append(choose(*a, **k))
        return plans[-1]

    monkeypatch.setattr(ai.shots, "choose_shot", spy)
    path = tmp_path / "g.json"
    g = sp.play_game(("easy", "easy"), mode="9ball", seed=4, candidates=8, max_shots=10,
                     record=path)
    data = json.loads(path.read_text())
    want = [dict.fromkeys(("shots", "fouls", "pot_attempts", "pots"), 0) | {"foul_kinds": {}}
            for _ in range(2)]
    for plan, rec in zip(plans, data["shots"], strict=True):
        w = want[rec["player"]]
        w["shots"] += 1
        foul = rec["outcome"]["foul"]
        w["fouls"] += foul is not None
        if foul is not None:
            w["foul_kinds"][foul] = w["foul_kinds"].get(foul, 0) + 1
        if plan.kind in ("pot", "combo"):
            w["pot_attempts"] += 1
            ids = [b["id"] for b in rec["scene"]["balls"]]
            w["pots"] += summarize(rec["events"], ids).pocketed.get(plan.ball) == plan.pocket
    got = [{k: t[k] for k in want[0]} for t in g["tallies"]]
    assert got == want
    assert sum(w["pot_attempts"] for w in want) > 0  # the game tried pots


def test_figures_pool_a_level_over_both_sides_and_count_player_games():
    def tally(level, **kw):
        return sp._tally(level) | kw

    games = [
        {"winner": 0, "shots": 10, "tallies": [
            tally("hard", pot_attempts=4, pots=3, fouls=1, breaks=1, runs=1, decisions=[0.2],
                  foul_kinds={"scratch": 1}),
            tally("hard", pot_attempts=2, pots=1, safeties=2, kicks=1, decisions=[0.4, 0.6],
                  safety_before=[0.5, 0.2], safety_after=[0.1, 0.3],
                  safety_foul=[False, True], kick_before=[0.1], kick_after=[0.6],
                  kick_foul=[False])]},
        {"winner": None, "shots": 30, "tallies": [
            tally("hard", pot_attempts=2, pots=2, breaks=1, decisions=[1.0],
                  shot_cpu=[0.3, 0.9, 0.1]),
            tally("hard", fouls=1, foul_kinds={"no_rail": 1})]},
    ]
    r = sp.figures(games, ["hard", "hard"])
    assert r["wins"] == {"hard": 1} and r["undecided"] == 1 and r["games"] == 2
    assert r["pot_rate"]["hard"] == pytest.approx(6 / 8)
    assert r["fouls_per_game"]["hard"] == pytest.approx(2 / 4)  # four player-games
    assert r["foul_kinds"]["hard"] == {"no_rail": 1, "scratch": 1}
    assert r["safeties_per_game"]["hard"] == pytest.approx(2 / 4)
    assert r["break_and_run_rate"]["hard"] == pytest.approx(1 / 2)
    assert r["shots_per_game"] == 20
    assert r["decision_s"]["hard"] == pytest.approx(0.5)
    assert r["decision_s_max"]["hard"] == 1.0
    assert r["shot_decision_cpu_s"]["hard"] == 0.3
    assert r["shot_decision_cpu_s_max"]["hard"] == 0.9
    assert r["kicks_per_game"]["hard"] == pytest.approx(1 / 4)
    s = r["safeties"]["hard"]
    assert s["count"] == 2 and s["lowered"] == 0.5 and s["lowered_without_foul"] == 1.0
    assert s["fouls"] == 1
    k = r["kicks"]["hard"]
    assert k["count"] == 1 and k["lowered"] == 0.0 and k["opponent_chance_after"] == 0.6
    assert s["opponent_chance_before"] == pytest.approx(0.35)


def test_game_seeds_are_independent_of_order():
    seeds = [sp.game_seed(7, k) for k in range(50)]
    assert len(set(seeds)) == 50
    assert sp.game_seed(7, 3) == seeds[3] and sp.game_seed(8, 3) != seeds[3]
