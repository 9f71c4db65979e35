"""Watching a saved match: the frames of the live game again, the keys, the command, bad files."""

from __future__ import annotations

import copy
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from termpool.ui.app import App, Options
from termpool.ui.headless import play, screen_text
from termpool.ui.keys import Key, parse_script
from termpool.ui.phases.turn import start_turn
from termpool.ui.shots import DT, FAST
from termpool.ui.state import Phase
from termpool.ui.table_view import layout
from termpool.ui.watch import AIM_S, VERDICT_S, Watch

ROOT = Path(__file__).resolve().parent.parent
# Two players at 8-ball: a break that pockets two balls, a miss, then the 10 (which gives
# the stripes) and the 9 for the same player.
MATCH_KEYS = ("enter space-hold 1.3 wait 12 left*3 space-hold 0.6 wait 8 right*7 "
              "space-hold 0.8 wait 8 space-hold 0.5 wait 8")
COLS, ROWS = 80, 24


def table_mask(table, cols: int = COLS, rows: int = ROWS) -> np.ndarray:
    """The cells of the table, not the panel."""
    col, row, ncols, nrows = layout(cols, rows, table).panel_rect
    mask = np.ones((rows, cols), bool)
    mask[row:row + nrows, col:col + ncols] = False
    return mask


def capture(app, key_of, mask_of, running):
    """Wrap `app.cells` to keep the table cells of every frame drawn while a shot runs
    (`running(app)`), by key_of(app) (the shot and the frame shown)."""
    seen = {}
    cells = app.cells

    def wrapped(cols, rows):
        out = cells(cols, rows)
        if running(app):
            m = mask_of(app)
            seen[key_of(app)] = tuple(None if a is None else a[m].copy() for a in out)
        return out

    app.cells = wrapped
    return seen


@pytest.fixture(scope="module", params=["truecolor", "mono"])
def live(request):
    """A two-player 8-ball match played headless, with the table cells of every frame of
    every shot as the game drew them."""
    app = App(Options(mode="8ball", opponent="human", seed=3, colors=request.param))
    seen = capture(app, lambda a: (len(a.state.match.history) + 1, a.state.part.shown),
                   lambda a: table_mask(a.state.match.table),
                   lambda a: a.state.phase is Phase.RUN)
    play(app, parse_script(MATCH_KEYS), COLS, ROWS)
    assert app.state.phase is Phase.AIM and len(app.state.match.history) == 4
    return app, seen, request.param


def test_watched_frames_equal_the_live_frames_at_the_same_times(live) -> None:
    app, seen, depth = live
    data = app.state.match.to_json()
    watch = Watch(data, depth)
    table = watch.scenes[0][0].table
    watched = capture(watch, lambda w: (w.i + 1, w.shown), lambda w: table_mask(table),
                      lambda w: w.phase == "run")
    play(watch, [], COLS, ROWS)
    assert watch.phase == "end"
    common = set(seen) & set(watched)
    assert {n for n, _ in common} == {1, 2, 3, 4} and len(common) > 0.8 * len(seen)
    for key in sorted(common):
        for a, b in zip(seen[key], watched[key], strict=True):
            assert (a is None and b is None) or np.array_equal(a, b), key
    # Every frame the game drew, the watch draws the same at the same shot and time.
    for n, k in sorted(set(seen) - common):
        watch.go_to(n - 1)
        watch.phase, watch.shown = "run", k
        watch.cells(COLS, ROWS)
        for a, b in zip(seen[n, k], watched[n, k], strict=True):
            assert (a is None and b is None) or np.array_equal(a, b), (n, k)
    # ... the last of each shot included, and frames from different times differ (the
    # comparison can tell them apart).
    for n in (1, 2, 3, 4):
        assert max(k for m, k in seen if m == n) == len(watch.played(n - 1).frames) - 1
    assert not np.array_equal(watched[1, 10][0], watched[1, 40][0])


