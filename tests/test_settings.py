"""Settings: the one table, the file (round trip, malformed, unwritable), the flags over it for
one run, and the Settings screen from the menu and from pause."""

from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest
from unprivileged import as_nobody

from termpool import cli
from termpool.ui.app import App, Options
from termpool.ui.headless import screen_text
from termpool.ui.keys import Key
from termpool.ui.phases.boxes import open_settings
from termpool.ui.phases.turn import new_match
from termpool.ui.settings import (
    BY_KEY,
    DEFAULTS,
    MAX_NAME,
    SETTINGS,
    format_settings,
    load_settings,
    parse_settings,
    settings_path,
)
from termpool.ui.shots import power_to_speed
from termpool.ui.state import Pause, Run, shooter_is_cpu

ROOT = Path(__file__).resolve().parent.parent

# A value other than the default for every setting (names with what a name may hold).
CHANGED = {"level": "hard", "table": "7ft", "frames": 5, "theme": "classic",
           "three_foul": True, "eight_break": "rerack", "colors": "16",
           "aid": "ghost", "power": "digits", "bell": True, "fast": "computer", "records": False,
           "player1": "Zoë #1", "player2": "Bob = B"}


KEYS = [s.key for s in SETTINGS]  # the Settings screen's order (↓ steps through it)


def conf() -> Path:
    return settings_path()  # in the test's own config directory (conftest)


def write_conf(text: str) -> Path:
    p = conf()
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text)
    return p


# ------------------------------------------------------------------------------ the table

def test_the_table_offers_what_the_game_has() -> None:
    from termpool import ai
    from termpool.physics.table import PRESETS
    from termpool.rules.common import EIGHT_BREAKS
    from termpool.rules.words import THEMES
    from termpool.ui.output import DEPTHS
    from termpool.ui.predict import LEVELS as AID_LEVELS

    assert set(BY_KEY["level"].values) == set(ai.LEVELS)
    assert set(BY_KEY["table"].values) == set(PRESETS)
    assert set(BY_KEY["theme"].values) == set(THEMES)
    assert BY_KEY["colors"].values == ("auto", *DEPTHS)
    assert set(BY_KEY["aid"].values) == set(AID_LEVELS)
    assert BY_KEY["eight_break"].values == EIGHT_BREAKS
    assert set(CHANGED) == set(BY_KEY)  # the tests below cover every setting


def test_the_level_help_says_who_each_level_plays_like() -> None:
    text = BY_KEY["level"].help
    for level in BY_KEY["level"].values:
        after = text.split(f" {level} ", 1)
        assert len(after) == 2 and after[1].startswith("(a "), level  # "pro (a professional)"


def test_options_default_to_the_table() -> None:
    opts = Options()
    assert {k: getattr(opts, k) for k in DEFAULTS} == DEFAULTS


def test_the_settings_file_lives_beside_keys_conf(tmp_path) -> None:
    from termpool.ui.controls import config_path

    env = {"XDG_CONFIG_HOME": str(tmp_path)}
    assert settings_path(env) == config_path(env).parent / "settings.conf"


# ------------------------------------------------------------------------------ the file

def test_round_trip_of_every_setting() -> None:
    values, warnings = parse_settings(format_settings(CHANGED))
    assert warnings == [] and values == CHANGED
    values, warnings = parse_settings(format_settings(DEFAULTS))
    assert warnings == [] and values == DEFAULTS


def test_saved_settings_are_read_back_and_written_whole() -> None:
    store = load_settings()
    assert store.saved == DEFAULTS and store.warnings == [] and not store.path.exists()
    assert store.save(CHANGED) is None  # creates the config directory too
    again = load_settings()
    assert again.saved == CHANGED and again.warnings == []
    assert [p.name for p in store.path.parent.iterdir()] == ["settings.conf"]  # no temp left


def test_a_save_keeps_what_the_file_had_and_adds_the_changes() -> None:
    write_conf("level = easy\n")
    store = load_settings()
    assert store.save({"table": "8ft"}) is None
    assert load_settings().saved == {**DEFAULTS, "level": "easy", "table": "8ft"}


