"""Hostile input: every malformed file gets one line and exit status 2 in `sim`, `replay`,
`play --keys` and `play --keymap`, never a traceback or a numpy warning, and no text from a file
reaches the terminal with its control characters live."""

from __future__ import annotations

import copy
import io
import json
import sys
import warnings
from pathlib import Path

import pytest

from termpool import cli
from termpool.game import Match, Shot
from termpool.text import shown

ESC = "\x1b[2J\x1b]0;pwned\x07"  # clear the screen, retitle the window, ring
ESCAPED = "\\x1b[2J\\x1b]0;pwned\\x07"


def main(capsys, *argv: str, stdin: bytes | None = None, monkeypatch=None) -> tuple[int, str,
                                                                                    str]:
    """Run the command in-process; numpy and Python warnings are errors here, so a warning
    printed before the one-line error fails the test."""
    if stdin is not None:
        monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(stdin)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rc = cli.main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def one_line(rc: int, err: str, *words: str) -> None:
    assert rc == 2, err
    assert err.startswith("termpool: ") and err.endswith("\n") and err.count("\n") == 1, err
    for w in words:
        assert w in err, err


@pytest.fixture(scope="module")
def record() -> dict:
    m = Match("9ball", seed=3, players=("Ann", "Bob"))
    m.begin(Shot(8.0, 0.0)).finish()
    return json.loads(json.dumps(m.to_json()))


def put(tmp_path: Path, text: str | bytes, name: str = "f.json") -> str:
    p = tmp_path / name
    if isinstance(text, bytes):
        p.write_bytes(text)
    else:
        p.write_text(text)
    return str(p)


# --------------------------------------------------------------------------------- the text


def test_shown_escapes_every_control_character_and_nothing_else() -> None:
    assert shown(ESC) == ESCAPED
    assert shown("a\nb\tc\rd") == "a\\nb\\tc\\rd"
    assert shown("\x9b31m\x7f") == "\\x9b31m\\x7f"  # C1 CSI and DEL
    assert shown("x\u202ey\u2028") == "x\\u202ey\\u2028"  # bidi override, line separator
    plain = "Ann O'Neil — 9-ball «pro» 🎱 ü"
    assert shown(plain) == plain
    assert shown(7) == "7"
    assert all(shown(chr(c)) != chr(c) for c in [*range(32), *range(0x7F, 0xA0)])


# ----------------------------------------------------------------------------- sim: the table

HUGE = "1" + "0" * 400
VAST = "9" * 5000


def nest(levels: int) -> str:
    return "[" * levels + "]" * levels


SIM_CASES = {
    "400-digit integer": ('{"balls": [{"x": ' + HUGE + ', "y": 0.5}]}', "more than 100 digits"),
    "5000-digit integer": ('{"balls": [{"x": 0.5, "y": ' + VAST + '}]}', "more than 100 digits"),
    "nesting 497": ('{"description": ' + nest(497) + "}", "nested more than 64 levels"),
    "nesting 1000": ('{"description": ' + nest(1000) + "}", "nested more than 64 levels"),
    "radius 1e-200": ('{"balls": [{"x": 0.5, "y": 0.5, "vx": 1, "radius": 1e-200}, '
                      '{"x": 0.6, "y": 0.5, "radius": 1e-200}]}', "balls[0].radius"),
    "mass 5e-324": ('{"balls": [{"x": 0.5, "y": 0.5, "vx": 1, "mass": 5e-324}, '
                    '{"x": 0.6, "y": 0.5}]}', "balls[0].mass"),
    "mouth 1e308": ('{"table": {"corner_mouth": 1e308}}', "table.corner_mouth"),
    "length 1e-300": ('{"table": {"length": 1e-300}}', "table.length"),
    "speed 1e308": ('{"balls": "8ball", "shot": {"speed": 1e308}}', "shot.speed"),
    "non-UTF-8": (b'{"description": "caf\xe9"}', "not UTF-8 text"),
    "10,000 balls": (json.dumps({"balls": [{"x": 0.1, "y": 0.1}] * 10_000}),
                     "more than the limit of 1000"),
    "NaN token": ('{"balls": [{"x": NaN, "y": 0.5}]}', "invalid JSON: NaN is not JSON"),
    "mu_slide 1e308": ('{"physics": {"mu_slide": 1e308}}', "physics.mu_slide: must be at most 1"),
}


@pytest.mark.parametrize("case", SIM_CASES)
def test_sim_malformed_scene_is_one_line(capsys, tmp_path, case) -> None:
    text, words = SIM_CASES[case]
    rc, out, err = main(capsys, "sim", put(tmp_path, text))
    one_line(rc, err, words)
    assert out == ""


def test_sim_from_stdin_is_bounded_and_checked(capsys, monkeypatch) -> None:
    rc, _, err = main(capsys, "sim", "-", stdin=('{"x": ' + VAST + "}").encode(),
                      monkeypatch=monkeypatch)
    one_line(rc, err, "stdin: invalid JSON: an integer with more than 100 digits")