@pytest.fixture(scope="module")
def record() -> dict:
    """The match of `live`, played in mono."""
    app = App(Options(mode="8ball", opponent="human", seed=3, colors="mono"))
    play(app, parse_script(MATCH_KEYS), COLS, ROWS)
    return app.state.match.to_json()


def watch_for(record, **kw) -> Watch:
    return Watch(copy.deepcopy(record), kw.pop("colors", "mono"), **kw)


def run_to(w: Watch, t0: float, seconds: float) -> float:
    """Tick `w` at 60 Hz from t0 for `seconds`; the clock at the end."""
    n = round(seconds * 60)
    for k in range(n + 1):
        w.tick(t0 + k / 60)
    return t0 + n / 60


def text(w: Watch, cols: int = COLS, rows: int = ROWS) -> str:
    return screen_text(w.cells(cols, rows)[0])


def test_a_shot_is_the_stick_then_the_balls_then_the_verdict(record) -> None:
    w = watch_for(record)
    assert w.phase == "aim" and "shot 1 of 4 · Player 1 · the break" in text(w)
    assert "power 100%" in text(w)
    t = run_to(w, 0.0, AIM_S + 0.5)
    assert w.phase == "run" and abs(w.shot_clock - 0.5) <= 2 * DT
    while w.phase == "run":
        t = run_to(w, t, 1.0)
    assert w.phase == "rest"
    screen = text(w)
    assert "legal break: the 11 and the 4 pocketed; the table is open and Player 1" in screen
    run_to(w, t, VERDICT_S + 0.1)
    assert w.phase == "aim" and w.i == 1 and "shot 2 of 4 · Player 1" in text(w)


def test_space_pauses_and_resumes(record) -> None:
    w = watch_for(record)
    t = run_to(w, 0.0, AIM_S + 0.5)
    clock = w.shot_clock
    w.key(Key("space"), t)
    assert w.paused and w.wake_in(t) is None
    t = run_to(w, t, 3.0)
    assert w.shot_clock == clock and "paused" in text(w)
    w.key(Key("space"), t)
    run_to(w, t, 0.5)
    assert not w.paused and abs(w.shot_clock - clock - 0.5) <= 2 * DT


def test_arrows_step_a_shot_back_and_forward(record) -> None:
    w = watch_for(record)
    w.key(Key("right"), 0.0)
    assert (w.i, w.phase, w.shown) == (1, "aim", 0)
    run_to(w, 0.0, AIM_S + 0.5)
    assert w.phase == "run" and w.i == 1
    w.key(Key("left"), 2.0)
    assert (w.i, w.phase, w.shown) == (0, "aim", 0)
    w.key(Key("left"), 2.1)  # the first shot: back to its start
    assert (w.i, w.phase) == (0, "aim")
    for k in range(5):  # past the last shot: its end, the table at rest and the verdict
        w.key(Key("right"), 3.0 + k)
    assert w.i == 3 and w.phase == "end"
    screen = text(w)
    assert "shot 4 of 4 · Player 2" in screen
    assert "the 9 in the top side pocket: Player 2 continues" in screen
    assert "the end: the record stops here" in screen
    w.key(Key("left"), 9.0)
    assert (w.i, w.phase) == (3, "aim")
    # Stepping keeps a pause.
    w.key(Key("space"), 10.0)
    w.key(Key("left"), 10.1)
    assert w.paused and w.i == 2


def test_f_plays_at_four_times_and_again_at_one(record) -> None:
    w = watch_for(record)
    w.key(Key("f"), 0.0)
    t = run_to(w, 0.0, (AIM_S + 0.5) / FAST)
    assert w.phase == "run" and abs(w.shot_clock - 0.5) <= 2 * FAST * DT
    assert "×4" in text(w)
    w.key(Key("f"), t)
    clock = w.shot_clock
    run_to(w, t, 0.5)
    assert abs(w.shot_clock - clock - 0.5) <= 2 * DT