@pytest.mark.parametrize(("text", "line", "key", "says"), [
    ("level = expert", 1, "level", "must be one of easy, normal, hard, pro, not 'expert'"),
    ("\n\nframes = 0", 3, "frames", "from 1 to 1000, not '0'"),
    ("frames = 1001", 1, "frames", "from 1 to 1000"),
    ("frames = three", 1, "frames", "not 'three'"),
    ("bell = yes", 1, "bell", "must be on or off, not 'yes'"),
    ("player1 = " + "x" * (MAX_NAME + 1), 1, "player1", f"at most {MAX_NAME} characters"),
    ("player2 = a\x1bb", 1, "player2", "printable"),
    ("player2 = Zoë 🎱", 1, "player2", "one column wide"),
    ("player1 = 王小明", 1, "player1", "one column wide"),
    ("# ok\nlevle = hard", 2, "levle", "unknown setting 'levle'"),
    ("level = hard\nlevel = easy", 2, "level", "already set on line 1"),
    ("aid", 1, "aid", "expected 'key = value'"),
    ("= full", 1, "= full", "expected 'key = value'"),
])
def test_each_malformed_line_is_one_warning_naming_its_line_and_key(text, line, key,
                                                                    says) -> None:
    values, warnings = parse_settings(text + "\ntable = 8ft\n")
    assert len(warnings) == 1
    assert warnings[0].startswith(f"settings.conf line {line}: ")
    assert key in warnings[0] and says in warnings[0]
    assert values["table"] == "8ft"  # the good lines hold
    if key in BY_KEY and "already set" not in says:
        assert key not in values  # the bad key keeps its default


def test_a_file_that_is_not_text_or_not_a_file_is_one_warning_and_the_defaults() -> None:
    p = write_conf("")
    p.write_bytes(b"level = hard\n\xff\xfe\n")
    store = load_settings()
    assert store.saved == DEFAULTS and len(store.warnings) == 1
    assert "not UTF-8" in store.warnings[0] and "default settings" in store.warnings[0]
    p.unlink()
    p.mkdir()
    store = load_settings()
    assert store.saved == DEFAULTS and len(store.warnings) == 1
    assert "cannot read" in store.warnings[0]


def test_an_unwritable_config_directory_is_one_warning() -> None:
    write_conf("level = easy\n")
    d = conf().parent
    os.chmod(d, 0o555)
    try:
        said = as_nobody(lambda: load_settings().save({"level": "hard"}))
    finally:
        os.chmod(d, 0o755)
    assert "cannot save the settings" in said and "this game only" in said
    assert load_settings().saved["level"] == "easy"


def test_a_config_path_through_a_file_cannot_be_saved_and_says_so(tmp_path) -> None:
    (tmp_path / "cfg").write_text("not a directory")
    store = load_settings(env={"XDG_CONFIG_HOME": str(tmp_path / "cfg")})
    assert store.warnings and store.saved == DEFAULTS  # reading through a file: unreadable
    warning = store.save({"level": "hard"})
    assert warning is not None and "\n" not in warning and "cannot save" in warning


# ------------------------------------------------------------------------------ the flags

def play(*args: str, keys: str = "q", env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "termpool", "play", "--headless", "--keys",
                           "-", *args], input=keys, capture_output=True, text=True, cwd=ROOT,
                          env={**os.environ, "PYTHONPATH": str(ROOT), **(env or {})},
                          timeout=120)


def recorded(tmp_path, *args: str, keys: str = "enter space-hold 0.5 wait 5 q y") -> dict:
    import json

    rec = tmp_path / "rec.json"
    p = play("--mode", "8ball", "--opponent", "human", "--seed", "1", "--record", str(rec),
             "--force", *args, keys=keys)
    assert p.returncode == 0, p.stderr
    return json.loads(rec.read_text())["match"]


