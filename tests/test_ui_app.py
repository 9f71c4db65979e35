"""The game's app driven headless: keys on a virtual clock in, screens and shots out."""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from termpool.physics.cue import MISCUE_OFFSET, strike
from termpool.physics.params import BALL_RADIUS
from termpool.physics.table import POCKET_NAMES
from termpool.rules import words
from termpool.rules.codes import Aim as PlanAim
from termpool.rules.codes import PlanNote, Said, Why
from termpool.ui import aid
from termpool.ui.app import App, Options
from termpool.ui.controls import PowerCharge
from termpool.ui.headless import play, screen_text
from termpool.ui.keys import Key, legacy_events, parse_script
from termpool.ui.phases.cpu import CPU_AIM_S, CPU_SHOW_S
from termpool.ui.phases.turn import new_match, start_turn
from termpool.ui.shots import DT, FAST, power_to_speed
from termpool.ui.state import (
    Aim,
    Aiming,
    Pause,
    Phase,
    Place,
    Quit,
    Run,
    Stats,
    Thinking,
    shooter_is_cpu,
    shot_clock,
    voice,
)
from termpool.ui.table_view import layout
from termpool.ui.view import positions

ROOT = Path(__file__).resolve().parent.parent


def app_for(mode="practice", opponent="human", colors="mono", input_mode="release", **kw) -> App:
    kw.setdefault("seed", 0)  # the same rack every time, for tests
    return App(Options(mode=mode, opponent=opponent, colors=colors, **kw), input_mode=input_mode)


def run_script(app: App, script: str, cols=100, rows=32, legacy=False, frames=None) -> str:
    events = parse_script(script)
    if legacy:
        events = legacy_events(events)
    return play(app, events, cols, rows, frames)


def shots(app: App) -> list[dict]:
    return [rec["shot"] for rec in app.state.match.history]


def strikes(app: App, events, cols=100, rows=32) -> list[float]:
    """Play the events headless; the clock at each strike."""
    found: list[float] = []

    def noting(real):
        def call(*a):
            real(*a)
            part = app.state.part
            if isinstance(part, Run) and part.struck_at not in found:
                found.append(part.struck_at)
        return call

    app.key, app.tick = noting(app.key), noting(app.tick)
    play(app, events, cols, rows)
    return found


def put(app: App, **kw) -> None:
    """Set parts of the app's state, as a test's starting point."""
    app.state = replace(app.state, **kw)


def stroke(app: App, **kw) -> None:
    put(app, stroke=replace(app.state.stroke, **kw))


# ------------------------------------------------------------------------- power and aim

def test_held_space_with_key_releases_shoots_with_the_power_held() -> None:
    app = app_for()
    run_script(app, "enter wait 0.2 space-hold 0.6 wait 1")
    (shot,) = shots(app)
    level = 0.6 / PowerCharge("release").full_time
    assert shot["speed"] == pytest.approx(power_to_speed(level), rel=1e-9)


def test_held_space_on_a_legacy_terminal_is_inferred_from_auto_repeat() -> None:
    app = app_for(input_mode="repeat")
    run_script(app, "enter wait 0.2 space-hold 0.9 wait 1", legacy=True)
    (shot,) = shots(app)
    full = PowerCharge("repeat").full_time
    # The charge runs from the first repeat (0.3 s after the press in scripts); the inferred
    # release is one repeat interval after the last repeat: within 0.05 s.
    lo, hi = power_to_speed((0.6 - 0.05) / full), power_to_speed((0.6 + 0.05) / full)
    assert lo <= shot["speed"] <= hi


def test_a_legacy_hold_s_last_frame_shows_the_power_it_strikes() -> None:
    # No key releases: after the last repeat the app wakes when the meter stops (one
    # interval on), draws it there, and then strikes that power when the release is
    # inferred; before, it slept to the strike, and the last frame read an interval under.
    app = app_for(input_mode="repeat")
    app.key(Key("enter"), 0.0)
    times = [0.2] + [0.7 + 0.033 * k for k in range(16)]
    for t in times:
        app.key(Key("space"), t)
        app.tick(t)
    last = times[-1]
    hold = last + app.wake_in(last)
    assert hold - last == pytest.approx(0.033)  # the terminal's interval, learnt
    app.tick(hold)
    level = app.state.controls.charge.level(hold)
    shown = screen_text(app.cells(100, 32)[0])
    assert f"power {round(100 * level)}%" in shown
    due = hold + app.wake_in(hold)
    assert due > hold
    app.tick(due)
    t = due
    while not app.state.match.history and t < due + 60:  # the shot played out
        t += 1 / 60
        app.tick(t)
    assert shots(app)[0]["speed"] == power_to_speed(level)


def test_classic_meter_press_to_start_press_to_strike() -> None:
    app = app_for(input_mode="classic")
    run_script(app, "enter wait 0.2 space wait 0.5 space wait 1", legacy=True)
    assert len(shots(app)) == 1


def test_balls_move_and_the_turn_comes_back_to_aim() -> None:
    app = app_for()
    rack = app.state.match.pos.copy()
    screen = run_script(app, "enter wait 0.2 space-hold 1.0 wait 1")
    assert len(app.state.match.history) == 1
    assert app.state.phase in (Phase.AIM, Phase.PLACE)
    assert not np.allclose(app.state.match.pos[1:], rack[1:])
    assert "You to shoot" in screen or "You to break" in screen or "ball in hand" in screen


def test_aim_keys_turn_the_shot_half_a_degree_a_tap() -> None:
    app = app_for(mode="8ball")
    run_script(app, "enter right*4 space-hold 1.0 wait 1")
    assert shots(app)[0]["angle"] == pytest.approx(360.0 - 4 * 0.5)


def test_spin_keys_set_the_tip_and_stay_inside_the_miscue_limit() -> None:
    app = app_for(mode="8ball")
    run_script(app, "enter w w d space-hold 1.0 wait 1")
    s = shots(app)[0]
    assert (s["side"], s["top"]) == pytest.approx((0.1, 0.2))
    app = app_for(mode="8ball")
    run_script(app, "enter w*9 a*9 space-hold 1.0 wait 1")
    s = shots(app)[0]
    assert np.hypot(s["side"], s["top"]) == pytest.approx(0.5)
    assert s["side"] < 0 < s["top"]


def test_spin_then_shot_from_the_bug_report_is_played() -> None:
    # The tip was clamped to 0.5 + 1e-9 and then rounded, which could land past the miscue
    # limit: this script ended the game with "tip offset 0.50 R is a miscue".
    app = app_for()
    run_script(app, "enter w*5 a w space-hold 0.5 wait 1")
    (s,) = shots(app)
    assert math.hypot(s["side"], s["top"]) <= MISCUE_OFFSET and s["side"] < 0 < s["top"]


def test_every_tip_the_spin_keys_reach_is_one_the_strike_takes() -> None:
    """Every sequence of up to 10 presses of the four spin keys at once (the bug took 7):
    walk the tip offsets they reach from the centre, press by press, and strike from each."""
    app = app_for()
    run_script(app, "enter")
    seen = level = {(0.0, 0.0)}
    for _ in range(10):
        reached = set()
        for tip in level:
            for name in "wasd":
                stroke(app, side=tip[0], top=tip[1])
                app.key(Key(name), 0.0)
                reached.add((app.state.stroke.side, app.state.stroke.top))
        level = reached - seen
        seen = seen | reached
    for tip in seen:
        strike(1.0, 0.0, *tip)  # raises for a miscue
    assert len(seen) > 1000  # the grid inside the limit, and many points along it
    assert max(math.hypot(*t) for t in seen) == pytest.approx(MISCUE_OFFSET, abs=1e-12)


def test_a_shot_the_match_refuses_is_a_message_not_a_crash(monkeypatch) -> None:
    from termpool.game import Match

    app = app_for()
    run_script(app, "enter")

    def refuse(self, shot):
        raise ValueError("called: name the pocket for the 8")

    monkeypatch.setattr(Match, "begin", refuse)
    run_script(app, "space-hold 0.5 wait 1")
    assert app.state.phase is Phase.AIM and not app.state.match.history
    assert app.state.message[0][0] == \
        "that shot cannot be played: called: name the pocket for the 8"


def test_no_shot_while_balls_move() -> None:
    app = app_for()
    run_script(app, "enter wait 0.2 space-hold 1.0 space-hold 1.0 wait 1")
    assert len(shots(app)) == 1  # the second hold came while the balls were rolling


# ------------------------------------------------------------------------ ball in hand

def test_ball_in_hand_refuses_a_spot_on_another_ball() -> None:
    app = app_for()
    assert app.state.phase is Phase.PLACE
    m = app.state.match
    put(app, part=Place(tuple(float(v) for v in m.pos[m.ids.index("1")])))
    app.key(Key("enter"), 0.0)
    assert app.state.phase is Phase.PLACE
    text = screen_text(app.cells(100, 32)[0])
    assert "Can't place the cue ball there" in text


def test_ball_in_hand_esc_leaves_the_cue_ball_where_it_lies() -> None:
    """Moved about, then Esc: the ball is put down where it lay (not at the cursor), and the
    key bar offers it."""
    app = app_for()
    m = app.state.match
    c = m.ids.index("cue")
    here = tuple(float(v) for v in m.pos[c])
    assert "Esc leave it" in screen_text(app.cells(120, 40)[0])
    run_script(app, "up*5 left*3")
    assert app.state.part.cursor != here
    app.key(Key("esc"), 10.0)
    assert app.state.phase is Phase.AIM
    assert tuple(float(v) for v in m.pos[c]) == here


def test_ball_in_hand_after_a_scratch_esc_asks_for_a_spot() -> None:
    """A cue ball off the table (pocketed) has nowhere to be left: Esc says to place it, and
    the key bar does not offer it."""
    app = app_for()
    m = app.state.match
    c = m.ids.index("cue")
    m.on_table[c] = False
    assert "leave it" not in screen_text(app.cells(120, 40)[0])
    app.key(Key("esc"), 0.0)
    assert app.state.phase is Phase.PLACE
    assert "put it down with Enter" in screen_text(app.cells(120, 40)[0])


def test_ball_in_hand_arrows_move_the_cue_ball() -> None:
    app = app_for()
    x0, y0 = app.state.part.cursor
    run_script(app, "up*3 left*2")
    assert app.state.part.cursor[1] > y0 and app.state.part.cursor[0] < x0
    cursor = app.state.part.cursor
    app.key(Key("enter"), 10.0)
    c = app.state.match.ids.index("cue")
    assert app.state.phase is Phase.AIM and tuple(app.state.match.pos[c]) == pytest.approx(cursor)


# ---------------------------------------------------------------------- pause, quit, help

def test_pause_freezes_the_shot_and_any_key_resumes() -> None:
    app = app_for()
    run_script(app, "enter wait 0.2 space-hold 1.0 wait 0.5 p")
    assert app.state.phase is Phase.RUN and isinstance(app.state.box, Pause)
    t = shot_clock(app.state)
    assert t > 0
    for k in range(300):
        app.tick(10.0 + k / 60)
    assert shot_clock(app.state) == t
    assert "paused" in screen_text(app.cells(100, 32)[0])
    app.key(Key("x"), 20.0)
    for k in range(60):
        app.tick(20.0 + k / 60)
    assert app.state.box is None and shot_clock(app.state) > t


def test_under_a_box_the_key_line_lists_none_of_the_phase_s_keys() -> None:
    """Paused while aiming, the aim's keys do nothing (any key but S goes on, Q too): the
    key line under the box does not offer them."""
    app = app_for()
    run_script(app, "enter")
    aiming = screen_text(app.cells(80, 24)[0]).splitlines()[-1]
    assert "aim" in aiming and "Q quit" in aiming
    app.key(Key("p"), 1.0)
    assert isinstance(app.state.box, Pause)
    under = screen_text(app.cells(80, 24)[0]).splitlines()[-1]
    assert "aim" not in under and "quit" not in under and "help" not in under, under


def test_quit_asks_first() -> None:
    app = app_for()
    run_script(app, "q")
    assert isinstance(app.state.box, Quit) and not app.done
    assert "Quit termpool?" in screen_text(app.cells(100, 32)[0])
    app.key(Key("n"), 1.0)
    assert app.state.box is None and not app.done
    app.key(Key("q"), 2.0)
    app.key(Key("y"), 2.1)
    assert app.done


def test_the_quit_box_says_y_and_m_both_end_the_game_in_play() -> None:
    """Y and M both leave the game in play (M does not keep it to take up again): the box
    says so while a game is in play, and not once the match is over."""
    app = app_for()
    run_script(app, "q")
    assert "Y and M both end the game in play" in screen_text(app.cells(100, 32)[0])
    app.key(Key("n"), 1.0)
    app.state.match.winner = 0
    run_script(app, "q")
    text = screen_text(app.cells(100, 32)[0])
    assert "Quit termpool?" in text and "both end" not in text