def test_a_non_finite_result_is_one_line_never_a_nan_token(capsys, monkeypatch) -> None:
    """JSON has no NaN or Infinity: should a result ever hold one, sim says where, in one
    line, instead of printing a token no JSON reader takes."""
    real = cli.sim_result

    def broken(*args, **kw):
        res = real(*args, **kw)
        res["balls"][2]["vy"] = float("-inf")
        return res

    monkeypatch.setattr(cli, "sim_result", broken)
    rc, out, err = main(capsys, "sim", cli.bundled_example())
    one_line(rc, err, "sim: the result cannot be written: balls[2].vy is -inf, not a finite")
    assert out == ""


@pytest.mark.parametrize("argv", [["sim"], ["replay"]])
def test_dev_zero_is_refused_not_read_to_the_end(capsys, argv) -> None:
    rc, _, err = main(capsys, *argv, "/dev/zero")
    one_line(rc, err, "/dev/zero: larger than")


# ------------------------------------------------------------------------- replay: the table


def mutate(record: dict, change) -> dict:
    data = copy.deepcopy(record)
    change(data)
    return data


REPLAY_CASES = {
    "400-digit steps": (lambda d: d["shots"][0].update(steps=int(HUGE)), "more than 100"),
    "5000-digit integer": (None, "more than 100 digits"),
    "nesting 497": (lambda d: d["shots"][0].update(outcome={"x": json.loads(nest(60))}),
                    "nested more than 64"),
    "radius 1e-200": (lambda d: d["shots"][0]["scene"]["balls"][0].update(radius=1e-200),
                      "shots[0].scene: balls[0].radius: must be at least"),
    "mass 5e-324": (lambda d: d["shots"][0]["scene"]["balls"][1].update(mass=5e-324),
                    "shots[0].scene: balls[1].mass"),
    "dt 1e-300": (lambda d: d["shots"][0].update(dt=1e-300), "shots[0].dt"),
    "player names not strings": (lambda d: d["match"].update(players=[1, {"a": 2}]),
                                 "match.players: must be a list of two names"),
}


@pytest.mark.parametrize("case", REPLAY_CASES)
def test_replay_malformed_is_one_line(capsys, tmp_path, record, case) -> None:
    change, words = REPLAY_CASES[case]
    if change is None:  # a number too long for the JSON parser's own integer limit
        text = json.dumps(record).replace('"time": ', f'"big": {VAST}, "time": ', 1)
    else:
        text = json.dumps(mutate(record, change))
    if case == "nesting 497":
        text = text.replace(nest(60), nest(497))
    rc, out, err = main(capsys, "replay", put(tmp_path, text))
    one_line(rc, err, words)
    assert out == ""


def test_replay_nesting_1000_is_one_line(capsys, tmp_path) -> None:
    rc, _, err = main(capsys, "replay", put(tmp_path, '{"shots": ' + nest(1000) + "}"))
    one_line(rc, err, "nested more than 64 levels")


# ----------------------------------------------------------------------------- play: the table


@pytest.fixture
def keys(tmp_path) -> str:
    return put(tmp_path, "enter", "keys.txt")


PLAY = ("play", "--headless", "--mode", "practice")


@pytest.mark.parametrize("script, words", [
    (b"enter caf\xe9", "--keys: "),
    (b"q*" + HUGE.encode(), "repeat count must be a whole number from 1 to 1000"),
    (b"q*" + VAST.encode(), "repeat count must be a whole number from 1 to 1000"),
    (b"wait " + HUGE.encode(), "wait: seconds must be finite"),
    (b"wait 1e300", "wait: at most 3600 seconds"),
    (b"space-hold 1e300", "hold: at most 60 seconds"),
    (b"wait 3000 wait 3000", "longer than the limit of 3600 seconds"),
    (b"click 1" + b"0" * 400 + b" 3", "click needs a column and a row"),
    (b"q*\xc2\xb2", "repeat count must be a whole number"),  # a superscript two
])
def test_play_malformed_key_script_is_one_line(capsys, tmp_path, script, words) -> None:
    rc, out, err = main(capsys, *PLAY, "--keys", put(tmp_path, script, "k.txt"))
    one_line(rc, err, words)
    assert out == "" and len(err) < 300  # a 5000-digit token is not echoed whole


def test_play_key_script_from_dev_zero_and_stdin(capsys, monkeypatch) -> None:
    rc, _, err = main(capsys, *PLAY, "--keys", "/dev/zero")
    one_line(rc, err, "--keys: /dev/zero: larger than 1 MiB")
    rc, _, err = main(capsys, *PLAY, "--keys", "-", stdin=b"\xff\xfe",
                      monkeypatch=monkeypatch)
    one_line(rc, err, "--keys: stdin: not UTF-8 text")


@pytest.mark.parametrize("conf, words", [
    (b"shoot = z\xff", "not UTF-8 text"),
    (b"quit =", "no key left for quit"),
    ("shoot = " + ESC, "unknown key name"),
])
def test_play_malformed_keymap_is_one_line(capsys, tmp_path, keys, conf, words) -> None:
    rc, _, err = main(capsys, *PLAY, "--keys", keys, "--keymap", put(tmp_path, conf, "k.conf"))
    one_line(rc, err, words)
    assert "\x1b" not in err and "\x07" not in err