def test_the_file_is_read_at_start_and_flags_override_it_for_one_run(tmp_path) -> None:
    write_conf("table = 7ft\nframes = 3\ntheme = classic\nplayer1 = Ann\nplayer2 = Bob\n")
    m = recorded(tmp_path)
    assert (m["frames"], m["theme"], m["players"]) == (3, "classic", ["Ann", "Bob"])
    assert m["table"]["length"] == pytest.approx(1.981)
    m = recorded(tmp_path, "--frames", "2", "--table", "9ft", "--player1", "Cy")
    assert (m["frames"], m["theme"], m["players"]) == (2, "classic", ["Cy", "Bob"])
    assert m["table"]["length"] == pytest.approx(2.54)
    assert load_settings().saved["frames"] == 3  # the flags were for that run only


def test_on_off_settings_have_both_flags() -> None:
    from termpool.ui.play import _settings

    write_conf("bell = on\n")
    parser = cli._parser()
    for argv, bell in (([], True), (["--no-bell"], False), (["--bell"], True)):
        _, values = _settings(parser.parse_args(["play", *argv]))
        assert values["bell"] is bell
    write_conf("power = digits\naid = ghost\n")
    _, values = _settings(parser.parse_args(["play", "--input", "classic", "--no-aid"]))
    assert values["power"] == "meter" and values["aid"] == "off"  # no holds: the meter
    _, values = _settings(parser.parse_args(["play", "--input", "classic", "--power",
                                             "digits"]))
    assert values["power"] == "digits"


@pytest.mark.parametrize(("args", "says"), [
    (["--player1", "x" * 40], f"--player1: at most {MAX_NAME} characters"),
    (["--player2", " Bo"], "--player2: must not start or end with a space"),
    (["--player2", "Bo\u0301b"], "--player2: only characters one column wide"),
    (["--frames", "0"], "--frames: must be a whole number from 1 to 1000"),
    (["--power", "turbo"], "--power: invalid choice"),
    (["--fast", "yes"], "--fast: invalid choice"),
])
def test_bad_setting_flags_are_one_line_and_status_2(args, says) -> None:
    p = play(*args)
    assert p.returncode == 2 and p.stderr.count("\n") == 1 and says in p.stderr, p.stderr


def test_a_malformed_file_is_one_line_per_bad_key_and_the_game_starts(tmp_path) -> None:
    write_conf("frames = 0\ntheme = classic\nlevel = \x1b[2Jexpert\n")
    rec = tmp_path / "r.json"
    p = play("--mode", "8ball", "--record", str(rec), keys="q y")
    assert p.returncode == 0
    lines = p.stderr.splitlines()
    assert lines[0].startswith("termpool: warning: settings.conf line 1: frames:")
    assert lines[1].startswith("termpool: warning: settings.conf line 3: level:")
    assert "\x1b" not in p.stderr and "\\x1b[2J" in lines[1]  # escaped, never obeyed
    assert len([x for x in lines if "settings.conf" in x]) == 2


# ------------------------------------------------------------------------------ the screen

def app_at_menu(**kw) -> App:
    return App(Options(colors="mono", seed=0, **kw), prefs=load_settings())


def keys(app: App, *names: str, t: float = 0.0) -> None:
    from termpool.ui.keys import parse_key

    for name in names:
        app.key(parse_key(name), t)
        t += 0.1


def menu_item(label: str) -> str:
    """The digit of a menu entry, as a session without a server shows the menu."""
    from termpool.ui.app import start
    from termpool.ui.state import menu_entries

    return str([m[0] for m in menu_entries(start())].index(label) + 1)


def test_the_menu_opens_the_settings_and_esc_saves_what_changed() -> None:
    app = app_at_menu(level="hard")  # as if --level hard: not to be saved
    keys(app, menu_item("Settings"))
    text = screen_text(app.cells(80, 24)[0])
    for s in SETTINGS:
        assert s.label in text
    assert "‹ hard ›" in text and "settings.conf" in text
    keys(app, "down", "right", "esc")  # the table: 9ft -> 7ft (round)
    assert app.state.box is None and app.state.opts.table == "7ft"
    saved = load_settings().saved
    assert saved["table"] == "7ft" and saved["level"] == "normal"