@pytest.mark.parametrize("key", ["q", "esc"])
def test_q_quits(record, key) -> None:
    w = watch_for(record)
    w.key(Key(key), 0.0)
    assert w.done


def test_help_shows_the_keys_and_the_rules_of_the_game_watched(record) -> None:
    w = watch_for(record)
    w.key(Key("h"), 0.0)
    screen = text(w)
    assert "Space" in screen and "back or forward one shot" in screen and "1/3" in screen
    w.key(Key("right"), 0.1)  # turns the page, does not step a shot
    assert w.i == 0 and "8-ball rules · 2/3" in text(w)
    w.key(Key("x"), 0.2)
    assert w.overlay is None and "rules" not in text(w)


def test_a_shot_that_plays_differently_from_its_record_says_so(record) -> None:
    data = copy.deepcopy(record)
    data["shots"][1]["time"] += 1.0
    w = Watch(data, "mono")
    w.key(Key("right"), 0.0)
    assert "plays differently from its record (time: recorded" in text(w, 120, 40)
    w.key(Key("left"), 0.1)
    assert "differently" not in text(w, 120, 40)


def test_a_watched_shot_takes_no_more_steps_than_its_record(record) -> None:
    """A replay's work budget is its recorded step count, watched too: a record claiming
    fewer steps than the shot takes is played that far (and the frame under way), not to the
    end, and says so."""
    from termpool.game.record import shot_scene
    from termpool.ui.watch import play_shot

    rec = copy.deepcopy(record["shots"][0])
    rec["steps"] = 30
    played = play_shot(shot_scene(rec["scene"], rec["shot"]), rec["dt"], rec)
    assert played.differs == "steps: still moving after the recorded 30 steps (a replay " \
                            "takes no more)"
    assert len(played.frames) == 30  # one step a frame at the game's dt


def test_words_from_the_file_are_shown_not_obeyed(record) -> None:
    data = copy.deepcopy(record)
    data["match"]["players"] = ["\x1b[2JAnn", "Bob\x07"]
    data["shots"][0]["outcome"]["reason"] = "player 0 \x1b]0;owned\x07 breaks"
    data["shots"][0]["outcome"]["groups"] = ["solids"]  # not the referee's form: ignored
    w = Watch(data, "truecolor")
    for k in range(3):
        w.key(Key("right"), float(k))
        w.key(Key("left"), float(k))
    w.phase = "rest"
    chars = w.cells(120, 40)[0]
    screen = screen_text(chars)
    # The verdict is the referee's on the recorded events, in the players' names as shown.
    assert "the table is open and \\x1b[2JAnn continues" in screen and "Bob\\x07" in screen
    assert "owned" not in screen  # the file's own words for it are not needed
    assert not any(ord(c) < 32 or c == "\x7f" for c in chars.ravel())


def test_a_race_shows_frames_and_the_match_winner(record) -> None:
    data = copy.deepcopy(record)
    data["match"]["frames"] = 2
    for k, winner in ((1, 1), (3, 1)):  # as if player 2 had won frames 1 and 2 here
        data["shots"][k]["outcome"]["winner"] = winner
    w = Watch(data, "mono")
    assert "frames 0/2" in text(w, 120, 40)
    for k in range(4):
        w.key(Key("right"), float(k))
    screen = text(w, 120, 40)
    assert "frames 2/2" in screen and "Player 2 wins the match 2-0" in screen


# --------------------------------------------------------------------------- in the game