def test_help_lists_the_key_bindings() -> None:
    from termpool.ui.controls import ACTIONS, KeyMap, parse_keymap

    app = app_for()
    app.key(Key("h"), 0.0)
    text = screen_text(app.cells(120, 40)[0])
    for desc in ACTIONS.values():
        assert desc in text
    # (the keys in a column as wide as the widest, "1-9, 0" for the power digits)
    assert "Space   shoot (hold to charge)" in text and "↑, ⇧←   fine aim" in text
    # Rebound keys show as bound, in the box and in the panel's key help and power label.
    app = App(Options(mode="practice", colors="mono"),
              keymap=parse_keymap("shoot = z\n"), input_mode="repeat")
    assert isinstance(app.state.keymap, KeyMap)
    app.key(Key("enter"), 0.0)
    text = screen_text(app.cells(120, 40)[0])
    assert "Z: hold to charge" in text
    app.key(Key("z"), 1.0)
    assert "keep z down to charge" in screen_text(app.cells(120, 40)[0])
    app.key(Key("h"), 1.0)
    assert "Z       shoot (hold to charge)" in screen_text(app.cells(120, 40)[0])
    assert "then Z strikes" in screen_text(app.cells(120, 40)[0])  # the power digits


def test_menu_picks_a_game() -> None:
    app = App(Options(colors="mono"))
    assert app.state.phase is Phase.MENU
    assert "8-ball vs computer" in screen_text(app.cells(100, 32)[0])
    run_script(app, "down down enter")
    assert app.state.match.mode == "9ball" and app.state.cpu == (False, True)


def test_settings_offer_every_level_of_the_computer() -> None:
    from termpool import ai
    from termpool.ui.settings import BY_KEY

    assert BY_KEY["level"].values == tuple(ai.LEVELS)  # the levels the AI has, pro too
    app = App(Options(colors="mono", level="pro"))
    run_script(app, "1")  # 8-ball vs computer, at that level
    assert app.state.match.mode == "8ball" and app.state.match.levels == (None, "pro")


def test_tiny_window_gets_a_message_and_the_game_survives() -> None:
    app = app_for()
    assert "make the window at least" in screen_text(app.cells(30, 10)[0])
    assert "You to break" in screen_text(app.cells(100, 32)[0])


def test_idle_app_asks_for_nothing() -> None:
    app = app_for()
    run_script(app, "enter")
    app.cells(100, 32)
    app.tick(50.0)
    assert app.wake_in(50.0) is None and not app.dirty


# ------------------------------------------------------------------------ screens

def test_diffed_frames_decode_to_the_same_screen_as_a_full_frame() -> None:
    pyte = pytest.importorskip("pyte")
    from termpool.ui.output import Screen

    app = app_for(colors="truecolor")
    frames: list[str] = []
    run_script(app, "enter right*3 space-hold 1.0 wait 1", cols=80, rows=24, frames=frames)
    assert len(frames) > 30
    diffed = pyte.Screen(80, 24)
    pyte.Stream(diffed).feed("".join(frames))
    full = pyte.Screen(80, 24)
    pyte.Stream(full).feed(Screen(80, 24, "truecolor").render(*app.cells(80, 24)))
    for r in range(24):
        for c in range(80):
            a, b = diffed.buffer[r][c], full.buffer[r][c]
            assert (a.data, a.bg) == (b.data, b.bg), (r, c)
            if b.data != " ":  # a blank cell's foreground colour shows nowhere
                assert a.fg == b.fg, (r, c)


def test_panel_names_players_and_fouls_in_words() -> None:
    app = app_for(mode="8ball", opponent="human")
    # A feeble break that does not reach the rack: a foul, and the turn passes.
    run_script(app, "enter space wait 20")
    text = screen_text(app.cells(120, 40)[0])
    assert "Player 1's foul:" in text  # whose foul, by name, before what it was
    assert "player 0" not in text and "player 1" not in text
    assert app.state.match.shooter == 1
    out = app.state.match.last_outcome
    v = words.Voice(players=("You", "Computer"), plain=False)
    assert words.verdict(out, v, 0)[0].startswith("Your foul: ")
    assert words.verdict(out, v, 1)[0].startswith("Computer's foul: ")


@pytest.mark.parametrize("three_foul", [False, True])
def test_fouls_in_a_row_are_shown_only_under_the_three_foul_rule(three_foul) -> None:
    from dataclasses import replace as _replace

    app = App(Options(mode="9ball", opponent="human", colors="mono", seed=3,
                      three_foul=three_foul))
    m = app.state.match
    m.state = _replace(m.state, fouls=(1, 0))
    text = screen_text(app.cells(120, 40)[0])
    assert ("fouls 1" in text) is three_foul


def test_computer_takes_its_turn() -> None:
    app = app_for(mode="8ball", opponent="cpu")
    run_script(app, "enter space wait 60")
    assert any(rec["player"] == 1 for rec in app.state.match.history)


# ---------------------------------------------------------------------------- the CLI

def cli(*args: str, stdin: str = "") -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "termpool", *args], cwd=ROOT, input=stdin,
                          capture_output=True, text=True, timeout=300,
                          env={"PATH": "/usr/bin:/bin", "PYTHONPATH": str(ROOT),
                               # the test's own directories (conftest), never the user's
                               **{k: os.environ[k] for k in ("XDG_CONFIG_HOME",
                                                             "XDG_DATA_HOME")}})


def test_headless_play_prints_the_screen_and_a_replayable_record(tmp_path) -> None:
    keys = tmp_path / "keys.txt"
    keys.write_text("enter wait 0.2 right*2 space-hold 1.0 wait 1\n")
    rec = tmp_path / "match.json"
    p = cli("play", "--headless", "--mode", "practice", "--size", "90x30", "--keys", str(keys),
            "--record", str(rec), "--colors", "mono")
    assert p.returncode == 0, p.stderr
    lines = p.stdout.rstrip("\n").split("\n")
    assert len(lines) == 30 and max(len(s) for s in lines) <= 90
    assert "You to" in p.stdout
    data = json.loads(rec.read_text())
    assert len(data["shots"]) == 1
    r = cli("replay", str(rec))
    assert r.returncode == 0, r.stdout + r.stderr


@pytest.mark.parametrize("args, needle", [
    (["--keys", "-"], "script token 1 'spce'"),
    (["--keys", "-", "--size", "100by30"], "--size"),
    (["--keys", "/nonexistent/keys.txt"], "--keys"),
    ([], "--keys"),
])
def test_headless_bad_input_is_one_line_and_exit_2(args, needle) -> None:
    p = cli("play", "--headless", *args, stdin="spce")
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0], p.stderr


def test_keys_given_in_place_of_a_key_file_are_told_to_be_a_file(tmp_path) -> None:
    p = cli("play", "--headless", "--keys", "wait 5 right space")
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 2 and len(lines) == 1, p.stderr
    assert "'wait 5 right space'" in lines[0] and "takes a file of keys" in lines[0]
    p = cli("play", "--headless", "--keys", str(tmp_path / "none.txt"))  # a file's name: as is
    assert p.returncode == 2 and "takes a file" not in p.stderr and "none.txt" in p.stderr


def test_bad_keymap_file_is_one_line_and_exit_2(tmp_path) -> None:
    conf = tmp_path / "keys.conf"
    conf.write_text("aim_ccw = left\nno_such_action = x\n")
    p = cli("play", "--headless", "--keys", "-", "--keymap", str(conf), stdin="q y")
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "line 2" in lines[0]


def test_push_out_then_pass_with_p_which_is_not_pause_here() -> None:
    app = app_for(mode="9ball", opponent="human")
    run_script(app, "enter space-hold 1.2 wait 20")
    if app.state.phase is Phase.PLACE:
        app.key(Key("enter"), 100.0)
    assert app.state.match.state.push_out == "available"
    pusher = app.state.match.shooter
    run_script(app, "o space-hold 0.3 wait 20")
    assert app.state.phase is Phase.OPTION and app.state.match.option == "shoot_or_pass"
    assert app.state.match.shooter != pusher
    screen = screen_text(app.cells(100, 32)[0])
    # Two players at one screen: the box names whose call it is.
    chooser = app.state.match.players[app.state.match.shooter]
    assert "pass" in screen and f"{chooser}'s call" in screen, screen
    app.key(Key("p"), 200.0)
    assert app.state.box is None and app.state.match.option is None
    assert app.state.match.shooter == pusher


def test_game_over_n_starts_a_new_game_and_does_not_toggle_the_bell() -> None:
    app = app_for(mode="8ball", opponent="human")
    run_script(app, "enter space-hold 1.0 wait 20")
    app.state.match.winner = 0  # as if the 8 had just gone down legally
    app.state = start_turn(app.state)
    assert app.state.phase is Phase.OVER and "wins" in screen_text(app.cells(100, 32)[0])
    bell = app.state.opts.bell
    app.key(Key("n"), 300.0)
    assert app.state.opts.bell == bell
    assert app.state.match.history == [] and app.state.phase is Phase.PLACE