def test_every_setting_can_be_changed_on_the_screen() -> None:
    app = app_at_menu()
    start = {k: getattr(app.state.opts, k) for k in DEFAULTS}
    keys(app, menu_item("Settings"))
    for s in SETTINGS:
        before = getattr(app.state.opts, s.key)
        if s.kind == "name":
            keys(app, "enter", "A", "n", "space", "n", "enter")
            assert getattr(app.state.opts, s.key) == "An n"
        else:
            keys(app, "right")
            assert getattr(app.state.opts, s.key) != before
        keys(app, "down")
    keys(app, "esc")
    saved = load_settings().saved
    assert all(saved[k] == getattr(app.state.opts, k) != start[k] for k in DEFAULTS)


def test_a_name_is_typed_and_plays_under_it() -> None:
    app = app_at_menu()
    keys(app, menu_item("Settings"), *["down"] * KEYS.index("player1"), "enter", "q",
         "backspace", "Z", "o", "e", "enter", "esc")
    assert app.state.opts.player1 == "Zoe"
    keys(app, "1")  # 8-ball against the computer
    assert app.state.match.players == ("Zoe", "Computer")
    assert "Zoe to break" in screen_text(app.cells(100, 32)[0])


def test_typing_over_a_name_starts_a_new_one_and_backspace_edits_the_old() -> None:
    app = app_at_menu()
    keys(app, menu_item("Settings"), *["down"] * KEYS.index("player1"),
         "enter", "A", "n", "n", "enter")
    assert app.state.opts.player1 == "Ann"
    keys(app, "enter")
    assert "or Backspace to edit this one" in screen_text(app.cells(100, 32)[0])
    keys(app, "B", "o", "b", "enter")  # a new name, not "AnnBob"
    assert app.state.opts.player1 == "Bob"
    keys(app, "enter", "backspace", "o", "enter")  # the old one, edited
    assert app.state.opts.player1 == "Boo"


def test_a_flag_s_value_set_on_the_screen_is_saved_as_the_screen_shows_it() -> None:
    # Run with --theme classic (a flag: not saved), the theme set to standard and back on the
    # screen, and another setting changed: the file keeps what the screen showed, classic.
    store = load_settings()
    app = App(Options(mode="8ball", opponent="human", colors="mono", seed=0, theme="classic"),
              prefs=store)
    keys(app, "enter", "p", "s", *["down"] * KEYS.index("theme"), "right", "left",
         *["down"] * (KEYS.index("aid") - KEYS.index("theme")), "right", "esc")
    saved = load_settings().saved
    assert saved["theme"] == "classic" and saved["aid"] == "ghost"
    # A flag's value left alone stays unsaved.
    app = App(Options(mode="8ball", opponent="human", colors="mono", seed=0, level="pro"),
              prefs=load_settings())
    keys(app, "enter", "p", "s", *["down"] * KEYS.index("aid"), "right", "esc")
    assert load_settings().saved["level"] == "normal"


def test_enter_changes_a_setting_as_right_does_and_the_box_stays() -> None:
    app = app_at_menu()
    keys(app, menu_item("Settings"), *["down"] * KEYS.index("aid"))
    keys(app, "enter")
    assert app.state.opts.aid == "ghost" and app.state.box is not None
    keys(app, "enter", "enter")  # round the choices
    assert app.state.opts.aid == "full" and app.state.box is not None
    keys(app, "esc")
    assert app.state.box is None