def test_w_at_the_end_of_a_match_watches_it_and_q_comes_back() -> None:
    app = App(Options(mode="8ball", opponent="human", seed=3, colors="mono"))
    play(app, parse_script("enter space-hold 1.3 wait 12"), COLS, ROWS)
    app.state.match.winner = 0  # as if the 8 had just gone down legally
    app.state = start_turn(app.state)
    assert "W: watch this match" in screen_text(app.cells(COLS, ROWS)[0])
    app.key(Key("w"), 100.0)
    assert app.state.watch is not None and app.wake_in(100.0) == 0.0
    assert "shot 1 of 1 · Player 1 · the break" in screen_text(app.cells(COLS, ROWS)[0])
    for k in range(120):
        app.tick(100.0 + k / 60)
    assert app.state.watch.phase == "run" and app.dirty
    app.key(Key("q"), 103.0)  # stops watching: the game-over box again, not a quit question
    assert app.state.watch is None and not app.done and app.state.box is None
    assert "W: watch this match" in screen_text(app.cells(COLS, ROWS)[0])


# ---------------------------------------------------------------------------- the command


def cli(*args: str, stdin: str = "") -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "termpool", *args], input=stdin,
                          capture_output=True, text=True, cwd=ROOT, timeout=120)


@pytest.fixture(scope="module")
def match_file(tmp_path_factory, record):
    path = tmp_path_factory.mktemp("watch") / "match.json"
    path.write_text(json.dumps(record))
    return path


def test_headless_watch_prints_the_screen(match_file) -> None:
    p = cli("replay", str(match_file), "--watch", "--headless", "--size", "80x24", "--colors",
            "mono", "--keys", "-", stdin="right right wait 0.5 space")
    assert p.returncode == 0, p.stderr
    assert "shot 3 of 4 · Player 2" in p.stdout and "paused" in p.stdout
    assert len(p.stdout.splitlines()) == 24


def bad(tmp_path, content) -> str:
    path = tmp_path / "bad.json"
    path.write_text(content if isinstance(content, str) else json.dumps(content))
    return str(path)


BAD_FILES = [
    ("{", "invalid JSON"),
    ({"shots": []}, "no shots to watch"),
    ({"shots": {}}, "shots: must be a list"),
    ({"shots": [{"n": 1}]}, "shots[0]: missing key 'frame'"),
]


@pytest.mark.parametrize("content, needle", BAD_FILES)
def test_bad_files_are_one_line_and_exit_2(tmp_path, content, needle) -> None:
    p = cli("replay", bad(tmp_path, content), "--watch", "--headless", "--keys", "-",
            stdin="q")
    assert p.returncode == 2 and p.stdout == ""
    assert p.stderr.count("\n") == 1 and needle in p.stderr, p.stderr


def test_a_bad_shot_deep_in_the_file_names_it(tmp_path, record) -> None:
    data = copy.deepcopy(record)
    del data["shots"][2]["dt"]
    data["shots"][3]["scene"]["balls"][0]["x"] = "\x1b[2J"
    p = cli("replay", bad(tmp_path, data), "--watch", "--headless", "--keys", "-", stdin="q")
    assert p.returncode == 2 and p.stderr.count("\n") == 1
    assert "shots[2]: missing key 'dt'" in p.stderr


def test_an_unknown_theme_and_a_missing_file(tmp_path, record) -> None:
    data = copy.deepcopy(record)
    data["match"]["theme"] = "\x1b]0;pwned\x07"
    p = cli("replay", bad(tmp_path, data), "--watch", "--headless", "--keys", "-", stdin="q")
    assert p.returncode == 2 and "match.theme: must be one of" in p.stderr
    p = cli("replay", str(tmp_path / "none.json"), "--watch")
    assert p.returncode == 2 and p.stderr.count("\n") == 1 and "none.json" in p.stderr


@pytest.mark.parametrize("args, needle", [
    (("--headless", "--keys", "-"), "--headless: only with --watch"),
    (("--watch", "--size", "80x24"), "--size: only with --headless"),
    (("--watch", "--headless"), "--headless needs --keys"),
    (("--watch", "--headless", "--keys", "-", "--size", "80"), "--size: must look like"),
    (("--watch", "--headless", "--keys", "-", "--size", "0x0"), "out of range (1x1 to 1000x1000)"),
    (("--watch", "--json"), "--json: not with --watch"),
    (("--watch",), "needs a terminal"),
])
def test_bad_options_are_one_line_and_exit_2(match_file, args, needle) -> None:
    p = cli("replay", str(match_file), *args, stdin="spce")
    assert p.returncode == 2 and p.stderr.count("\n") == 1 and needle in p.stderr, p.stderr