@pytest.mark.parametrize("cols, rows", [(80, 24), (120, 40), (200, 60)])
@pytest.mark.parametrize("depth", ["truecolor", "256", "16", "mono"])
def test_game_screen_at_sizes_and_depths(cols, rows, depth) -> None:
    pyte = pytest.importorskip("pyte")
    from termpool.ui.output import Screen

    app = app_for(mode="8ball", colors=depth)
    app.key(Key("enter"), 0.0)  # place the cue ball on the head spot: aiming at the rack
    scr = pyte.Screen(cols, rows)
    pyte.Stream(scr).feed(Screen(cols, rows, depth).render(*app.cells(cols, rows)))
    text = "\n".join(scr.display)
    assert "Player 1 to break" in text
    lay = app.seen.layout
    c = app.state.match.ids.index("cue")
    x, y = lay.to_pixels(*app.state.match.pos[c])
    cell = scr.buffer[int(y) // 2][int(x)]
    felt = scr.buffer[(lay.py + lay.ph // 4) // 2][lay.px + lay.pw // 2]  # open cloth
    if depth == "mono":
        assert cell.data == "○"
    else:
        pixel = cell.fg if int(y) % 2 == 0 else cell.bg  # the upper or lower half of the cell
        assert pixel != felt.bg  # the cue ball is drawn where it is, over the cloth
        if depth == "truecolor":
            r, g, b = (int(felt.bg[k:k + 2], 16) for k in (0, 2, 4))
            assert g > r and g > b  # the felt is green
            r, g, b = (int(pixel[k:k + 2], 16) for k in (0, 2, 4))
            assert min(r, g, b) > 200  # the cue ball is white


def test_resizing_during_a_shot_relays_out_without_losing_the_shot() -> None:
    app = app_for()
    app.key(Key("enter"), 0.0)
    app.key(Key("space"), 0.1)
    app.key(Key("space", kind="release"), 1.1)  # held for a second: the shot starts
    assert app.state.phase is Phase.RUN
    sizes = [(80, 24), (30, 10), (160, 50), (100, 32)]
    for k, (cols, rows) in enumerate(sizes):
        app.tick(10.0 + k * 0.1)
        chars = app.cells(cols, rows)[0]
        assert chars.shape == (rows, cols)
    for k in range(60 * 60):
        app.tick(11.0 + k / 60)
        if app.state.phase is not Phase.RUN:
            break
    assert len(app.state.match.history) == 1


def test_the_shot_plays_in_real_time_and_fast_forward_is_four_times_faster() -> None:
    for fast in (False, True):
        app = app_for()
        app.key(Key("enter"), 0.0)
        app.key(Key("space"), 0.1)
        app.key(Key("space", kind="release"), 1.3)  # a full-power break: seconds of motion
        if fast:
            app.key(Key("f"), 1.3)
        for k in range(31):  # half a second of 60 Hz ticks
            app.tick(1.3 + k / 60)
        want = 0.5 * (FAST if fast else 1.0)
        assert abs(shot_clock(app.state) - want) <= DT + 1e-9
        # What is drawn is the frame a match stepped live reaches at that time, bit for bit.
        from termpool.game import Match, Shot

        m = Match("practice", players=("You", "You"))
        shot = app.state.part.shot.shot.to_json()
        m.place_cue(*app.state.match.pos[0])  # where the app's player put it (the head spot)
        live = m.begin(Shot(**{k: shot[k] for k in ("speed", "angle", "side", "top")}))
        for _ in range(app.state.part.shown):
            live.step(DT)
        pos, _ = positions(app.state)
        assert np.array_equal(pos[app.state.part.shot.rows], live.engine.pos[0])


def test_three_foul_warning_shows_before_the_shot() -> None:
    from dataclasses import replace

    app = app_for(mode="9ball", opponent="human", three_foul=True)
    app.key(Key("enter"), 0.0)
    m = app.state.match
    m.state = replace(m.state, fouls=(2, 0))
    text = screen_text(app.cells(120, 40)[0])
    assert "Player 1 is on two fouls" in text


def test_waiting_spot_is_legal_even_with_the_head_spot_taken() -> None:
    app = app_for(mode="8ball", opponent="human")
    m = app.state.match
    k = m.ids.index("1")
    m.pos[k] = m.table.head_spot  # a ball sits on the head spot
    x, y = m.waiting_spot()  # the computer's fallback for ball in hand
    assert m.placement_error(x, y) is None


def test_referee_words_get_the_players_names() -> None:
    from termpool.rules.codes import Said, Why
    from termpool.rules.words import foul_warning, reason

    app = app_for(mode="8ball", opponent="human")
    assert reason([Said(Why.OPEN_CONTINUES, player=0)], voice(app.state)) == \
        "the table is open and Player 1 continues"
    assert foul_warning(voice(app.state), 0).startswith("Player 1 is on two fouls")
    app = app_for(mode="8ball", opponent="cpu")
    assert reason([Said(Why.OPEN_TURN, player=0), Said(Why.EIGHT_ON_FOUL, player=1)],
                  voice(app.state)) == \
        "the table is open and it is your turn; the 8 went down on a foul: Computer loses"
    assert reason([Said(Why.OPEN_CONTINUES, player=0)], voice(app.state)) == \
        "the table is open and you continue"
    assert reason([Said(Why.POTTED_CONTINUES, balls=("3",), player=0),
                   Said(Why.SCRATCH, pocket="foot_left")], voice(app.state)) == \
        ("the 3 pocketed: you continue; scratch: the cue ball went into the top-right corner "
         "pocket")
    assert reason([Said(Why.POTTED_CONTINUES, balls=("3",), pockets=("foot_left",), player=0)],
                  voice(app.state)) == "the 3 in the top-right corner pocket: you continue"
    assert reason([Said(Why.POTTED_CONTINUES, balls=("3", "5"), pockets=("foot_left", "side_left"),
                        player=0)], voice(app.state)) == "the 3 and the 5 pocketed: you continue"
    assert reason([Said(Why.IN_HAND, player=0)], voice(app.state)) == \
        "You have ball in hand"
    assert foul_warning(voice(app.state), 0).startswith("You are on two fouls")


# --------------------------------------------------------------------------------- mouse

def test_sgr_mouse_reports_decode_in_order_with_keys() -> None:
    from termpool.ui.keys import Mouse, decode_input

    got = decode_input("a\x1b[<0;10;5M\x1b[<32;11;5M\x1b[<0;11;5mb\x1b[<35;3;3M\x1b[<65;1;1M")
    assert got == [Key("a"), Mouse(9, 4, "press", 0), Mouse(10, 4, "drag", 0),
                   Mouse(10, 4, "release", 0), Key("b"), Mouse(2, 2, "move", 3),
                   Mouse(0, 0, "wheel_down", 3)]


def test_scripts_click_and_legacy_terminals_keep_mouse_releases() -> None:
    from termpool.ui.keys import Mouse

    ev = parse_script("click 12 7 q")
    assert ev[:2] == [(0.0, Mouse(12, 7, "press")), (0.025, Mouse(12, 7, "release"))]
    assert [e for _, e in legacy_events(ev)][:2] == [Mouse(12, 7, "press"),
                                                     Mouse(12, 7, "release")]
    with pytest.raises(ValueError, match="script token 1 'click'"):
        parse_script("click 12")


def cell_of(app: App, x: float, y: float, cols=120, rows=40) -> tuple[int, int]:
    app.cells(cols, rows)
    lay = app.seen.layout
    px, py = lay.to_pixels(x, y)
    return int(px), int(py) // 2


def test_click_aims_at_the_point_and_places_the_ball_in_hand() -> None:
    from termpool.ui.keys import Mouse

    app = app_for(mode="8ball", opponent="human")
    m = app.state.match
    # Ball in hand: a click puts the cursor at the clicked cell.
    col, row = cell_of(app, 0.4, 0.3)
    app.mouse(Mouse(col, row, "press"), 0.0)
    lay = app.seen.layout
    cell_m = 2.0 / lay.scale  # a cell is two pixels high
    x, y = app.state.part.cursor
    assert abs(x - 0.4) <= cell_m and abs(y - 0.3) <= cell_m
    app.key(Key("enter"), 0.1)
    assert app.state.phase is Phase.AIM
    # Aiming: a click on a ball turns the stick at it, to within the cell's size.
    k = m.ids.index("5")
    col, row = cell_of(app, *m.pos[k])
    app.mouse(Mouse(col, row, "press"), 0.2)
    d = m.pos[k] - m.pos[0]
    want = math.degrees(math.atan2(d[1], d[0])) % 360
    tol = math.degrees(math.atan2(cell_m, float(np.hypot(*d))))
    assert abs(app.state.stroke.angle - want) <= tol
    # A right click or a release does nothing.
    before = app.state.stroke.angle
    app.mouse(Mouse(0, 0, "press", 2), 0.3)
    app.mouse(Mouse(0, 0, "release", 0), 0.4)
    assert app.state.stroke.angle == before


# ---------------------------------------------------------------- from the QA session

def test_ball_in_hand_taps_move_a_centimetre_and_a_hold_crosses_the_table_but_stays_on_it():
    app = app_for(mode="practice")
    x0, y0 = app.state.part.cursor
    run_script(app, "down")
    # Up and down move as much as left and right.
    assert app.state.part.cursor[1] == pytest.approx(y0 - 0.01)
    run_script(app, "right*3", legacy=True)  # legacy taps 50 ms apart count as a short hold
    assert app.state.part.cursor[0] > x0
    run_script(app, "left-hold 4")
    r = float(app.state.match.radius[0])
    # Clamped at the cushion, still on the cloth.
    assert app.state.part.cursor[0] == pytest.approx(r)
    run_script(app, "up-hold 4")
    assert app.state.part.cursor[1] == pytest.approx(app.state.match.table.width - r)
    app.key(Key("enter"), 100.0)  # the corner is a pocket's mouth: refused, in words
    assert app.state.phase is Phase.PLACE and "Can't place" in app.state.message[0][0]
    run_script(app, "right-hold 1.5")
    app.key(Key("enter"), 200.0)
    assert app.state.phase is Phase.AIM


def test_kitchen_keeps_the_ball_in_hand_behind_the_head_string():
    app = app_for(mode="8ball", opponent="human")
    assert app.state.match.ball_in_hand == "kitchen"
    run_script(app, "right-hold 3")
    assert app.state.part.cursor[0] == pytest.approx(app.state.match.table.length / 4)
    app.key(Key("enter"), 100.0)
    assert app.state.phase is Phase.AIM


def test_mono_shows_the_ball_in_hand_at_the_cursor():
    app = app_for(mode="practice")
    col, row = cell_of(app, *app.state.part.cursor, cols=100, rows=32)
    chars = app.cells(100, 32)[0]
    assert chars[row, col] == "○"


def test_mono_at_80x24_shows_the_power_while_charging():
    app = app_for(mode="8ball", opponent="human", input_mode="classic")
    app.key(Key("enter"), 0.0)
    put(app, message=(("a verdict long enough to wrap onto a second line of the narrow "
                       "bottom panel at eighty columns, as real ones do", "plain"),))
    app.key(Key("space"), 1.0)
    app.tick(1.6)
    text = screen_text(app.cells(80, 24)[0])
    assert "power 50%" in text


def test_a_finished_match_is_kept_for_the_record_after_n():
    app = app_for(mode="8ball", opponent="human")
    run_script(app, "enter space-hold 1.0 wait 20")
    first = app.state.match
    app.state.match.winner = 0
    app.state = start_turn(app.state)
    app.key(Key("enter"), 300.0)  # Enter is not "new game" on the game-over box
    assert app.state.match is first
    app.key(Key("n"), 301.0)
    assert app.state.match is not first and app.record() is first


def test_fast_forward_lasts_one_shot():
    app = app_for()
    run_script(app, "enter space-hold 1.0 f wait 20")
    assert len(shots(app)) == 1
    app.key(Key("space"), 100.0)
    app.key(Key("space", kind="release"), 100.5)
    assert app.state.phase is Phase.RUN and not app.state.part.fast


def test_frame_result_stays_in_view_while_the_computer_thinks():
    app = app_for(mode="8ball", opponent="cpu", frames=2)
    put(app, message=(("You win the frame (1-0); Computer breaks", "good"),))
    app.state.match.state = replace(app.state.match.state, shooter=1)
    put(app, part=Thinking())
    app.tick(0.0)
    app.tick(0.1)  # the computer decides
    assert any("wins the frame" in m or "win the frame" in m for m, _ in app.state.message)
    text = screen_text(app.cells(120, 40)[0])
    assert "frames 0/2" in text


def test_help_box_fits_80x24_and_says_how_to_close_it():
    app = app_for()
    app.key(Key("h"), 0.0)
    text = screen_text(app.cells(80, 24)[0])
    assert "any other key closes" in text and "rerack" in text and "mouse" in text
    assert "← → pages" in text  # the rules of the game come after the keys


def test_quit_question_shows_even_when_the_window_is_too_small():
    app = app_for()
    app.key(Key("q"), 0.0)
    assert "Quit termpool?" in screen_text(app.cells(30, 10)[0])


def test_a_click_as_the_first_script_token_works():
    app = app_for(mode="practice")
    before = app.state.part.cursor
    run_script(app, "click 30 8")
    assert app.state.part.cursor != before


def test_play_only_options_and_play_as_the_default_command():
    p = cli("play", "--size", "10")
    assert p.returncode == 2 and "--size: only with --headless" in p.stderr
    p = cli("--colors", "mono")  # `play` is implied; without a terminal it says so
    assert p.returncode == 2 and "needs a terminal" in p.stderr


def test_keys_that_do_not_apply_say_why():
    app = app_for(mode="8ball", opponent="human")
    run_script(app, "enter o")
    assert "push-out is only" in app.state.message[0][0]
    run_script(app, "c")
    assert "no call needed" in app.state.message[0][0]
    app = app_for(mode="practice")
    run_script(app, "enter u")
    assert app.state.message[0][0] == "nothing to take back"


def test_ball_in_hand_push_out_and_take_back_keys_say_why_in_every_phase():
    # B with no ball in hand (aiming)
    app = app_for(mode="8ball", opponent="human")
    app.key(Key("enter"), 0.0)
    m = app.state.match
    m.state = replace(m.state, is_break=False)
    m.ball_in_hand = None
    app.state = start_turn(app.state)
    run_script(app, "b")
    assert app.state.phase is Phase.AIM
    assert app.state.message[0][0].startswith("no ball in hand")
    # O and U with the ball in hand before the break (8-ball): why not
    app = app_for(mode="8ball", opponent="human")
    assert app.state.phase is Phase.PLACE
    run_script(app, "o")
    assert app.state.message[0][0].startswith("a push-out is only for the shot right after")
    run_script(app, "u")
    assert app.state.message[0][0] == "take back and re-rack are for practice"
    # while the balls roll: wait (and the verdict comes as ever)
    for k, name in enumerate(("enter", "5", "space", "b", "o", "u")):  # 50%, struck at once
        app.key(Key(name), 100.0 + k * 0.05)
    assert app.state.phase is Phase.RUN
    assert app.state.message[-1] == ("wait for the balls to stop", "dim")
    assert sum(x == ("wait for the balls to stop", "dim") for x in app.state.message) == 1
    run_script(app, "wait 20")
    assert ("wait for the balls to stop", "dim") not in app.state.message
    # 9-ball: a scratch on the break leaves ball in hand with the push-out to come
    app = app_for(mode="9ball", opponent="human")
    app.key(Key("enter"), 0.0)
    m = app.state.match
    m.state = replace(m.state, is_break=False, push_out="available")
    m.ball_in_hand = "anywhere"
    app.state = start_turn(app.state)
    assert app.state.phase is Phase.PLACE
    run_script(app, "o")
    assert app.state.message[0][0] == "put the cue ball down first (Enter), then push out"


def test_take_back_works_with_the_ball_in_hand_in_practice():
    app = app_for(mode="practice")
    run_script(app, "enter space-hold 1.0 wait 20")
    m = app.state.match
    assert len(m.history) == 1
    m.ball_in_hand = "anywhere"  # as after a scratch
    app.state = start_turn(app.state)
    assert app.state.phase is Phase.PLACE
    run_script(app, "u")
    assert m.history == [] and app.state.message[0][0] == "took the last shot back"


def test_a_re_rack_says_how_to_take_it_back_and_u_takes_it_back():
    app = app_for(mode="practice")
    run_script(app, "enter space-hold 1.0 wait 20")
    m = app.state.match
    before = m.pos.copy()
    stroke = app.state.stroke
    run_script(app, "r")
    assert app.state.message[0][0] == "re-racked (U puts the balls back)"
    assert m.on_table.all() and not np.array_equal(m.pos, before)
    run_script(app, "u")
    assert app.state.message[0][0] == "the re-rack taken back: the balls as they were"
    assert np.array_equal(m.pos, before) and len(m.history) == 1
    assert app.state.stroke.angle == stroke.angle  # the stick stays: no shot was taken back


def test_a_shot_taken_back_leaves_the_stick_as_it_was_for_it():
    """Practice's U: the layout comes back, and so do the shot's aim and tip, to play it
    again or nudge it; from ball in hand once the ball goes down where it lay, and not
    when it is put down elsewhere."""
    app = app_for(mode="practice")
    run_script(app, "enter")  # ball in hand put down: aiming
    stroke = replace(app.state.stroke, angle=123.25, side=0.2, top=-0.3)
    app.state = replace(app.state, stroke=stroke)
    run_script(app, "space-hold 1.0 wait 20")
    assert app.state.phase is Phase.PLACE  # practice's first shot was from ball in hand
    run_script(app, "u")
    assert app.state.phase is Phase.PLACE and app.state.match.history == []
    run_script(app, "enter")
    s = app.state.stroke
    assert app.state.phase is Phase.AIM and (s.angle, s.side, s.top) == (123.25, 0.2, -0.3)
    # From the aim (no ball in hand after it): at once.
    run_script(app, "space-hold 1.0 wait 20")
    app.state.match.ball_in_hand = None
    app.state = start_turn(app.state)
    app.state = replace(app.state, stroke=replace(app.state.stroke, angle=10.0))
    run_script(app, "space-hold 1.0 wait 20")
    app.state.match.ball_in_hand = None
    app.state = start_turn(app.state)
    assert app.state.phase is Phase.AIM
    run_script(app, "u")
    s = app.state.stroke
    assert app.state.phase is Phase.AIM and (s.angle, s.side, s.top) == (10.0, 0.0, 0.0)
    # Moved before it goes down: aimed afresh.
    run_script(app, "u u")
    assert app.state.phase is Phase.PLACE
    run_script(app, "left enter")
    assert app.state.stroke.angle != 123.25


def test_the_bell_is_called_the_bell_in_the_help_the_settings_and_its_key():
    from termpool.ui.controls import ACTIONS
    from termpool.ui.settings import BY_KEY

    word = BY_KEY["bell"].label.lower()
    assert ACTIONS["bell"].startswith(f"{word} on/off")
    app = app_for(mode="practice")
    run_script(app, "n")
    assert app.state.message[0][0] == f"{word} on"
    assert "sound" not in ACTIONS["bell"] + BY_KEY["bell"].help


# ------------------------------------------------------------- from QA round 2

def eight_on_the_8(app: App):
    """Player 1 has cleared the solids: the 8 is next and must be called."""
    from dataclasses import replace

    m = app.state.match
    m.state = replace(m.state, is_break=False, groups={0: "solids", 1: "stripes"})
    m.ball_in_hand = None
    for b in "1234567":
        m.on_table[m.index(b)] = False
    L, W = m.table.length, m.table.width
    m.pos[m.index("8")] = (L - 0.4, W - 0.3)
    m.pos[0] = (L - 0.9, W - 0.8)  # cue, 8 and the foot_left corner in line
    put(app, part=Aim())
    stroke(app, angle=45.0)
    assert m.needs_call()
    return app


def test_the_8_is_called_in_the_pocket_the_aim_sends_it_to_until_one_is_picked():
    app = app_for(mode="8ball", opponent="human")
    app.key(Key("enter"), 0.0)
    eight_on_the_8(app)
    assert aid.called(app.state) == ("8", "foot_left")
    assert "calling the 8 in the top-right corner pocket" in screen_text(app.cells(120, 40)[0])
    app.key(Key("left"), 0.5)  # unpicked, the call follows the aim
    app.key(Key("left", kind="release"), 0.51)
    assert aid.called(app.state) == ("8", POCKET_NAMES[aid.aimed_pocket(app.state)])
    app.key(Key("right"), 0.6)
    app.key(Key("right", kind="release"), 0.61)
    app.key(Key("c"), 1.0)  # the player picks another pocket
    picked = aid.called(app.state)
    assert picked[1] != "foot_left"
    for t in (2.0, 2.2, 2.4):  # ... and it stays called however the aim moves
        app.key(Key("left"), t)
        app.key(Key("left", kind="release"), t + 0.01)
        assert aid.called(app.state) == picked
    text = screen_text(app.cells(120, 40)[0])
    assert f"calling the 8 in the {words.voice(('A', 'B')).pocket(picked[1])} pocket" in text
    app.key(Key("space"), 3.0)
    app.key(Key("space", kind="release"), 3.3)
    assert app.state.part.shot.shot.called == picked


def test_holding_space_to_place_the_ball_does_not_also_shoot():
    for legacy in (True, False):
        app = app_for(mode="practice", input_mode="repeat" if legacy else "release")
        run_script(app, "space-hold 0.8 wait 1", legacy=legacy)
        assert app.state.phase is Phase.AIM and not app.state.match.history
        assert not app.state.controls.charge.active
        run_script(app, "space-hold 0.8 wait 1", legacy=legacy)  # a new press shoots
        assert len(app.state.match.history) == 1


def test_ball_in_hand_taps_with_releases_are_taps_and_shift_is_fine_when_held():
    app = app_for(mode="practice")
    x0, y0 = app.state.part.cursor
    run_script(app, "left*10")
    assert app.state.part.cursor[0] == pytest.approx(x0 - 0.10)
    run_script(app, "shift+up*2")
    assert app.state.part.cursor[1] == pytest.approx(y0 + 0.004)
    x1 = app.state.part.cursor[0]
    run_script(app, "shift+right-hold 1")
    # A second of fine steps: centimetres, not metres.
    assert 0 < app.state.part.cursor[0] - x1 < 0.1


def test_refusals_name_pockets_in_words_and_clicks_off_the_table_are_ignored():
    from termpool.ui.keys import Mouse

    app = app_for(mode="practice")
    put(app, part=Place((0.03, 0.03)))  # the bottom-left corner's mouth
    app.key(Key("enter"), 0.0)
    assert "bottom-left corner pocket" in app.state.message[0][0]
    app.cells(100, 32)
    before = app.state.part.cursor
    app.mouse(Mouse(50, 31, "press"), 1.0)  # the panel's last row
    assert app.state.part.cursor == before


def test_nine_ball_says_which_ball_is_on():
    app = app_for(mode="9ball", opponent="human")
    run_script(app, "enter space-hold 1.2 wait 20")
    if app.state.phase is Phase.PLACE:
        app.key(Key("enter"), 100.0)
    m = app.state.match
    low = min((b for b in m.ids[1:] if m.on_table[m.index(b)]), key=int)
    assert f"the {low} is on" in screen_text(app.cells(120, 40)[0])


def test_key_help_follows_the_phase():
    app = app_for(mode="practice")
    assert "Enter place" in screen_text(app.cells(120, 40)[0])
    app.key(Key("enter"), 0.0)
    app.key(Key("space"), 1.0)
    rows = screen_text(app.cells(120, 40)[0]).rstrip("\n").split("\n")
    # What Space does now is said once, above; the key bar has what else there is.
    assert sum("release space to shoot" in r for r in rows) == 1
    assert rows[-1].strip() == "Esc cancel"


def test_the_computer_announces_its_plan_not_the_result_it_simulated(monkeypatch):
    from termpool import ai

    def plan(*a, **k):
        return ai.Plan(2.0, 10.0, 0.0, 0.0, None, 1.0,
                       PlanNote(PlanAim.VERDICT, said=(Said(Why.NINE_LEGAL, pocket="head_right",
                                                        player=1),)),
                       "pot", "9", "head_right", "win")

    monkeypatch.setattr(ai.Computer, "shot", plan)
    app = app_for(mode="9ball", opponent="cpu")
    app.state.match.state = replace(app.state.match.state, shooter=1)
    app.state.match.ball_in_hand = None
    put(app, part=Thinking())
    app.tick(0.0)
    app.tick(0.1)
    assert not any("wins" in m for m, _ in app.state.message)


def test_referee_words_take_the_theme_s_group_names():
    from termpool.rules import words
    from termpool.rules.codes import Said, Why
    from termpool.rules.words import reason

    said = [Said(Why.TAKES_GROUP, balls=("11",), player=0, group="stripes")]
    assert reason(said, words.voice(["Ann", "Bob"], "classic")) == \
        "a yellow pocketed: Ann takes the yellows and continues"
    assert reason(said, words.voice(["You", "Bob"])) == \
        "the 11 pocketed: you take the stripes and continue"
    app = app_for(mode="8ball", opponent="human", theme="classic")
    assert reason([Said(Why.HIT_NOT_GROUP, ball="9", group="solids")], voice(app.state)) == \
        "the cue ball hit a yellow first, not one of the reds"


def test_the_classic_theme_names_its_unnumbered_balls_by_colour():
    # Its reds and yellows show no numbers on the table: a person hears "a red", and balls
    # of a colour are counted; the 8, the cue ball and the record keep their names.
    from termpool.rules import words
    from termpool.rules.codes import Said, Why
    from termpool.rules.words import RECORD, reason

    classic, standard = words.voice(["You", "Bob"], "classic"), words.voice(["You", "Bob"])
    down = [Said(Why.STAY_DOWN, balls=("3", "12", "5", "8"))]
    assert reason(down, classic) == "two reds, a yellow and the 8 stay down"
    assert reason(down, standard) == "the 3, the 12, the 5 and the 8 stay down"
    assert reason(down, RECORD) == "the 3, the 12, the 5 and the 8 stay down"
    one = [Said(Why.POTTED_CONTINUES, balls=("6",), pockets=("foot_left",), player=0)]
    assert reason(one, classic) == "a red in the top-right corner pocket: you continue"
    practice = [Said(Why.PRACTICE_POTTED, balls=("9", "8"))]
    assert reason(practice, classic) == "a yellow and the 8 pocketed"
    assert reason(practice, RECORD) == "the 9, the 8 pocketed"  # as records have it
    # The aid's first ball too.
    app = app_for(mode="8ball", opponent="human", theme="classic")
    text = run_script(app, "enter wait 0.2", cols=120, rows=40)
    assert re.search(r"first ball: a (red|yellow)\b", text), text


@pytest.mark.parametrize("mode, red", [("9ball", False), ("8ball", True)])
def test_the_classic_theme_colours_8_ball_s_groups_and_leaves_9_ball_its_colours(mode, red):
    # Reds and yellows are 8-ball's groups: in 9-ball they would make the 1 to 7 one red,
    # and its rules ask for the lowest ball.
    from termpool.ui.palette import BALL_C, CLASSIC_RED_C
    from termpool.ui.state import shown_theme
    from termpool.ui.table_view import Geometry
    from termpool.ui.view import draw

    app = app_for(mode=mode, opponent="human", theme="classic", colors="truecolor")
    assert shown_theme(app.state) == ("classic" if red else "standard")
    (_, fg, bg), _ = draw(app.state, 120, 40, Geometry())
    seen = {tuple(int(x) for x in c) for c in [*fg.reshape(-1, 3), *bg.reshape(-1, 3)]}
    assert (CLASSIC_RED_C.rgb in seen) is red
    assert (BALL_C[1].rgb in seen) is not red
    assert (BALL_C[3].rgb in seen) is not red


def test_the_record_keeps_the_computer_s_level():
    assert app_for(mode="9ball", opponent="cpu", level="hard").state.match.levels == (None, "hard")
    assert app_for(mode="9ball", opponent="human", level="hard").state.match.levels == (None, None)


def test_the_eight_on_the_break_variant_reaches_the_match():
    assert app_for(mode="8ball", eight_break="rerack").state.match.eight_break == "rerack"
    assert app_for(mode="8ball").state.match.eight_break == "respot"
    p = cli("play", "--headless", "--keys", "-", "--eight-break", "sometimes", stdin="q y")
    assert p.returncode == 2 and "--eight-break" in p.stderr


# ------------------------------------------------------------ power without key releases

@pytest.mark.parametrize("delay", [0.25, 0.5, 0.66])
def test_legacy_terminal_softest_hold_is_gentle_and_strikes_within_100_ms(delay) -> None:
    # A terminal without key releases (tmux, most terminals), emulated by the script's
    # `repeat` token: the softest hold is the press and its first repeat.
    for hold, most in ((delay + 0.01, 0.15), (delay + 0.5, 1.0)):
        app = app_for(input_mode="repeat")
        events = legacy_events(parse_script(f"repeat {delay} 0.033 enter wait 0.2 "
                                            f"space-hold {hold} wait 1"))
        (struck,) = strikes(app, events)
        (shot,) = shots(app)
        assert shot["speed"] <= power_to_speed(most)
        last = max(t for t, k in events if k.name == "space")
        assert 0.0 < struck - last <= 0.1


def test_digit_then_space_strikes_at_that_power_and_the_hint_names_the_mode() -> None:
    for mode in ("release", "repeat", "classic"):
        app = app_for(input_mode=mode)
        run_script(app, "enter wait 0.2", legacy=mode != "release")
        hint = screen_text(app.cells(120, 40)[0]).splitlines()[-1]
        assert {"release": "Space: hold, let go", "repeat": "Space: hold to charge",
                "classic": "Space: meter"}[mode] in hint
        play(app, [(1.0, Key("3")), (1.1, Key("space"))] if mode != "release" else
             [(1.0, Key("3")), (1.1, Key("space")), (1.15, Key("space", "release"))], 100, 32)
        (shot,) = shots(app)
        assert shot["speed"] == power_to_speed(0.3)
        hint = screen_text(app.cells(120, 40)[0]).splitlines()[-1]
        way = "meter" if mode == "classic" else "hold"  # what Esc gives back
        assert "Space: strike at 30%" in hint and f"Esc {way}" in hint
        app.key(Key("esc"), 100.0)  # back to holding, or to the meter
        text = screen_text(app.cells(120, 40)[0])
        assert "Space: strike" not in text.splitlines()[-1]
        assert ("power: the meter (space starts it) again" if way == "meter" else
                "power: hold space again") in text
    app = app_for(input_mode="repeat")
    run_script(app, "enter wait 0.2 0 space wait 5", legacy=True)
    assert shots(app)[0]["speed"] == power_to_speed(1.0)


def test_esc_s_note_goes_when_the_charge_begins_and_the_verdict_stays() -> None:
    """A digit set, then Esc: "power: hold space again" says it; Space then begins a charge,
    and the note, answered, goes (it would sit under the running meter saying the opposite).
    The last shot's verdict is not a note: it stays."""
    app = app_for(input_mode="repeat")
    run_script(app, "enter wait 0.2 3", legacy=True)
    app.key(Key("esc"), 1.0)
    verdict = ("the 3 pocketed: you continue", "good")
    app.state = replace(app.state, message=(verdict, *app.state.message))
    assert "power: hold space again" in screen_text(app.cells(120, 40)[0])
    app.key(Key("space"), 2.0)
    assert app.state.controls.charge.active
    text = screen_text(app.cells(120, 40)[0])
    assert "hold space again" not in text and verdict[0] in text
    # An option's answer is news, not a note: a charge leaves it (as the aim's moves do).
    app.key(Key("esc"), 3.0)  # the charge cancelled
    chose = ("Player 1 chose to pass the shot back", "dim")
    app.state = replace(app.state, message=(chose,))
    app.key(Key("right"), 4.0)
    app.key(Key("space"), 5.0)
    assert app.state.controls.charge.active and chose[0] in screen_text(app.cells(120, 40)[0])


def test_headless_repeat_input_is_a_legacy_terminal_with_the_script_s_repeat(tmp_path) -> None:
    rec = tmp_path / "m.json"
    p = cli("play", "--headless", "--mode", "practice", "--input", "repeat", "--keys", "-",
            "--record", str(rec), "--colors", "mono",
            stdin="repeat 0.66 0.04 enter wait 0.2 space-hold 0.68 wait 5 7 space wait 5")
    assert p.returncode == 0, p.stderr
    first, second = (s["shot"]["speed"] for s in json.loads(rec.read_text())["shots"])
    assert first <= power_to_speed(0.15) and second == power_to_speed(0.7)
    p = cli("play", "--headless", "--keys", "-", stdin="repeat 0.5")
    assert p.returncode == 2 and "repeat needs" in p.stderr


def solids_to_shoot(place: dict) -> App:
    """An 8-ball table after the break, the first player on solids, only the balls of
    `place` (id: position) on it, the first player's turn begun."""
    app = app_for(mode="8ball", opponent="human")
    m = app.state.match
    m.state = replace(m.state, is_break=False, groups={0: "solids", 1: "stripes"})
    m.ball_in_hand = None
    m.on_table[:] = False
    for b, p in place.items():
        m.pos[m.ids.index(b)] = p
        m.on_table[m.ids.index(b)] = True
    app.state = start_turn(app.state)
    return app


def test_the_opening_aim_is_at_the_nearest_legal_ball_with_a_clear_path() -> None:
    app = solids_to_shoot({"cue": (0.5, 0.6), "1": (1.0, 0.6), "9": (0.75, 0.6),
                           "2": (1.1, 1.0), "8": (2.2, 0.3)})
    m = app.state.match
    # The 1 is nearer, but the 9 (not the shooter's) is in its way: the aim goes to the 2.
    assert app.state.stroke.angle == pytest.approx(math.degrees(math.atan2(0.4, 0.6)))
    m.pos[m.ids.index("9")] = (0.75, 0.2)  # out of the way: the nearest again
    app.state = start_turn(app.state)
    assert app.state.stroke.angle == pytest.approx(0.0)


def test_tab_aims_at_the_shooter_s_balls_in_turn_and_shift_tab_goes_back() -> None:
    """Solids to shoot, the cue ball in the middle: Tab aims at each solid's centre in turn
    going clockwise (as → turns the aim), never at a stripe or the 8; Shift+Tab retraces. A
    solid behind another ball is passed by."""
    place = {"cue": (1.27, 0.635), "1": (2.0, 0.635), "2": (1.27, 1.1), "3": (0.5, 0.2),
             "9": (1.27, 0.2), "8": (0.5, 1.0)}
    app = solids_to_shoot(place)
    m = app.state.match
    cue = np.array(place["cue"])

    def at(b: str) -> float:
        d = np.array(place[b]) - cue
        return math.degrees(math.atan2(d[1], d[0])) % 360.0

    put(app, stroke=replace(app.state.stroke, angle=at("1")))
    seen = []
    for _ in range(3):
        app.key(Key("tab"), 1.0)
        seen.append(app.state.stroke.angle)
    assert seen == pytest.approx([at("3"), at("2"), at("1")])  # clockwise: angles falling
    back = []
    for _ in range(3):
        app.key(Key("tab", shift=True), 2.0)
        back.append(app.state.stroke.angle)
    assert back == pytest.approx([at("2"), at("3"), at("1")])
    assert "Tab next ball" in screen_text(app.cells(120, 40)[0])
    # A stripe between the cue ball and the 2: the 2 cannot be hit first, and is passed by.
    m.pos[m.ids.index("9")] = (1.27, 0.9)
    seen = []
    for _ in range(2):
        app.key(Key("tab"), 3.0)
        seen.append(app.state.stroke.angle)
    assert seen == pytest.approx([at("3"), at("1")])
    # The 3 down, the 2 behind the stripe: the 1 is the only clear one, and Tab says that.
    m.on_table[m.ids.index("3")] = False
    app.key(Key("tab"), 3.5)
    assert app.state.stroke.angle == pytest.approx(at("1"))
    text = " ".join(screen_text(app.cells(120, 40)[0]).split())
    assert "no other ball you may hit has a clear path" in text, text
    # The 2 down too: the 1 alone, already aimed at. Tab says so, and leaves the aim.
    m.on_table[m.ids.index("2")] = False
    app.key(Key("tab"), 4.0)
    assert app.state.stroke.angle == pytest.approx(at("1"))
    assert "no other ball to aim at" in screen_text(app.cells(120, 40)[0])
    app.key(Key("right"), 5.0)  # the aim moved: the note, answered, goes
    assert "no other ball to aim at" not in screen_text(app.cells(120, 40)[0])
    # A stripe between the cue ball and the 1: Tab names it, in the way of the only ball.
    m.pos[m.ids.index("9")] = (1.6, 0.635)
    put(app, stroke=replace(app.state.stroke, angle=at("1")))
    app.key(Key("tab"), 6.0)
    assert app.state.stroke.angle == pytest.approx(at("1"))
    text = " ".join(screen_text(app.cells(120, 40)[0]).split())
    assert "the 9 is in the way of the 1, the only ball you may hit: a cushion first?" in text, \
        text


# -------------------------------------------------------------------- the computer's turn

THREE_TOP_RIGHT = PlanNote(PlanAim.POT, ball="3", pocket="foot_left")


def cpu_to_shoot(monkeypatch, note=THREE_TOP_RIGHT):
    """An 8-ball table where the computer is to shoot a plan of our own (no ball in hand)."""
    from termpool import ai

    plan = ai.Plan(1.5, 20.0, 0.0, 0.2, None, 1.0, note)
    monkeypatch.setattr(ai.Computer, "shot", lambda *a, **k: plan)
    app = app_for(mode="8ball", opponent="cpu")
    app.state.match.state = replace(app.state.match.state, shooter=1, is_break=False)
    app.state.match.ball_in_hand = None
    app.state = start_turn(app.state)
    assert app.state.phase is Phase.CPU
    return app, plan


def test_the_computer_shows_its_aim_and_plan_for_1_2_s_then_keeps_its_words(monkeypatch):
    app, plan = cpu_to_shoot(monkeypatch)
    t, aimed = 0.0, None
    while app.state.phase is Phase.CPU:
        app.tick(t)
        screen = screen_text(app.cells(120, 40)[0])
        if isinstance(app.state.part, Aiming):
            assert "Computer's plan: the 3 in the top-right corner pocket" in screen
            assert aid.prediction(app.state) is not None and "o" in screen  # its ghost ball
            if aimed is None and app.state.stroke.angle == plan.angle:
                aimed = t
        t += 1 / 60
    assert aimed is not None and app.state.part.struck_at - aimed >= 1.2
    while app.state.phase is Phase.RUN:  # its words stay up while the shot runs ...
        shown = screen_text(app.cells(120, 40)[0])
        assert "Computer's plan: the 3 in the top-right corner pocket" in shown
        app.tick(t)
        t += 1 / 60
    # ... and when it is over, after the verdict, until the next shot: in the past, so that
    # on your turn it does not read as a shot still to come
    assert app.state.message[1][0] == "Computer's plan was: the 3 in the top-right corner pocket"
    assert len(app.state.message) == 2
    shown = screen_text(app.cells(120, 40)[0])
    assert "Computer's plan was: the 3 in the top-right corner pocket" in shown
    assert "Computer's plan: " not in shown


def test_a_second_computer_shot_shows_only_its_own_plan_and_names_its_ball(monkeypatch):
    app, plan = cpu_to_shoot(monkeypatch)
    t = 0.0
    while app.state.phase in (Phase.CPU, Phase.RUN):
        app.tick(t)
        t += 1 / 60
    verdict = app.state.message[0]
    m = app.state.match
    m.state = replace(m.state, shooter=1)
    m.ball_in_hand = None
    m.on_table[:] = False
    for b, p in {"cue": (0.5, 0.6), "3": (1.0, 0.6), "8": (0.5, 1.0)}.items():
        m.pos[m.ids.index(b)] = p
        m.on_table[m.ids.index(b)] = True
    monkeypatch.setattr(__import__("termpool").ai.Computer, "shot",
                        lambda *a, **k: plan._replace(angle=0.0,
                                                      note=PlanNote(PlanAim.POT, ball="3",
                                                                    pocket="side_left"),
                                                      target="3"))
    app.state = start_turn(app.state)
    stroke(app, angle=90.0)  # its stick starts away from its aim, on the 8
    app.tick(t)
    app.tick(t + 0.1)  # it has its new plan; the old one is gone, the verdict stays
    assert app.state.message == (verdict,
                                 ("Computer's plan: the 3 in the top side pocket", "turn"))
    # Its plan's ball from the start, the one its note names: not the 8 its stick is on.
    assert app.state.stroke.angle != 0.0
    assert "Computer is aiming at the 3\n" in screen_text(app.cells(120, 40)[0])
    app.tick(t + 0.2)  # the first frame with its plan: the stick starts to turn
    app.tick(t + 0.2 + 0.7)
    assert app.state.stroke.angle == 0.0 and "Computer is aiming at the 3" in \
        screen_text(app.cells(120, 40)[0])


def test_the_computer_names_its_plan_s_ball_even_where_its_aim_meets_another(monkeypatch):
    # Its aim's error sends the cue ball at the 8, but its plan (and note) is the 3: the
    # status names the 3; without a ball to name it says so plainly; the break is a break.
    app, base = cpu_to_shoot(monkeypatch)
    m = app.state.match
    m.on_table[:] = False
    for b, p in {"cue": (0.5, 0.6), "3": (1.0, 0.6), "8": (0.5, 1.0)}.items():
        m.pos[m.ids.index(b)] = p
        m.on_table[m.ids.index(b)] = True
    from termpool import ai

    for plan, said in ((base._replace(angle=90.0, target="3"), "Computer is aiming at the 3\n"),
                       (base._replace(angle=90.0), "Computer is aiming\n"),
                       (base._replace(angle=90.0, kind="break", note=PlanNote(PlanAim.BREAK)),
                        "Computer is about to break\n")):
        monkeypatch.setattr(ai.Computer, "shot", lambda *a, plan=plan, **k: plan)
        app.state = start_turn(app.state)
        put(app, stroke=replace(app.state.stroke, angle=90.0))
        app.tick(0.0)
        app.tick(0.1)
        app.tick(1.0)  # on its aim, which meets the 8
        assert app.state.stroke.angle == 90.0
        pred = aid.prediction(aid.refresh(app.state))
        assert pred is not None and m.ids[pred.ball] == "8"
        assert said in screen_text(app.cells(120, 40)[0])


def test_the_computer_s_thinking_time_does_not_eat_its_aim(monkeypatch):
    # Its plan takes a second of wall time, so the next frame comes a second after the last:
    # the turn and the 1.2 s hold are timed from the first frame that shows the plan.
    app, plan = cpu_to_shoot(monkeypatch)
    app.tick(0.0)
    app.tick(0.1)  # it plans (here at once; in play this tick blocks for about a second)
    shown = 1.1
    t, aimed = shown, None
    while app.state.phase is Phase.CPU:
        app.tick(t)
        if aimed is None and app.state.stroke.angle == plan.angle:
            aimed = t
        t += 1 / 60
    assert aimed - shown >= CPU_AIM_S - 1e-9
    assert app.state.part.struck_at - aimed >= CPU_SHOW_S - 1e-9


def test_a_key_skips_the_computer_s_wait(monkeypatch):
    app, plan = cpu_to_shoot(monkeypatch)
    app.tick(0.0)
    app.tick(0.1)  # it has its plan, and starts turning its stick
    assert isinstance(app.state.part, Aiming)
    app.key(Key("x"), 0.2)
    app.tick(0.2)
    assert app.state.phase is Phase.RUN and app.state.part.struck_at == 0.2
    assert shots(app) == [] and app.state.match.running.shot.angle == plan.angle


def test_the_computer_says_what_it_chose(monkeypatch):
    # After the human's push-out, the computer shoots or passes, and says which.
    app = app_for(mode="9ball", opponent="cpu")
    app.state.match.option = "shoot_or_pass"
    app.state.match.state = replace(app.state.match.state, shooter=1, is_break=False)
    app.state.match.ball_in_hand = None
    app.state = start_turn(app.state)
    for k in range(5):
        app.tick(k / 60)
    assert app.state.match.option is None
    words = screen_text(app.cells(120, 40)[0])
    assert "Computer chose to shoot" in words
    # After an illegal break the computer accepts the table, in words too.
    app = app_for(mode="8ball", opponent="cpu")
    app.state.match.option = "rerack_or_accept"
    app.state.match.state = replace(app.state.match.state, shooter=1, is_break=False)
    app.state = start_turn(app.state)
    for k in range(5):
        app.tick(k / 60)
    assert "Computer chose to accept the table" in screen_text(app.cells(120, 40)[0])


# ------------------------------------------------------------------------------ the table

def test_racks_differ_from_game_to_game_unless_a_seed_is_given(tmp_path) -> None:
    racks = set()
    seeds = set()
    for _ in range(3):
        app = App(Options(mode="8ball", opponent="human", colors="mono"))
        racks.add(app.state.match.pos.round(9).tobytes())
        seeds.add(app.state.match.seed)
    assert len(racks) == 3 and len(seeds) == 3
    app = App(Options(mode="8ball", opponent="human", colors="mono"))
    first = app.state.match.pos.copy()
    # A new game (N on the game-over screen) deals anew.
    app.state = new_match(app.state, "8ball", "human")
    assert not np.array_equal(app.state.match.pos, first)
    same = [App(Options(mode="9ball", colors="mono", seed=7)).state.match.pos for _ in range(2)]
    assert np.array_equal(*same)
    # The seed goes into the record, and deals the same rack again.
    rec = tmp_path / "m.json"
    p = cli("play", "--headless", "--mode", "8ball", "--opponent", "human", "--keys", "-",
            "--record", str(rec), stdin="enter space wait 20")
    assert p.returncode == 0, p.stderr
    data = json.loads(rec.read_text())
    from termpool.game import Match

    again = Match("8ball", seed=data["match"]["seed"])
    first_scene = {b["id"]: (b["x"], b["y"]) for b in data["shots"][0]["scene"]["balls"]}
    assert all(first_scene[b] == tuple(again.pos[k]) for k, b in enumerate(again.ids)
               if b != "cue")


@pytest.mark.parametrize("cols, rows, numbered", [(200, 60, True), (160, 50, True),
                                                  (120, 40, False)])
def test_balls_three_cells_wide_carry_their_numbers(cols, rows, numbered) -> None:
    from termpool.ui.palette import ball_style

    app = app_for(mode="9ball", opponent="human", colors="truecolor")
    # Spread the rack out so that no two balls share a cell row and column span.
    for k in range(1, len(app.state.match.ids)):
        app.state.match.pos[k] = (0.4 + 0.2 * k, 0.3 + 0.07 * k)
    chars, fg, bg = app.cells(cols, rows)
    lay = layout(cols, rows, app.state.match.table)
    wide = 2 * BALL_RADIUS * lay.scale >= 3
    assert wide == numbered
    for k, b in enumerate(app.state.match.ids):
        if b == "cue":
            continue
        x, y = lay.to_pixels(*app.state.match.pos[k])
        r = int(y) // 2
        line = "".join(chars[r])
        at = line.find(b, int(x) - 2)
        if not numbered:
            assert at < 0 or abs(at - x) > 3  # no number on a two-cell ball
            continue
        assert 0 <= at and abs(at + len(b) / 2 - x) <= 1.0, (b, line)
        assert (bg[r, at] == ball_style(b).colour.rgb).all()  # on the ball's own colour


def test_the_called_pocket_is_marked_on_the_table_and_follows_c() -> None:
    from termpool.ui.palette import CALL_C

    app = eight_on_the_8(app_for(mode="8ball", opponent="human", colors="truecolor"))
    lay = layout(120, 40, app.state.match.table)

    def marked():
        _, fg, bg = app.cells(120, 40)
        hits = (fg == CALL_C.rgb).all(axis=2) | (bg == CALL_C.rgb).all(axis=2)
        rr, cc = np.nonzero(hits)
        holes = app.state.match.table.hole_c.reshape(-1, 2)
        px = np.array([lay.to_pixels(*h) for h in holes])
        near = [np.hypot(cc + 0.5 - px[k, 0], 2 * rr + 1 - px[k, 1]).min() for k in range(6)]
        return int(np.argmin(near)), len(rr)

    k, n = marked()
    assert n > 0 and app.state.match.table.hole_names[k] == aid.called(app.state)[1]
    app.key(Key("c"), 1.0)
    k2, _ = marked()
    assert k2 != k and app.state.match.table.hole_names[k2] == aid.called(app.state)[1]
    mono = eight_on_the_8(app_for(mode="8ball", opponent="human"))
    assert "*" in screen_text(mono.cells(120, 40)[0])


def test_the_head_string_shows_while_the_ball_in_hand_must_stay_behind_it() -> None:
    from termpool.ui.palette import GUIDE_C

    for mode, kitchen in (("8ball", True), ("practice", False)):
        app = app_for(mode=mode, opponent="human", colors="truecolor")
        assert app.state.phase is Phase.PLACE
        lay = layout(120, 40, app.state.match.table)
        chars, fg, bg = app.cells(120, 40)
        guide = (fg == GUIDE_C.rgb).all(axis=2) | (bg == GUIDE_C.rgb).all(axis=2)
        col = int(lay.to_pixels(app.state.match.table.length / 4, 0.0)[0])
        rows = np.nonzero(guide[:, col])[0]
        if kitchen:
            assert len(rows) >= 0.4 * lay.ph / 2  # dotted, from rail to rail
            assert guide.sum() == guide[:, col].sum()  # one straight column
        else:
            assert not guide.any()
    mono = app_for(mode="8ball", opponent="human")
    text = screen_text(mono.cells(120, 40)[0]).splitlines()
    table = mono.state.match.table
    col = int(layout(120, 40, table).to_pixels(table.length / 4, 0.0)[0])
    assert sum(line[col:col + 1] == ":" for line in text) >= 10


# ------------------------------------------------------------------- the panel and words

def grouped(app: App, frames_won=(0, 0)) -> App:
    from dataclasses import replace

    m = app.state.match
    m.state = replace(m.state, is_break=False, groups={0: "solids", 1: "stripes"})
    m.ball_in_hand = None
    m.scores = list(frames_won)
    put(app, part=Aim())
    return app


def panel_text(app: App, cols: int, rows: int) -> list[str]:
    lay = layout(cols, rows, app.state.match.table)
    text = screen_text(app.cells(cols, rows)[0]).split("\n")
    c, r, w, _ = lay.panel_rect
    return [line[c:c + w] for line in text[r:]]


@pytest.mark.parametrize("colors", ["mono", "256"])
@pytest.mark.parametrize("frames", [1, 3])
def test_at_80x24_both_players_groups_are_listed_whole(colors, frames) -> None:
    for opponent in ("cpu", "human"):
        app = grouped(app_for(mode="8ball", opponent=opponent, colors=colors, frames=frames))
        stroke(app, side=0.1, top=-0.2)
        panel = panel_text(app, 80, 24)
        rows = " ".join(panel)
        for k in range(1, 16):
            if k != 8:
                assert f"{k}" in rows.replace("10", " ").replace("11", " ") or k > 9
        for p in (0, 1):  # each player's row holds all their balls, in order
            row = next(line for line in panel if app.state.match.players[p] in line)
            want = "1 2 3 4 5 6 7" if p == 0 else "9 10 11 12 13 14 15"
            got = " ".join(row.replace("●", " ").replace("◐", " ").split())
            assert want in got, row
            if frames > 1:
                assert "0/3" in row
        name = app.state.match.players[0]
        assert any(line.strip().startswith(f"{name} to shoot") for line in panel)
        # the spin, in words where no face fits
        assert "tip: side +0.1, top -0.2" in " ".join(rows.split())


def test_at_200x60_the_spin_readout_shows() -> None:
    for colors, want in (("truecolor", ("side +0.3", "top -0.1")),
                         ("mono", ("tip: side +0.3, top -0.1",))):
        app = grouped(app_for(mode="8ball", opponent="cpu", colors=colors))
        put(app, message=(("Computer: 12 in the bottom-left corner pocket", "dim"),
                          ("legal break: the 6 and the 7 pocketed; the table is open",
                           "plain")))
        stroke(app, side=0.3, top=-0.1)
        for size in ((200, 60), (120, 40), (100, 32)):
            text = " ".join(" ".join(panel_text(app, *size)).split())
            for w in want:
                assert w in text, (size, colors)


@pytest.mark.parametrize("size", [(40, 12), (45, 14), (60, 16)])
@pytest.mark.parametrize("mode", ["release", "repeat", "classic"])
def test_small_screens_keep_the_key_help_whole(size, mode) -> None:
    from termpool.ui.panel import fit_hint
    from termpool.ui.view import hint_lines

    app = grouped(app_for(mode="8ball", opponent="human", input_mode=mode))
    hint = panel_text(app, *size)[-1].strip()
    parts = [t if isinstance(t, str) else t for t, _ in hint_lines(app.state)]
    assert hint == fit_hint(hint_lines(app.state), size[0] - 2)  # the panel's text width
    assert hint.endswith("Q quit") and hint.startswith("←→ aim")
    assert {"release": "Space:hold", "repeat": "Space:hold",
            "classic": "Space:meter"}[mode] in hint.replace(": ", ":").replace(", let go", "")
    assert parts  # every piece shown is whole: the line is pieces joined, none cut
    for piece in hint.split("  ") if "  " in hint else [hint]:
        assert piece


def test_a_race_s_end_gives_the_match_s_score() -> None:
    app = app_for(mode="8ball", opponent="cpu", frames=3)
    app.state.match.scores = [1, 3]
    app.state.match.winner = 1
    app.state = start_turn(app.state)
    assert app.state.phase is Phase.OVER
    text = screen_text(app.cells(80, 24)[0])
    assert "Computer wins the match 3-1" in text, text


def test_game_over_says_you_win_and_q_quits_at_once() -> None:
    app = app_for(mode="8ball", opponent="cpu")
    app.state.match.winner = 0
    put(app, message=(("the 8 went into the top-right corner pocket: You win", "good"),))
    app.state = start_turn(app.state)
    assert app.state.phase is Phase.OVER
    text = screen_text(app.cells(120, 40)[0])
    assert "You win!" in text and "You wins" not in text
    app.key(Key("q"), 1.0)
    assert app.done and app.state.box is None  # no second "Quit termpool?" on top
    app = app_for(mode="8ball", opponent="human")
    app.state.match.winner = 1
    app.state = start_turn(app.state)
    assert "Player 2 wins!" in screen_text(app.cells(120, 40)[0])


# A foul from a real game, three lines at 80 columns, under "ball in hand anywhere".
LONG_VERDICT = ("Foul: the cue ball hit the 14 first; with the solids cleared it must be the "
                "8; no ball reached a cushion after contact and nothing was pocketed; you have "
                "ball in hand")


def test_a_verdict_too_long_for_the_panel_ends_in_an_ellipsis() -> None:
    app = app_for(mode="8ball")
    put(app, message=((LONG_VERDICT, "foul"),))
    text = screen_text(app.cells(45, 14)[0])
    assert any(s.rstrip().endswith("…") for s in text.splitlines())
    assert "ball in hand" in text  # the status still says it


def test_at_80x24_a_verdict_three_lines_long_takes_the_keys_row_to_read_whole() -> None:
    # What the rule said, whole, rather than the key bar (H still opens the help); the key
    # bar comes back with the next status that fits beside it.
    app = app_for(mode="8ball")
    put(app, message=((LONG_VERDICT, "foul"),))
    rows = [s.strip() for s in panel_text(app, 80, 24)]
    assert LONG_VERDICT in " ".join(" ".join(rows).split()), rows
    assert not any("…" in s for s in rows) and "to break · ball in hand" in " ".join(rows)
    put(app, message=(("nothing pocketed: your turn", "plain"),))
    assert panel_text(app, 80, 24)[-1].strip().endswith("Q quit")


# ----------------------------------------------------- power on terminals without releases

def test_a_tap_without_key_releases_starts_the_meter_from_nothing() -> None:
    ch = PowerCharge("repeat")
    assert ch.key(Key("space"), 10.0) is None
    assert ch.waiting and ch.level(10.5) == 0.0  # a tap or a hold: nothing known yet
    t = 10.0 + PowerCharge.INITIAL_DELAY_MAX + 0.2  # no repeat came: a tap
    assert ch.poll(t) is None and ch.fallback and not ch.waiting
    # The meter rises from 0 at the moment the tap was known, not from the press.
    known = 10.0 + PowerCharge.INITIAL_DELAY_MAX
    assert ch.level(known) == 0.0
    assert ch.level(t) == pytest.approx(0.2 / ch.full_time)
    power = ch.key(Key("space"), known + 0.1)  # a quick second press: a soft shot
    assert power == pytest.approx(0.1 / ch.full_time)


def test_the_screen_says_what_a_tap_is_waiting_for() -> None:
    app = app_for(input_mode="repeat")
    run_script(app, "enter wait 0.2", legacy=True)
    app.key(Key("space"), 1.0)
    app.tick(1.4)
    text = screen_text(app.cells(80, 24)[0])
    assert "keep space down to charge, or let go for a meter" in text
    assert "release space" not in text and "power 0%" not in text
    app.tick(1.0 + PowerCharge.INITIAL_DELAY_MAX + 0.06)
    text = screen_text(app.cells(80, 24)[0])
    assert "power 5%" in text and "space again to strike" in text


def test_power_set_with_a_digit_does_not_carry_into_the_next_game() -> None:
    for power in ("hold", "digits"):
        app = app_for(mode="8ball", opponent="human", power=power)
        run_script(app, "enter 2 space wait 20")
        assert shots(app)[0]["speed"] == power_to_speed(0.2)
        app.key(Key("2"), 100.0)  # set for the next shot ...
        app.state.match.winner = 0
        app.state = start_turn(app.state)
        app.key(Key("n"), 101.0)  # ... but a new game starts afresh
        assert app.state.controls.charge.preset_level == (0.5 if power == "digits" else None)
        assert app.state.last_power == 0.5


def test_the_aid_takes_the_shooter_s_last_power_and_says_it_in_few_words() -> None:
    app = app_for(mode="8ball", opponent="human")
    run_script(app, "enter")
    text = screen_text(app.cells(120, 40)[0])
    assert "aid at 50% power · first ball" in text  # half, before any shot
    m = app.state.match
    m.state = replace(m.state, is_break=False)  # (a break's power is the break's alone)
    run_script(app, "space-hold 0.9 wait 20")
    struck = round(100 * app.state.last_power)
    assert struck != 50
    for shooter, said in ((0, f"aid at {struck}% power · "),  # the breaker's own
                          (1, "aid at 50% power · ")):  # not the other's
        m.state = replace(m.state, shooter=shooter)
        m.ball_in_hand = None
        app.state = start_turn(app.state)
        assert said in screen_text(app.cells(120, 40)[0])


# -------------------------------------------------------------- what the panel keeps in view

def _to_the_computer(app: App) -> float:
    """The player breaks and the balls stop; the computer's turn, its plan made."""
    app.key(Key("enter"), 0.0)
    app.key(Key("space"), 1.0)
    app.key(Key("space", "release"), 2.0)
    t = 2.0
    while not isinstance(app.state.part, Aiming) and t < 100:
        t += 1 / 30
        app.tick(t)
    assert app.state.phase is Phase.CPU
    return t


def _computer_turns(app: App, script: str):
    """Play `script` (the player's break) and then until the player's turn comes back;
    yield (part, verdict of the shot last played, 80x24 screen) at each frame of the
    computer's aim and of its shots running."""
    events = parse_script(script)
    for t, key in events:
        app.key(key, t)
    last = None
    while t < 300:
        t += 1 / 30
        before = app.state.phase
        app.tick(t)
        s = app.state
        if before is Phase.RUN and s.phase is not Phase.RUN:  # a shot judged: its verdict
            last = s.message[0]
        if s.phase in (Phase.AIM, Phase.PLACE, Phase.OVER, Phase.OPTION):
            return
        if isinstance(s.part, Aiming) or (s.phase is Phase.RUN and shooter_is_cpu(s)):
            yield s.part, last, screen_text(app.cells(80, 24)[0])


def test_through_the_computers_run_its_last_verdict_keeps_its_row_above_its_plan() -> None:
    """A pro computer running balls: from thinking to aiming to the next shot, the verdict
    on its last shot stays on one row of the panel, its plan (old, then new) below it."""
    app = app_for(mode="8ball", opponent="cpu", level="pro", seed=1)
    for key in parse_script("enter 0 space"):
        app.key(key[1], key[0])
    t, rows, seen = 0.0, {}, 0
    while t < 300 and app.state.phase not in (Phase.AIM, Phase.PLACE, Phase.OVER):
        t += 1 / 30
        app.tick(t)
        s = app.state
        if s.phase is not Phase.CPU or not shooter_is_cpu(s):
            continue
        lines = screen_text(app.cells(120, 40)[0]).splitlines()
        verdict = s.message[0][0][:40]
        at = [k for k, line in enumerate(lines) if verdict in line]
        plan = [k for k, line in enumerate(lines) if "Computer's plan" in line]
        if at and plan:
            assert at[0] < plan[0], lines[-8:]
            rows.setdefault(verdict, set()).add(at[0])
            seen += 1
    assert seen and all(len(r) == 1 for r in rows.values()), rows


def test_the_verdict_in_view_through_the_computers_turn_is_the_last_shots() -> None:
    # A full-power break and a pro computer that runs balls: while it aims at each and while
    # each shot runs, the panel shows the verdict on the shot just played (its own last
    # pot), not the player's older verdict on the break.
    app = app_for(mode="8ball", opponent="cpu", level="pro", seed=1)
    own = set()
    for _, verdict, text in _computer_turns(app, "enter 0 space"):
        assert verdict is not None and verdict in app.state.message
        assert verdict[0][:30] in text, (verdict, text)
        if "Computer continues" in verdict[0]:
            own.add(verdict)
    assert len(own) >= 2  # it aimed after at least two of its own pots


def test_the_computer_announces_its_answer_to_an_illegal_break() -> None:
    # A 10% break is illegal: the computer accepts the table or has it re-racked, and its
    # choice replaces the break's verdict (which asks for it) as a player's does.
    app = app_for(mode="8ball", opponent="cpu", level="pro", seed=1)
    seen = 0
    for _, _, text in _computer_turns(app, "enter 1 space"):
        assert "Computer chose to" in text and "may accept the table" not in text, text
        seen += 1
    assert seen


def test_the_players_turn_shows_the_power_line_before_the_computers_plan() -> None:
    app = app_for(mode="8ball", opponent="cpu", seed=4)
    app.key(Key("enter"), 0.0)
    run_script(app, "")
    note = (("Computer: 3 in the bottom side pocket", "turn"),)
    put(app, shot_note=note, message=(*note, ("nothing pocketed: your turn", "plain")))
    assert app.state.phase in (Phase.AIM, Phase.PLACE)
    put(app, part=Aim())
    lines = screen_text(app.cells(80, 24)[0]).splitlines()[-5:]
    assert lines[1].strip().startswith("You to")
    assert lines[2].strip().startswith("aid at 50% power") and "first ball" in lines[2]
    assert lines[3].strip().startswith("nothing pocketed: your turn")


@pytest.mark.parametrize("cols, rows", [(120, 40), (100, 32), (160, 50)])
def test_the_second_players_name_stays_put_from_ball_in_hand_to_aim_to_charge(cols, rows):
    app = app_for(mode="8ball", opponent="human", colors="256")

    def column() -> int:
        (line,) = [x for x in screen_text(app.cells(cols, rows)[0]).splitlines()
                   if "Player 1" in x and "Player 2" in x]
        return line.index("Player 2")

    where = [column()]  # ball in hand
    app.key(Key("enter"), 0.0)
    where.append(column())  # aiming, the spin face up
    app.key(Key("space"), 1.0)
    app.tick(1.5)
    assert app.state.controls.charge.active
    where.append(column())  # charging, the power meter up too
    assert len(set(where)) == 1, where


def test_an_open_table_names_its_balls_in_a_spare_row_at_80x24():
    from termpool.ui.view import panel_info

    app = app_for(mode="8ball", opponent="human", colors="256")
    app.key(Key("enter"), 0.0)
    chars, fg, bg = app.cells(80, 24)
    lines = screen_text(chars).splitlines()
    (row,) = [r for r, line in enumerate(lines) if line.strip().startswith("balls ")]
    assert lines[row].split()[1:] == [str(n) for n in range(1, 16)]
    # Each number in its ball's colour, as the players' lines show a group's balls.
    from termpool.ui.panel import ball_tokens

    m = app.state.match
    want = ball_tokens(m.ids, [m.index(str(n)) for n in range(1, 16)], False)
    col = lines[row].index("balls ") + len("balls")
    for text, f, b in want:
        col += 1
        assert "".join(chars[row, col:col + len(text)]) == text
        assert tuple(bg[row, col]) == tuple(b) and tuple(fg[row, col + len(text) - 1]) == f
        col += len(text)
    # Once the groups are set, the players' lines show them instead.
    app.state.match.state = app.state.match.state.__class__(mode="8ball", shooter=0,
                                                groups={0: "solids", 1: "stripes"})
    assert panel_info(app.state).legend == []


def test_each_player_starts_their_turn_at_their_own_power_never_the_other_s() -> None:
    for power in ("hold", "digits"):
        app = app_for(mode="8ball", opponent="human", power=power)
        run_script(app, "enter 9 space wait 20")  # player 1 breaks at 90% ...
        m = app.state.match
        m.state = replace(m.state, shooter=1, is_break=False)  # ... and the turn passes
        m.ball_in_hand = None
        app.state = start_turn(app.state)
        charge = app.state.controls.charge
        # Player 2 has not shot: the default power, not the 90% of player 1's break.
        assert charge.preset_level == (0.5 if power == "digits" else None)
        assert app.state.last_power == 0.5
        assert "90%" not in screen_text(app.cells(120, 40)[0])
        app.key(Key("3"), 50.0)
        app.key(Key("space"), 50.1)  # a soft 30% ...
        app.key(Key("space", kind="release"), 50.2)
        t = 50.2
        while app.state.phase is Phase.RUN:
            t += 1 / 30
            app.tick(t)
        assert shots(app)[-1]["speed"] == power_to_speed(0.3)
        m.state = replace(m.state, shooter=0)  # ... and player 1's turn again: their 90%,
        m.ball_in_hand = None  # (a break's power set with a digit is the break's: holding,
        app.state = start_turn(app.state)  # and the aid at half, unless digits are the only
        # way)
        assert app.state.controls.charge.preset_level == (0.9 if power == "digits" else None)
        assert app.state.last_power == (0.9 if power == "digits" else 0.5)
        if power == "hold":
            assert "aid at 50% power" in screen_text(app.cells(120, 40)[0])
        m.state = replace(m.state, shooter=1)  # player 2's 30% is theirs
        app.state = start_turn(app.state)
        assert app.state.controls.charge.preset_level == 0.3


@pytest.mark.parametrize(("cols", "rows"), [(50, 16), (60, 20), (80, 24), (120, 40)])
@pytest.mark.parametrize("name", ["Ann", "Maximilian Alexander von Habsburg-Lothringen"])
def test_whose_turn_and_the_verdict_always_show(cols, rows, name) -> None:
    app = app_for(mode="8ball", opponent="human", player1=name, player2=name + " II")
    run_script(app, "enter space-hold 1.3 wait 12")
    s = app.state
    assert s.phase in (Phase.AIM, Phase.PLACE, Phase.OPTION) and s.message
    if s.phase is Phase.OPTION:
        return
    text = " ".join(screen_text(app.cells(cols, rows)[0]).split())
    shooter = s.match.players[s.match.shooter]
    what = "to shoot" if s.phase is Phase.AIM else "to shoot · ball in hand"
    whose = f"{shooter} {what}"
    verdict = s.message[-1][0]
    for said in (whose, verdict):  # each in view, whole or cut to its first row ("…")
        head = said[:cols - 20].rsplit(" ", 1)[0]
        assert head in text, (said, text)


def test_a_name_too_long_for_its_half_of_the_row_shows_as_much_as_fits() -> None:
    name = "Maximilian Alexander von Habsburg-Lothringen"
    app = app_for(mode="8ball", opponent="human", player1=name, player2="Bob")
    run_script(app, "enter space-hold 1.3 wait 12")
    text = screen_text(app.cells(50, 16)[0])
    assert "Maximilian Alex" in text and "▶ Bob" in text


def aid_done(app: App) -> str:
    """The aid's prediction of the aim run to its end; the 120x40 screen's text."""
    app.state = aid.refresh(app.state)
    while not app.state.aid.job.done:
        app.state.aid.job.run(1000)
    return " ".join(screen_text(app.cells(120, 40)[0]).split())


def test_the_aid_warns_of_a_shot_that_loses_the_game_or_fouls() -> None:
    app = app_for(mode="8ball", opponent="human")
    app.key(Key("enter"), 0.0)
    eight_on_the_8(app)  # the solids cleared: the 8 is next, called where the aim sends it
    m = app.state.match
    m.state = replace(m.state, pocketed=tuple("1234567"))  # as the referee keeps them
    hole = m.table.hole_c.reshape(-1, 2)[list(m.table.hole_names).index("head_left")]
    u = np.array([-1.0, 1.0]) / math.sqrt(2.0)  # cue, 8 and the corner's centre in line
    m.pos[m.index("8")] = hole - 0.35 * u
    m.pos[0] = hole - 0.85 * u
    stroke(app, angle=135.0)
    assert "As aimed" not in aid_done(app)  # the 8 in the called pocket: a win, no warning
    assert aid.foreseen(app.state).winner == 0
    app.key(Key("c"), 1.0)  # another pocket called: the 8 in this one loses
    text = aid_done(app)
    assert "As aimed: the 8 goes into the top-left corner pocket, not the called" in text
    m.on_table[m.index("1")] = True  # a solid still on: the 8 is not the shooter's ball
    m.state = replace(m.state, pocketed=tuple("234567"))
    m.pos[m.index("1")] = (1.2, 0.3)
    text = aid_done(app)
    assert aid.foreseen(app.state).winner == 1
    assert "As aimed: the cue ball hits the 8 first, not one of the solids; the 8 goes down " \
           "on a foul: Player 1 loses" in text
    m.state = replace(m.state, groups=None)  # an open table: the 8 first is a foul too
    assert "As aimed: the cue ball hits the 8 first, which is not allowed on an open table; " \
           "the 8 goes down on a foul: Player 1 loses" in aid_done(app)
    m.pos[m.index("8")] = (1.2, 0.6)  # the 1 where the 8 was: the aim meets it ...
    m.pos[m.index("1")] = hole - 0.35 * u
    m.state = replace(m.state, groups={0: "stripes", 1: "solids"})  # ... not the shooter's
    text = aid_done(app)
    assert "As aimed, a foul: the cue ball hits the 1 first, not one of the stripes" in text
    m.state = replace(m.state, groups={0: "solids", 1: "stripes"})
    assert "As aimed" not in aid_done(app)  # their own ball: no warning


SMALL_SIZES = [(50, 16), (60, 20), (80, 24)]


@pytest.mark.parametrize(("cols", "rows"), SMALL_SIZES)
@pytest.mark.parametrize("in_game", [False, True])
def test_the_settings_screen_loses_nothing_on_a_small_screen(cols, rows, in_game) -> None:
    from termpool.ui.phases.boxes import open_settings
    from termpool.ui.settings import SETTINGS

    app = app_for(mode="8ball", opponent="human") if in_game else App(Options(colors="mono"))
    app.state = open_settings(app.state)
    for k, setting in enumerate(SETTINGS):
        put(app, box=replace(app.state.box, index=k))
        text = screen_text(app.cells(cols, rows)[0])
        lines = [x[x.index("│") + 1:x.rindex("│")].strip() for x in text.splitlines()
                 if x.count("│") >= 2]  # the box's insides
        assert any(x.startswith("▶ " + setting.label) for x in lines), (k, text)
        assert "↑↓ choose · ←→ or Enter change · Esc done" in text
        said = " ".join(x for x in lines if x)  # what the setting does, whole
        assert " ".join(setting.help.split()) in said or setting.kind == "name", (k, text)
        shown_ = sum(any(x.lstrip("▶ ").startswith(s.label) for x in lines) for s in SETTINGS)
        if shown_ < len(SETTINGS):  # a hint that there is more
            assert "↑ more" in text or "↓ more" in text
        if in_game:
            assert "a change marked * applies from the next game." in said


def test_the_stats_screen_scrolls_both_ways_and_says_so() -> None:
    text = ("a" * 60 + " THE END", *(f"line {n}" for n in range(30)))
    app = App(Options(colors="mono"))
    put(app, box=Stats(text))
    first = screen_text(app.cells(50, 16)[0])
    assert "THE END" not in first and "line 29" not in first
    assert "↑↓ ←→" in first and "more" in first  # the hint: more down and to the right
    for t in range(5):
        app.key(Key("right"), float(t))
    assert "THE END" in screen_text(app.cells(50, 16)[0])
    app.key(Key("end"), 10.0)
    for t in range(5):
        app.key(Key("left"), 10.0 + t / 10)
    assert "line 29" in screen_text(app.cells(50, 16)[0])
    app.key(Key("x"), 11.0)  # any other key closes it
    assert app.state.box is None


def at_the_push_out_question() -> App:
    """A 9-ball game between two players after its break and a push-out: the other player's
    question (shoot from here or pass the shot back) on show."""
    app = app_for(mode="9ball", opponent="human")
    run_script(app, "enter space-hold 1.2 wait 20")
    if app.state.phase is Phase.PLACE:
        app.key(Key("enter"), 100.0)
    run_script(app, "o space-hold 0.3 wait 20")
    assert app.state.phase is Phase.OPTION
    return app


@pytest.mark.parametrize(("cols", "rows"), [(50, 16), (80, 24), (120, 40)])
def test_the_push_out_question_leaves_the_cue_ball_and_the_balls_by_it_in_view(cols, rows):
    app = at_the_push_out_question()
    m = app.state.match
    centre = np.array([m.table.length / 2, m.table.width / 2])
    c = m.ids.index("cue")
    m.pos[c] = centre  # where a box in the middle of the screen would hide it
    lay = layout(cols, rows, m.table)
    x, y = lay.to_pixels(*centre)
    rx, ry = m.radius[c] * lay.sx, m.radius[c] * lay.sy
    cue = (int(x - rx), int(y - ry) // 2, int(x + rx) - int(x - rx) + 1,
           int(y + ry) // 2 - int(y - ry) // 2 + 1)  # the cue ball's cells
    chars = app.cells(cols, rows)[0]
    text = screen_text(chars)
    assert "s: shoot from here" in text and "p: pass the shot back" in text
    top = next(r for r, line in enumerate(text.splitlines()) if "┌" in line)
    left = text.splitlines()[top].index("┌")
    bottom = next(r for r, line in enumerate(text.splitlines()) if "┘" in line)
    right = text.splitlines()[bottom].index("┘")
    kc, kr, kw, kh = cue
    assert (bottom < kr or kr + kh <= top or right < kc or kc + kw <= left), (cue, text)


@pytest.mark.parametrize(("cols", "rows"), [(50, 16), (80, 24)])
@pytest.mark.parametrize("where", [(0.5, 0.5), (0.3, 0.5), (0.5, 0.3), (0.7, 0.7)])
def test_the_push_out_question_never_covers_the_players_row(cols, rows, where):
    # The cue ball with balls all about it, so that no place on the table keeps them all in
    # view: the box must still leave the players' row (whose call it is) alone.
    app = at_the_push_out_question()
    m = app.state.match
    c = m.ids.index("cue")
    at = np.array([m.table.length * where[0], m.table.width * where[1]])
    m.pos[c] = at
    others = [k for k in range(len(m.ids)) if k != c and m.on_table[k]]
    step = 2 * np.pi / len(others)
    for n, k in enumerate(others):  # a ring 2.5 diameters out
        m.pos[k] = at + 5 * m.radius[c] * np.array([np.cos(n * step), np.sin(n * step)])
    lay = layout(cols, rows, m.table)
    text = screen_text(app.cells(cols, rows)[0]).splitlines()
    assert "s: shoot from here" in "\n".join(text)
    _, row, _, _ = lay.panel_rect
    assert "Player 1" in text[row] and "Player 2" in text[row], "\n".join(text)


@pytest.mark.parametrize(("cols", "rows"), SMALL_SIZES)
def test_the_aid_s_warning_leaves_the_last_verdict_in_view(cols, rows) -> None:
    # The computer's shot said, then a foul aimed: both are in view, and whose turn it is.
    app = app_for(mode="8ball", opponent="cpu")
    app.key(Key("enter"), 0.0)
    eight_on_the_8(app)
    m = app.state.match
    m.state = replace(m.state, groups={0: "stripes", 1: "solids"})  # the 8 first: a foul
    put(app, message=(("Computer potted the 3: nothing else went down, your turn", "plain"),))
    stroke(app, angle=45.0)
    aid_done(app)
    assert aid.foreseen(app.state).foul is not None
    text = " ".join(screen_text(app.cells(cols, rows)[0]).split())
    assert "You to shoot" in text and "As aimed" in text, text
    assert "Computer potted the 3" in text, text


def cue_in_a_corner() -> App:
    """8-ball, solids to shoot: the cue ball alone in a corner of the table, the 3 and the 8
    far off."""
    app = app_for(mode="8ball", opponent="human")
    app.key(Key("enter"), 0.0)
    eight_on_the_8(app)
    m = app.state.match
    m.on_table[:] = False
    for b, p in {"cue": (0.3, 0.3), "3": (1.8, 0.9), "8": (2.0, 0.4)}.items():
        m.pos[m.index(b)] = p
        m.on_table[m.index(b)] = True
    m.state = replace(m.state, groups={0: "solids", 1: "stripes"},
                      pocketed=tuple(b for b in m.ids[1:] if b not in ("3", "8")))
    return app


def test_the_aid_warns_of_a_shot_that_meets_no_ball() -> None:
    # The cue ball alone in a corner of the table with the 3 and the 8 far off: aimed along
    # the head cushion softly it stops short of every ball, a foul; aimed at the 3, no warning.
    app = cue_in_a_corner()
    m = app.state.match
    put(app, last_power=0.1)
    stroke(app, angle=90.0)  # up the screen's short side, softly
    text = aid_done(app)
    pred = aid.prediction(app.state)
    assert pred.ball is None and pred.cue.end == "rest"
    assert "As aimed, a foul: the cue ball hits no ball" in text, text
    angle = math.degrees(math.atan2(0.9 - 0.3, 1.8 - 0.3))
    stroke(app, angle=angle)  # at the 3: a legal shot
    put(app, last_power=0.5)
    assert "As aimed" not in aid_done(app)
    assert m.ids[aid.prediction(app.state).ball] == "3"


def test_the_aid_says_when_it_sees_no_ball_within_its_cushions() -> None:
    # The same table: aimed along the long side past the 8, hard, the cue ball runs rail to
    # rail through the aid's cushions without meeting a ball. Nothing sure to judge (it may
    # meet one later), so no warning; the power line says what the aid saw.
    from termpool.ui.predict import MAX_CUSHIONS

    app = cue_in_a_corner()
    put(app, last_power=1.0)
    stroke(app, angle=0.0)
    text = aid_done(app)
    pred = aid.prediction(app.state)
    assert pred.ball is None and pred.cue.end == "cushion"
    assert f"no ball within {MAX_CUSHIONS} cushions" in text, text
    assert "As aimed" not in text
    angle = math.degrees(math.atan2(0.9 - 0.3, 1.8 - 0.3))
    stroke(app, angle=angle)  # at the 3: its name instead
    assert "no ball within" not in aid_done(app)


def test_in_practice_the_aid_warns_of_a_cue_ball_lost() -> None:
    # Practice has no fouls, but a cue ball sent into a pocket is a shot spoiled: said.
    app = app_for(mode="practice")
    app.key(Key("enter"), 0.0)
    m = app.state.match
    m.on_table[:] = False
    for b, p in {"cue": (0.3, 0.3), "3": (1.8, 0.9)}.items():
        m.pos[m.index(b)] = p
        m.on_table[m.index(b)] = True
    m.ball_in_hand = None
    m.state = replace(m.state, is_break=False)
    put(app, last_power=0.4)
    stroke(app, angle=225.0)  # straight into the corner pocket behind it
    text = aid_done(app)
    pred = aid.prediction(app.state)
    assert pred.cue.end == "pocket"
    said = f"As aimed: the cue ball goes into the {words.spoken_pocket(pred.cue.pocket)} " \
           "pocket: ball in hand"
    assert said in text, text
    stroke(app, angle=math.degrees(math.atan2(0.9 - 0.3, 1.8 - 0.3)))  # at the 3
    assert "As aimed" not in aid_done(app)