def test_a_name_stops_at_its_length_and_esc_leaves_it_as_it_was() -> None:
    app = app_at_menu()
    keys(app, menu_item("Settings"), *["down"] * KEYS.index("player2"), "enter", "x")
    text = screen_text(app.cells(100, 32)[0])
    assert f"up to {MAX_NAME} characters" in text
    assert "Enter keeps it · Esc leaves it as it was" in text and "Esc done" not in text
    keys(app, *["x"] * (MAX_NAME + 4))
    # Typing stopped: the screen says why.
    assert f"a name holds {MAX_NAME} characters at most" in screen_text(app.cells(100, 32)[0])
    keys(app, "enter")
    assert app.state.opts.player2 == "x" * MAX_NAME
    keys(app, "enter", "y", "esc")
    assert app.state.opts.player2 == "x" * MAX_NAME


def test_a_wide_character_is_not_typed_into_a_name_and_the_screen_says_why() -> None:
    """An emoji takes two columns, and the screen is drawn a character a cell: it is left
    out of the name (the rest is typed), the box keeps its shape, and the line says why."""
    app = app_at_menu()
    keys(app, menu_item("Settings"), *["down"] * KEYS.index("player2"), "enter", "Z", "o")
    app.key(Key("🎱"), 1.0)
    keys(app, "e")  # (said until the name is done: the keys after it do not hide it)
    text = screen_text(app.cells(100, 32)[0])
    assert "not typed: only characters one column wide" in text and "🎱" not in text
    assert "Backspace deletes" in text
    keys(app, "enter")
    assert app.state.opts.player2 == "Zoe"
    rows = [r for r in screen_text(app.cells(100, 32)[0]).splitlines() if "│" in r]
    assert len({r.rindex("│") for r in rows}) == 1  # every row's border in one column


def test_from_pause_match_settings_wait_for_the_next_game() -> None:
    app = App(Options(mode="8ball", opponent="human", colors="mono", seed=0),
              prefs=load_settings())
    keys(app, "enter", "p")
    assert "S: settings" in screen_text(app.cells(100, 32)[0])
    keys(app, "s", "right")  # level: normal -> hard, for the next game
    text = screen_text(app.cells(100, 32)[0])
    assert "* next game" in text and "from the next game" in text
    assert app.state.opts.level == "normal" and app.state.pending == {"level": "hard"}
    keys(app, *["down"] * KEYS.index("aid"), "right")  # the aim aid: at once
    assert app.state.opts.aid == "ghost"
    keys(app, "esc")
    assert isinstance(app.state.box, Pause)  # back to the pause box
    keys(app, "space")
    assert app.state.box is None
    app.state = new_match(app.state, "8ball", "human")
    assert app.state.opts.level == "hard" and app.state.pending == {}
    assert load_settings().saved["level"] == "hard"


def test_every_key_on_the_screen_is_drawn() -> None:
    app = app_at_menu()
    keys(app, menu_item("Settings"))
    for name in ("down", "right", "esc"):
        app.cells(80, 24)  # drawn: nothing left to draw
        keys(app, name)
        assert app.dirty  # the terminal draws only what is dirty


def test_the_colour_depth_changes_at_once() -> None:
    app = App(Options(mode="practice", opponent="human", colors="16", seed=0))
    assert app.cells(80, 24)[1] is not None
    keys(app, "p", "s", *["down"] * 4, "right")  # 16 -> mono
    assert app.depth == "mono" and app.cells(80, 24)[1] is None


def test_an_unwritable_config_directory_costs_one_line(tmp_path) -> None:
    (tmp_path / "file").write_text("")
    app = App(Options(colors="mono"),
              prefs=load_settings(env={"XDG_CONFIG_HOME": str(tmp_path / "file")}))
    keys(app, menu_item("Settings"), "right", "esc")
    assert app.state.opts.level == "hard"  # for this run
    assert len(app.state.notes) == 1 and "cannot save the settings" in app.state.notes[0]


# ------------------------------------------------------------------------- what they do

def shots(app: App) -> list[dict]:
    return [rec["shot"] for rec in app.state.match.history]


def run(app: App, script: str) -> None:
    from termpool.ui.headless import play as play_keys
    from termpool.ui.keys import parse_script

    play_keys(app, parse_script(script), 100, 32)