def test_a_bad_key_script_and_stdin_twice(match_file) -> None:
    p = cli("replay", str(match_file), "--watch", "--headless", "--keys", "-", stdin="spce")
    assert p.returncode == 2 and "--keys: script token 1 'spce'" in p.stderr
    p = cli("replay", "-", "--watch", "--headless", "--keys", "-",
            stdin=match_file.read_text())
    assert p.returncode == 2 and "stdin already holds the replay" in p.stderr


def test_a_tip_that_rounds_to_zero_reads_0_0_never_minus_0_0(record) -> None:
    data = copy.deepcopy(record)
    shot = data["shots"][0]["shot"]
    shot["side"], shot["top"] = 0.3, -0.04  # a draw too small to show at one decimal
    w = Watch(data, "mono")
    assert "tip: side +0.3, top 0.0" in w.describe(0)
    shot["side"], shot["top"] = -0.0, -0.3
    assert "tip: side 0.0, top -0.3" in Watch(data, "mono").describe(0)


@pytest.mark.parametrize(("conf", "flag", "env", "want"), [
    ("colors = 16\n", None, {}, "16"),  # the settings file's choice, as play takes it
    ("colors = 16\n", "256", {}, "256"),  # --colors over it
    ("", None, {"NO_COLOR": "1", "TERM": "xterm-256color"}, "mono"),  # auto: NO_COLOR
    ("", None, {"TERM": "xterm-256color"}, "256"),  # auto: the terminal
])
def test_watching_takes_the_colour_depth_as_play_does(monkeypatch, tmp_path, match_file, conf,
                                                     flag, env, want) -> None:
    import argparse

    from termpool.ui import watch as watch_mod

    (tmp_path / "termpool").mkdir()
    (tmp_path / "termpool" / "settings.conf").write_text(conf)
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    for name in ("NO_COLOR", "COLORTERM", "TERM_PROGRAM"):
        monkeypatch.delenv(name, raising=False)
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    seen = {}
    real = watch_mod.Watch.from_file

    def from_file(path, colors):
        w = real(path, colors)
        seen["depth"] = w.depth
        raise watch_mod.WatchError("stop here")

    monkeypatch.setattr(watch_mod.Watch, "from_file", staticmethod(from_file))
    args = argparse.Namespace(file=str(match_file), headless=True, size=None, keys="-",
                              colors=flag)
    with pytest.raises(watch_mod.WatchError, match="stop here"):
        watch_mod.run(args)
    assert seen["depth"] == want


@pytest.mark.parametrize("mode, red", [("9ball", False), ("8ball", True)])
def test_a_classic_replay_is_coloured_as_its_game_was(mode, red) -> None:
    # The classic theme's reds and yellows are 8-ball's groups; 9-ball keeps its colours.
    from termpool.ui.palette import BALL_C, CLASSIC_RED_C

    app = App(Options(mode=mode, opponent="human", seed=3, colors="mono", theme="classic"))
    play(app, parse_script("enter space-hold 1.3 wait 12"), COLS, ROWS)
    data = app.state.match.to_json()
    assert data["match"]["theme"] == "classic"
    w = Watch(data, "truecolor")
    _, fg, bg = w.cells(120, 40)
    seen = {tuple(int(x) for x in c) for c in [*fg.reshape(-1, 3), *bg.reshape(-1, 3)]}
    assert (CLASSIC_RED_C.rgb in seen) is red
    assert (BALL_C[1].rgb in seen) is not red