def test_play_with_an_unreadable_config_warns_and_plays(capsys, tmp_path, keys,
                                                       monkeypatch) -> None:
    (tmp_path / "xdg" / "termpool" / "keys.conf").mkdir(parents=True)
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "xdg"))
    rc, out, err = main(capsys, *PLAY, "--keys", keys)
    assert rc == 0 and "Space:" in out  # the default keys: Space shoots
    assert err.count("\n") == 1 and err.startswith("termpool: warning: cannot read key map ")
    assert err.endswith("; playing with the default keys\n")


def test_play_with_a_mistake_in_the_default_config_warns_and_plays(capsys, tmp_path,
                                                                  monkeypatch) -> None:
    # A slip in keys.conf, as in settings.conf, keeps the game: the default keys, the
    # warning said once and shown whole on the first screen.
    conf = tmp_path / "xdg" / "termpool" / "keys.conf"
    conf.parent.mkdir(parents=True)
    conf.write_text("shoot = space\nshot = \x1b[31mx\n")
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "xdg"))
    rc, out, err = main(capsys, "play", "--headless", "--keys", put(tmp_path, "wait 1", "k.txt"),
                        "--size", "80x24")
    assert rc == 0 and "Enter start" in out  # the menu
    assert err.count("\n") == 1 and err.startswith("termpool: warning: keys.conf line 2: ")
    assert err.endswith("; playing with the default keys\n") and "\x1b" not in err
    screen = " ".join(" ".join(out.split()).split("Enter start · Q quit", 1)[1].split())
    assert screen.startswith("keys: keys.conf line 2: unknown action")
    assert screen.endswith("playing with the default keys")


def test_play_keymap_from_dev_zero(capsys, keys) -> None:
    rc, _, err = main(capsys, *PLAY, "--keys", keys, "--keymap", "/dev/zero")
    one_line(rc, err, "/dev/zero: larger than 64 KiB")


@pytest.mark.parametrize("argv, words", [
    (["--seed", "-1"], "--seed: must be a whole number from 0 to 18446744073709551615, "
                       "not '-1'"),
    (["--seed", str(2 ** 64)], "--seed: must be a whole number from 0"),
    (["--seed", VAST], "--seed: must be a whole number from 0"),
    (["--seed", "1.5"], "--seed: must be a whole number from 0"),
    (["--frames", "0"], "--frames: must be a whole number from 1 to 1000"),
    (["--frames", HUGE], "--frames: must be a whole number from 1 to 1000"),
])
def test_play_bad_numbers_are_one_line(capsys, keys, argv, words) -> None:
    rc, _, err = main(capsys, *PLAY, "--keys", keys, *argv)
    one_line(rc, err, words)
    assert len(err) < 300


# ----------------------------------------------------------------------- escapes in messages


def test_unknown_scene_keys_and_ball_ids_are_shown_escaped(capsys, tmp_path) -> None:
    for scene in ({ESC: 1}, {"balls": [{"id": ESC, "x": 0.5, "y": 0.5},
                                       {"id": ESC, "x": 1.0, "y": 0.5}]},
                  {"table": {ESC: 2}}, {"balls": "8ball", "shot": {"ball": ESC, "speed": 1}}):
        rc, _, err = main(capsys, "sim", put(tmp_path, json.dumps(scene)))
        one_line(rc, err, ESCAPED)
        assert "\x1b" not in err and "\x07" not in err


def test_replay_player_names_are_shown_escaped(capsys, tmp_path, record) -> None:
    data = mutate(record, lambda d: d["match"].update(players=[ESC + "\r\nshot 9: ok", "B"]))
    rc, out, err = main(capsys, "replay", put(tmp_path, json.dumps(data)))
    assert rc == 0, err
    assert f"(frame 1, {ESCAPED}\\r\\nshot 9: ok)" in out
    assert "\x1b" not in out and "\x07" not in out and "\r" not in out
    assert len(out.splitlines()) == len(data["shots"]) + 1  # one line a shot, one verdict


def test_replay_differences_show_dict_keys_escaped(capsys, tmp_path, record) -> None:
    data = mutate(record, lambda d: d["shots"][0]["outcome"].update({ESC: 1}))
    rc, out, _ = main(capsys, "replay", put(tmp_path, json.dumps(data)))
    assert rc == 1
    assert f"outcome.{ESCAPED}: only in the recorded shot" in out
    assert "\x1b" not in out and "\x07" not in out


def test_replay_json_output_escapes_too(capsys, tmp_path, record) -> None:
    data = mutate(record, lambda d: d["shots"][0]["outcome"].update({ESC: 1}))
    rc, out, _ = main(capsys, "replay", "--json", put(tmp_path, json.dumps(data)))
    assert rc == 1 and "\x1b" not in out and json.loads(out)["identical"] is False


def test_a_path_with_control_characters_is_shown_escaped(capsys, tmp_path) -> None:
    rc, _, err = main(capsys, "sim", str(tmp_path / f"{ESC}.json"))
    one_line(rc, err, ESCAPED)
    assert "\x1b" not in err