def test_power_digits_strikes_at_once_at_the_level_set() -> None:
    app = App(Options(mode="practice", opponent="human", colors="mono", seed=0,
                      power="digits"))
    run(app, "enter wait 0.2 space wait 30 esc 3 space wait 30")
    a, b = shots(app)
    assert a["speed"] == power_to_speed(0.5)  # the set level, before any digit
    assert b["speed"] == power_to_speed(0.3)  # Esc keeps digits; 3 sets 30%


def test_power_meter_is_the_swinging_meter_even_with_key_releases() -> None:
    app = App(Options(mode="practice", opponent="human", colors="mono", seed=0,
                      power="meter"), input_mode="release")
    assert app.state.controls.charge.mode == "classic"
    run(app, "enter wait 0.2 space wait 0.5 space wait 5")
    assert len(shots(app)) == 1


@pytest.mark.parametrize(("fast", "human", "cpu"), [("off", False, False),
                                                    ("computer", False, True),
                                                    ("always", True, True)])
def test_fast_forward_setting_starts_shots_at_x4(fast, human, cpu) -> None:
    app = App(Options(mode="8ball", opponent="cpu", colors="mono", seed=0, fast=fast))
    seen = []

    def noting(real):  # each shot as it starts: whose, and whether fast-forwarded
        def call(*a):
            real(*a)
            part = app.state.part
            new = isinstance(part, Run) and all(part.shot is not x for x, _ in seen)
            if new:
                seen.append((part.shot, (shooter_is_cpu(app.state), part.fast)))
        return call

    app.key, app.tick = noting(app.key), noting(app.tick)
    run(app, "enter wait 0.2 space-hold 0.3 wait 30")
    seen = [x for _, x in seen]
    assert (False, human) in seen and (True, cpu) in seen


def test_level_from_settings_reaches_the_computer() -> None:
    app = App(Options(mode="8ball", opponent="cpu", colors="mono", seed=0, level="easy"))
    calls = []
    import termpool.ai as ai

    real = ai.shots.choose_shot

    def spy(*a, **k):
        calls.append(k["level"])
        return real(*a, **k)

    ai.shots.choose_shot = spy
    try:
        run(app, "enter wait 0.2 space-hold 0.2 wait 30")
    finally:
        ai.shots.choose_shot = real
    assert calls and set(calls) == {"easy"}


def test_key_press_in_the_settings_never_reaches_the_game() -> None:
    app = App(Options(mode="practice", opponent="human", colors="mono", seed=0))
    keys(app, "enter", "p", "s")
    angle = app.state.stroke.angle
    app.key(Key("space"), 1.0)
    app.key(Key("left"), 1.1)
    assert app.state.stroke.angle == angle and app.state.match.history == []
    assert app.state.box is not None


@pytest.mark.parametrize("cols, rows", [(80, 24), (120, 40), (60, 30)])
def test_the_settings_box_keeps_its_width_as_the_selection_moves(cols, rows) -> None:
    from termpool.ui.app import App, Options
    from termpool.ui.headless import screen_text
    from termpool.ui.keys import Key
    from termpool.ui.settings import SETTINGS

    app = App(Options(colors="mono"))
    app.state = open_settings(app.state)
    widths = set()
    for k in range(len(SETTINGS) + 1):
        text = screen_text(app.cells(cols, rows)[0])
        (top,) = [line for line in text.splitlines() if "┌" in line]
        widths.add((top.index("┌"), top.index("┐")))
        app.key(Key("down"), float(k))
    assert len(widths) == 1, widths


def test_the_files_warnings_are_on_the_games_first_screen_too() -> None:
    # Said on stderr before the game takes the screen, and on its first screen (the menu
    # here, where a "wait" draws it), so that a player in the game sees them.
    write_conf("tabel = 7ft\nframes = lots\n")
    p = play("--size", "100x32", keys="wait 0.1")
    assert p.returncode == 0, p.stderr
    assert "warning: settings.conf line 1: unknown setting 'tabel'" in p.stderr
    # (wrapped to the menu's width: read as words)
    assert ("settings: 2 warnings (all said after play), the first: settings.conf line 1: "
            "unknown setting 'tabel'") in " ".join(p.stdout.split())


def test_the_box_says_the_file_is_written_when_it_closes() -> None:
    app = App(Options(mode="8ball", opponent="human", colors="mono", seed=0),
              prefs=load_settings())
    keys(app, "enter", "p", "s")
    text = " ".join(screen_text(app.cells(120, 40)[0]).split())
    assert "closing saves the changes in " in text, text
    assert not load_settings().path.exists()  # nothing written while it is open


def test_the_settings_open_again_on_the_row_they_closed_on() -> None:
    app = app_at_menu()
    keys(app, menu_item("Settings"), *["down"] * KEYS.index("aid"), "esc")
    keys(app, menu_item("Settings"), "right")  # the aim aid again, not the computer's level
    assert app.state.opts.aid == "ghost" and app.state.opts.level == "normal"


@pytest.mark.parametrize(("cols", "rows"), [(80, 24), (100, 30), (60, 20), (120, 40)])
def test_the_settings_box_holds_still_as_the_choice_moves(cols, rows) -> None:
    # Its headings, its frame and its key line stay where they are, whichever setting's
    # words (one line or three) are shown under the list.
    app = App(Options(mode="8ball", opponent="human", colors="mono", seed=0))
    app.state = open_settings(app.state)
    seen = set()
    for k in range(len(SETTINGS)):
        app.state = replace(app.state, box=replace(app.state.box, index=k))
        lines = screen_text(app.cells(cols, rows)[0]).splitlines()
        where = tuple(next((i for i, x in enumerate(lines) if mark in x), None)
                      for mark in ("┌─ settings", "The game", "Names", "Esc done"))
        seen.add(where)
    assert len(seen) == 1, seen


def test_frames_to_win_is_typed_in_digits() -> None:
    app = app_at_menu()
    keys(app, menu_item("Settings"), *["down"] * KEYS.index("frames"), "1", "5")
    assert "15_" in screen_text(app.cells(80, 24)[0])
    assert app.state.opts.frames == 1  # not yet: Enter keeps it
    keys(app, "enter")
    assert app.state.opts.frames == 15 and app.state.box.editing is None
    keys(app, "7", "backspace", "9", "enter")  # Backspace takes the last digit back
    assert app.state.opts.frames == 9
    keys(app, "0", "enter")  # out of range: refused, said, and still being typed
    assert app.state.opts.frames == 9
    assert "from 1 to 1000" in screen_text(app.cells(80, 24)[0])
    keys(app, "esc")  # leaves it as it was
    assert app.state.box.editing is None and app.state.opts.frames == 9
    keys(app, "1", "2", "3", "4", "5")  # no more digits than the largest number has
    assert app.state.box.editing == "1234"
    keys(app, "x")  # not a digit: refused
    assert app.state.box.editing == "1234" and "not typed" in screen_text(app.cells(80, 24)[0])
    keys(app, "backspace", "enter", "esc")
    assert app.state.opts.frames == 123 and load_settings().saved["frames"] == 123


def test_the_computer_s_level_says_when_no_computer_plays() -> None:
    for opponent, said in (("human", True), ("cpu", False)):
        app = App(Options(mode="8ball", opponent=opponent, colors="mono", seed=0),
                  prefs=load_settings())
        keys(app, "enter", "p", "s")
        text = screen_text(app.cells(80, 24)[0])
        assert "Computer's level" in text
        assert ("‹ normal ›  (not in this game)" in text) == said, text


def test_the_menu_names_the_computer_s_level() -> None:
    app = app_at_menu(level="hard")
    text = screen_text(app.cells(80, 24)[0])
    assert "8-ball vs computer (hard)" in text and "9-ball vs computer (hard)" in text
    assert "8-ball, two players" in text and "two players (" not in text
    keys(app, menu_item("Settings"), "left", "esc")  # the level changed: the menu says so
    assert "8-ball vs computer (normal)" in screen_text(app.cells(80, 24)[0])
