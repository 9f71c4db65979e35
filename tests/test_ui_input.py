"""Input layer tests: key decoding, key scripts, the key map and its config file, aim
acceleration and power charging. Pure: synthetic key streams on a virtual clock, no terminal."""

from __future__ import annotations

import io
import random
from collections import OrderedDict

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from termpool.ui.controls import (
    ACTIONS,
    AimControl,
    KeyMap,
    PowerCharge,
    load_keymap,
    parse_keymap,
)
from termpool.ui.keys import (
    NAMED_KEYS,
    Key,
    decode,
    from_keystroke,
    legacy_events,
    parse_key,
    parse_script,
)

SPACE = Key("space")


def K(name: str, kind: str = "press", **mods: bool) -> Key:
    return Key(name, kind, **mods)


# ----------------------------------------------------------------------------- decoding

LEGACY = {
    # plain arrows, CSI (normal cursor mode) and SS3 (application cursor mode)
    "\x1b[A": K("up"), "\x1b[B": K("down"), "\x1b[C": K("right"), "\x1b[D": K("left"),
    "\x1bOA": K("up"), "\x1bOB": K("down"), "\x1bOC": K("right"), "\x1bOD": K("left"),
    "\x1b[H": K("home"), "\x1bOF": K("end"), "\x1b[5~": K("pageup"), "\x1b[6~": K("pagedown"),
    "\x1bOP": K("f1"), "\x1b[15~": K("f5"), "\x1b[24~": K("f12"), "\x1b[[A": K("f1"),
    # control characters and text
    "\r": K("enter"), "\n": K("enter"), "\t": K("tab"), "\x7f": K("backspace"),
    "\x08": K("backspace"), " ": K("space"), "\x1b": K("esc"), "q": K("q"), "?": K("?"),
    "A": K("a", shift=True), "\x03": K("c", ctrl=True), "\x00": K("space", ctrl=True),
    "é": K("é"),
}

MODIFIED = {
    "\x1b[1;2D": K("left", shift=True), "\x1b[1;2C": K("right", shift=True),
    "\x1b[1;5C": K("right", ctrl=True), "\x1b[1;3A": K("up", alt=True),
    "\x1b[1;6B": K("down", shift=True, ctrl=True),
    "\x1b[1;8D": K("left", shift=True, ctrl=True, alt=True),
    "\x1b[3;5~": K("delete", ctrl=True), "\x1b[15;2~": K("f5", shift=True),
    "\x1b[Z": K("tab", shift=True), "\x1bO2P": K("f1", shift=True),
    "\x1b[a": K("up", shift=True), "\x1bOd": K("left", ctrl=True),  # rxvt
    "\x1bx": K("x", alt=True), "\x1bX": K("x", shift=True, alt=True),
    "\x1b\x7f": K("backspace", alt=True), "\x1b\x1b[D": K("left", alt=True),
    "\x1b[27;5;99~": K("c", ctrl=True),  # xterm modifyOtherKeys
}

KITTY = {
    "\x1b[32u": K("space"), "\x1b[32;1u": K("space"), "\x1b[32;1:1u": K("space"),
    "\x1b[32;1:2u": K("space", "repeat"), "\x1b[32;1:3u": K("space", "release"),
    "\x1b[32;2:3u": K("space", "release", shift=True),
    "\x1b[1;1:2D": K("left", "repeat"), "\x1b[1;1:3D": K("left", "release"),
    "\x1b[1;2:2C": K("right", "repeat", shift=True), "\x1b[1;5:3A": K("up", "release", ctrl=True),
    "\x1b[13u": K("enter"), "\x1b[13;1:3u": K("enter", "release"), "\x1b[27u": K("esc"),
    "\x1b[9u": K("tab"), "\x1b[127u": K("backspace"), "\x1b[113u": K("q"),
    "\x1b[113;1:3u": K("q", "release"), "\x1b[97;2u": K("a", shift=True),
    "\x1b[99;5u": K("c", ctrl=True), "\x1b[47:63;2u": K("?", shift=True),
    "\x1b[47;2u": K("?", shift=True), "\x1b[49;2u": K("!", shift=True),
    "\x1b[57417u": K("left"), "\x1b[57414u": K("enter"), "\x1b[57400u": K("1"),
    "\x1b[3;1:3~": K("delete", "release"), "\x1b[15;1:2~": K("f5", "repeat"),
    "\x1b[32;1:3;32u": K("space", "release"),  # with the text field
}

NO_KEY = [
    "\x1b[57441;2u",  # left shift pressed alone (kitty "report all keys")
    "\x1b[57441;2:3u", "\x1b[57358u",  # caps lock
    "\x1b[<0;10;5M", "\x1b[<0;10;5m",  # SGR mouse
    "\x1b[I", "\x1b[O",  # focus in/out
    "\x1b[200~left q\x1b[201~",  # bracketed paste: skipped whole
    "\x1b[1;5",  # cut off
    "\x1b[?1u",  # reply to a kitty flags query
]


@pytest.mark.parametrize("table", [LEGACY, MODIFIED, KITTY], ids=["legacy", "modified", "kitty"])
def test_decode_single_sequences(table):
    for text, key in table.items():
        assert decode(text) == [key], repr(text)


@pytest.mark.parametrize("text", NO_KEY)
def test_decode_gives_no_key_for_non_keys(text):
    assert decode(text) == []


def test_decode_streams_split_into_keys_in_order():
    text = "\x1b[32u\x1b[32;1:2u\x1b[32;1:2u\x1b[32;1:3uq\x1b[D\x1bOAx\r"
    assert decode(text) == [K("space"), K("space", "repeat"), K("space", "repeat"),
                            K("space", "release"), K("q"), K("left"), K("up"), K("x"),
                            K("enter")]
    # the paste swallows its text but not what follows
    assert decode("a\x1b[200~qqq\x1b[201~b") == [K("a"), K("b")]
    # two escapes are two Esc presses, not alt+Esc
    assert decode("\x1b\x1b") == [K("esc"), K("esc")]


ALL_TABLES = LEGACY | MODIFIED | KITTY


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(sorted(ALL_TABLES)), max_size=12))
def test_decode_of_a_concatenation_is_the_concatenation(seqs):
    # "\x1b" alone is only a key at the end of the input (else it starts a sequence)
    seqs = [s for s in seqs if s != "\x1b"]
    assert decode("".join(seqs)) == [ALL_TABLES[s] for s in seqs]


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet=st.sampled_from(list("\x1b[O;:u~1235789ABCDPqZ \r\x7f?") + ["é"]),
               max_size=40))
def test_decode_never_raises_and_names_are_valid(text):
    for key in decode(text):
        assert key.name in NAMED_KEYS or len(key.name) == 1
        assert key.kind in ("press", "repeat", "release")
        assert key.name == key.name.lower()


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=30), st.sampled_from(["", "\x1b", "\x1b[", "\x1bO", "\x1b[1;", "\x1b[9"]))
def test_decode_never_raises_on_any_text(text, prefix):
    for key in decode(prefix + text):
        assert key.name in NAMED_KEYS or len(key.name) == 1


def test_decode_recovers_after_broken_sequences():
    # a character that cannot be in a CSI sequence ends it; what follows is read again
    assert decode("\x1b[1;\rq") == [K("enter"), K("q")]
    assert decode("\x1b[99999999999999999999u\x1b[27;5;1114112~\x1b[1114112uq") == [K("q")]
    assert decode("\x1bO\u00b2Pq") == [K("p", shift=True), K("q")]


def _blessed_mapper():
    from blessed.keyboard import DEFAULT_SEQUENCE_MIXIN, get_keyboard_codes

    mapper = OrderedDict(sorted(DEFAULT_SEQUENCE_MIXIN, key=lambda kv: -len(kv[0])))
    return mapper, get_keyboard_codes()


_BLESSED_BASE = {"ESCAPE": "esc", "PGUP": "pageup", "PGDOWN": "pagedown"}


def test_decode_agrees_with_blessed_on_names_modifiers_and_event_types():
    """blessed parses the same sequences independently: name, modifiers and kind agree."""
    from blessed.keyboard import resolve_sequence

    mapper, codes = _blessed_mapper()
    checked = 0
    for text, key in (MODIFIED | KITTY).items():
        ks = resolve_sequence(text, mapper, codes, final=True)
        if str(ks) != text or not ks.uses_keyboard_protocol or ks.key_name is None:
            continue  # blessed reads only part of it, or without modifier data
        base = ks.key_name[4:].split("_")
        while base[0] in ("SHIFT", "CTRL", "ALT"):
            base.pop(0)
        name = "_".join(base)
        if len(name) > 1 and name not in _BLESSED_BASE and name.lower() not in NAMED_KEYS:
            continue  # blessed's names for symbols ("SLASH")
        if key.shift and len(key.name) == 1 and not key.name.isalpha():
            continue  # blessed names the unshifted key ("1"), decode the character ("!")
        assert _BLESSED_BASE.get(name, name.lower()) == key.name, repr(text)
        assert (ks.modifiers_bits & 7) == key.shift + 2 * key.alt + 4 * key.ctrl, repr(text)
        kind = "release" if ks.released else "repeat" if ks.repeated else "press"
        assert kind == key.kind, repr(text)
        checked += 1
    assert checked >= 25


def _terminal():
    from blessed import Terminal

    return Terminal(kind="xterm-256color", stream=io.StringIO(), force_styling=True)


def test_from_keystroke_reads_what_terminal_inkey_returns():
    term = _terminal()
    term.ungetch("\x1bOD\x1b[1;2C\x1b[32;1:3uq\x1b[1;1:2DA")
    got = []
    while ks := term.inkey(timeout=0):
        got.append(from_keystroke(ks))
    assert got == [K("left"), K("right", shift=True), K("space", "release"), K("q"),
                   K("left", "repeat"), K("a", shift=True)]


def test_from_keystroke_timeout_and_terminfo_only_sequences():
    from blessed.keyboard import Keystroke, get_keyboard_codes, resolve_sequence

    assert from_keystroke(Keystroke("")) is None  # inkey timed out
    codes = get_keyboard_codes()
    f7 = next(c for c, n in codes.items() if n == "KEY_F7")
    sleft = next(c for c, n in codes.items() if n == "KEY_SLEFT")
    # a sequence only some terminal's terminfo entry knows: blessed's name is used
    ks = resolve_sequence("\x1bOZ", OrderedDict([("\x1bOZ", f7)]), codes, final=True)
    assert decode(str(ks)) == []
    assert from_keystroke(ks) == Key("f7")
    ks = resolve_sequence("\x1b[2$", OrderedDict([("\x1b[2$", sleft)]), codes, final=True)
    assert from_keystroke(ks) == K("left", shift=True)


# ----------------------------------------------------------------------------- key specs


@pytest.mark.parametrize("spec,key", [
    ("left", K("left")), ("shift+left", K("left", shift=True)), ("Left", K("left")),
    ("ctrl+alt+shift+up", Key("up", shift=True, ctrl=True, alt=True)),
    ("Q", K("q", shift=True)), ("q", K("q")), ("?", K("?")), ("escape", K("esc")),
    ("return", K("enter")), ("F5", K("f5")), ("+", K("+")), ("plus", K("+")),
    ("shift++", K("+", shift=True)), ("comma", K(",")), ("hash", K("#")),
    ("control+c", K("c", ctrl=True)), ("shift + left", K("left", shift=True)),
])
def test_parse_key(spec, key):
    assert parse_key(spec) == key


def test_key_spec_round_trips():
    for spec in ["left", "shift+left", "ctrl+alt+shift+up", "?", "comma", "plus", "f12", "esc"]:
        assert parse_key(spec).spec == spec
        assert parse_key(parse_key(spec).spec) == parse_key(spec)


@pytest.mark.parametrize("spec,words", [
    ("spce", "unknown key name 'spce'"), ("hyper+a", "unknown modifier 'hyper'"),
    ("shift+", "no key name"), ("", "empty key name"), ("shift+spce", "'spce' in key"),
])
def test_parse_key_errors_name_the_spec(spec, words):
    with pytest.raises(ValueError, match=words):
        parse_key(spec)


# ----------------------------------------------------------------------------- scripts


def test_script_taps_waits_and_holds_on_the_virtual_clock():
    ev = parse_script("right*3 wait 0.2 space-hold 1.0 q", tap_gap=0.05, repeat_delay=0.3,
                      repeat_rate=0.033)
    presses = [(t, k) for t, k in ev if k.kind == "press"]
    assert presses == [(0.0, K("right")), (0.05, K("right")), (0.1, K("right")),
                       (0.35, K("space")), (1.4, K("q"))]
    releases = [(t, k.name) for t, k in ev if k.kind == "release"]
    assert releases == [(0.025, "right"), (0.075, "right"), (0.125, "right"),
                        (1.35, "space"), (1.425, "q")]
    reps = [t for t, k in ev if k.kind == "repeat"]
    # first repeat one delay after the press, then every 33 ms while before the release
    assert reps[0] == pytest.approx(0.65) and reps[1] == pytest.approx(0.683)
    assert len(reps) == 22 and reps[-1] < 1.35 < reps[-1] + 0.033
    assert [t for t, _ in ev] == sorted(t for t, _ in ev)


def test_script_modifiers_and_parameters():
    ev = parse_script("shift+left ctrl+c ? Q", tap_gap=0.1)
    assert [k for _, k in ev if k.kind == "press"] == [
        K("left", shift=True), K("c", ctrl=True), K("?"), K("q", shift=True)]
    assert [t for t, k in ev if k.kind == "press"] == [0.0, 0.1, 0.2, 0.3]
    short = parse_script("space-hold 0.2", repeat_delay=0.3)  # released before any repeat
    assert [(t, k.kind) for t, k in short] == [(0.0, "press"), (0.2, "release")]
    assert parse_script("") == [] and parse_script("  \n ") == []


def test_script_is_deterministic():
    text = "left*7 wait 0.13 space-hold 1.37 right-hold 0.9 q y"
    assert parse_script(text) == parse_script(text)


@pytest.mark.parametrize("text,where,words", [
    ("q spce", "token 2 'spce'", "unknown key name"),
    ("wait", "token 1 'wait'", "needs a number"),
    ("left wait soon", "token 2 'wait'", "not a number"),
    ("x*0", "token 1 'x\\*0'", "whole number"),
    ("a b c*two", "token 3 'c\\*two'", "whole number"),
    ("space-hold", "token 1 'space-hold'", "needs a number"),
    ("space-hold -1", "token 1 'space-hold'", "not negative"),
    ("hyper+q", "token 1 'hyper\\+q'", "unknown modifier"),
    ("wait inf", "token 1 'wait'", "finite"),
])
def test_script_errors_name_token_and_position(text, where, words):
    with pytest.raises(ValueError, match=f"script {where}: .*{words}"):
        parse_script(text)


def test_legacy_events_drop_releases_and_make_repeats_presses():
    ev = parse_script("space-hold 0.5 q", repeat_delay=0.3, repeat_rate=0.05)
    leg = legacy_events(ev)
    assert all(k.kind == "press" for _, k in leg)
    assert [t for t, _ in leg] == [t for t, k in ev if k.kind != "release"]
    assert len(leg) == 1 + 4 + 1  # press, repeats at .3 .35 .4 .45, q


# ----------------------------------------------------------------------------- key map

# the defaults as the brief lists them (written out here, not read from the code)
BRIEF_DEFAULTS = {
    "left": "aim_ccw", "right": "aim_cw", "up": "aim_fine_ccw", "down": "aim_fine_cw",
    "shift+left": "aim_fine_ccw", "shift+right": "aim_fine_cw", "space": "shoot",
    "w": "spin_up", "s": "spin_down", "a": "spin_left", "d": "spin_right", "x": "spin_reset",
    "b": "place", "enter": "confirm", "esc": "cancel", "h": "help", "?": "help", "p": "pause",
    "q": "quit", "f": "fast_forward", "g": "aim_aid", "c": "call_pocket", "o": "push_out",
    "n": "bell", "u": "undo", "r": "rerack",
}


def test_keymap_defaults_match_the_brief():
    km = KeyMap()
    for spec, action in BRIEF_DEFAULTS.items():
        assert km.action(parse_key(spec)) == action, spec
    assert km.keys_for("aim_fine_ccw") == ["up", "shift+left"]
    assert km.keys_for("help") == ["h", "?"]
    assert km.action(K("z")) is None and km.action(K("f1")) is None


def test_keymap_kinds_shift_fallback_and_modifiers():
    km = KeyMap()
    assert km.action(K("space", "release")) == "shoot"
    assert km.action(K("left", "repeat")) == "aim_ccw"
    assert km.action(K("?", shift=True)) == "help"  # kitty: shift+"/" reported as "?"
    assert km.action(K("q", shift=True)) == "quit"  # caps lock
    assert km.action(K("left", shift=True)) == "aim_fine_ccw"  # own binding beats fallback
    assert km.action(K("q", ctrl=True)) is None  # ctrl and alt are not dropped
    assert km.action(K("left", alt=True)) is None
    with pytest.raises(ValueError, match="unknown action 'shot'"):
        km.keys_for("shot")


def test_keymap_help_lines_list_every_bound_action_with_its_keys():
    lines = KeyMap().help_lines()
    assert len(lines) == len(KeyMap.DEFAULTS)
    assert any(line.startswith("up, shift+left ") for line in lines)
    assert any(line.startswith("h, ? ") and "help" in line for line in lines)
    assert len({line.index(line.split("  ")[-1].strip()) for line in lines}) == 1  # aligned
    lines = parse_keymap("undo =\nrerack =").help_lines()
    assert len(lines) == len(KeyMap.DEFAULTS) - 2
    assert not any("practice" in line for line in lines)


CONF = """\
# my keys
shoot = enter, s   # the space bar is broken

confirm = y
aim_ccw = j, shift+j
undo =
help = hash, F1
"""


def test_keys_conf_overrides_defaults_and_takes_keys_from_them():
    km = parse_keymap(CONF)
    assert km.action(K("enter")) == "shoot" and km.action(K("s")) == "shoot"
    assert km.action(K("space")) is None
    assert km.keys_for("spin_down") == []  # "s" was taken by shoot
    assert km.action(K("y")) == "confirm"
    assert km.action(K("j")) == "aim_ccw" and km.action(K("j", shift=True)) == "aim_ccw"
    assert km.action(K("left")) is None
    assert km.keys_for("undo") == [] and km.action(K("u")) is None
    assert km.action(K("#")) == "help" and km.action(K("f1")) == "help"
    assert km.action(K("q")) == "quit"  # untouched actions keep their defaults


@pytest.mark.parametrize("text,line,words", [
    ("shoot = space\nshot = x\n", 2, "unknown action 'shot' \\(known: aim_ccw, aim_cw,"),
    ("\n\nshoot = spce\n", 3, "unknown key name 'spce'"),
    ("shoot space\n", 1, "expected 'action = key, key'"),
    ("= space\n", 1, "expected 'action = key, key'"),
    ("shoot = space\nshoot = enter\n", 2, "already set on line 1"),
    ("shoot = space\nquit = space\n", 2, "key 'space' is already bound to shoot on line 1"),
    ("shoot = space,,enter\n", 1, "empty key name"),
    ("shoot = hyper+space\n", 1, "unknown modifier 'hyper'"),
])
def test_keys_conf_errors_name_the_line(text, line, words):
    with pytest.raises(ValueError, match=f"^keys.conf line {line}: .*{words}"):
        parse_keymap(text)


def test_keymap_constructor_errors():
    with pytest.raises(ValueError, match="unknown action 'fly'"):
        KeyMap({"fly": ["x"]})
    with pytest.raises(ValueError, match="bound to both"):
        KeyMap({"shoot": ["x"], "quit": ["x"]})


@pytest.mark.parametrize("text, line", [
    ("pause = ctrl+c\n", 1), ("\nhelp = ctrl+z\n", 2), ("pause = ctrl+shift+c\n", 1),
    ("pause = ctrl+alt+z\n", 1), ("quit = q, ctrl+\\\n", 1),
])
def test_keys_the_terminal_keeps_cannot_be_bound(text, line):
    with pytest.raises(ValueError, match=f"^keys.conf line {line}: key '.*' cannot be bound: "
                                         "Ctrl-"):
        parse_keymap(text)
    with pytest.raises(ValueError, match="cannot be bound"):
        KeyMap({"pause": ["ctrl+c"]})


@pytest.mark.parametrize("text, missing", [
    ("shoot =\n", "shoot"), ("quit =\n", "quit"), ("confirm =\n", "confirm"),
    ("pause = space\n", "shoot"),  # taken from shoot by another binding
    ("pause = q\nhelp = enter\n", "confirm and quit"),
    ("".join(f"{a} =\n" for a in ACTIONS), "shoot and confirm and quit"),
])
def test_a_map_that_leaves_no_way_to_play_or_leave_is_refused(text, missing):
    with pytest.raises(ValueError, match=f"^keys.conf: no key left for {missing}: a game "):
        parse_keymap(text)


def test_the_required_actions_can_move_to_other_keys():
    km = parse_keymap("shoot = enter\nconfirm = tab\nquit = ctrl+q\n")
    assert km.action(K("enter")) == "shoot" and km.action(K("q", ctrl=True)) == "quit"


def test_a_byte_order_mark_is_accepted(tmp_path):
    p = tmp_path / "keys.conf"
    p.write_bytes("\ufeffpause = k\n".encode())
    assert load_keymap(p).action(K("k")) == "pause"


def test_an_unreadable_default_config_falls_back_with_a_warning(tmp_path):
    xdg = tmp_path / "xdg"
    (xdg / "termpool" / "keys.conf").mkdir(parents=True)  # a directory where the file goes
    said = []
    km = load_keymap(env={"XDG_CONFIG_HOME": str(xdg)}, warn=said.append)
    assert km.action(K("space")) == "shoot"
    assert len(said) == 1 and said[0].startswith("cannot read key map ")
    assert said[0].endswith("Is a directory; playing with the default keys")
    # An explicit --keymap that cannot be read stays an error.
    with pytest.raises(ValueError, match="Is a directory"):
        load_keymap(xdg / "termpool" / "keys.conf")


def test_a_config_directory_that_cannot_be_entered_falls_back(tmp_path):
    import ast
    import shutil
    import tempfile
    from pathlib import Path

    from unprivileged import as_nobody

    xdg = Path(tempfile.mkdtemp(dir="/tmp"))
    try:
        (xdg / "termpool").mkdir(mode=0o700)
        (xdg / "termpool" / "keys.conf").write_text("pause = k\n")
        xdg.chmod(0o755)
        (xdg / "termpool").chmod(0o000)

        def load():
            said = []
            km = load_keymap(env={"XDG_CONFIG_HOME": str(xdg)}, warn=said.append)
            return km.action(K("space")), said

        action, said = ast.literal_eval(as_nobody(load))
        assert action == "shoot" and len(said) == 1 and "Permission denied" in said[0]
    finally:
        (xdg / "termpool").chmod(0o700)
        shutil.rmtree(xdg)


@pytest.mark.parametrize("text", ["shoot = space\nshot = x\n", "pause = space\n"])
def test_a_default_config_with_a_mistake_falls_back_with_a_warning(tmp_path, text):
    xdg = tmp_path / "xdg"
    (xdg / "termpool").mkdir(parents=True)
    (xdg / "termpool" / "keys.conf").write_text("quit = k\n" + text)
    said = []
    km = load_keymap(env={"XDG_CONFIG_HOME": str(xdg)}, warn=said.append)
    # The defaults whole: none of the file's lines, the good ones neither.
    assert km.action(K("space")) == "shoot" and km.action(K("q")) == "quit"
    assert km.action(K("k")) is None
    assert len(said) == 1 and said[0].startswith("keys.conf")
    assert said[0].endswith("; playing with the default keys")
    # The same file given explicitly stays an error.
    with pytest.raises(ValueError, match="^keys.conf"):
        load_keymap(xdg / "termpool" / "keys.conf")


def test_load_keymap_finds_the_config_file(tmp_path):
    xdg = tmp_path / "xdg"
    # missing file: the defaults
    km = load_keymap(env={"XDG_CONFIG_HOME": str(xdg)})
    assert km.action(K("space")) == "shoot"
    (xdg / "termpool").mkdir(parents=True)
    (xdg / "termpool" / "keys.conf").write_text("shoot = enter\nconfirm = tab\n")
    assert load_keymap(env={"XDG_CONFIG_HOME": str(xdg)}).action(K("enter")) == "shoot"
    # no XDG_CONFIG_HOME: ~/.config
    home = tmp_path / "home"
    (home / ".config" / "termpool").mkdir(parents=True)
    (home / ".config" / "termpool" / "keys.conf").write_text("quit = k\n")
    assert load_keymap(env={"HOME": str(home)}).action(K("k")) == "quit"
    # an explicit path
    p = tmp_path / "mine.conf"
    p.write_text("pause = k\n")
    assert load_keymap(p).action(K("k")) == "pause"


def test_load_keymap_errors(tmp_path):
    with pytest.raises(ValueError, match="^cannot read key map '.*nope.conf': No such file"):
        load_keymap(tmp_path / "nope.conf")
    bad = tmp_path / "keys.conf"
    bad.write_bytes(b"shoot = \xff\n")
    with pytest.raises(ValueError, match="^.*/keys.conf: not UTF-8 text$"):
        load_keymap(bad)
    bad.write_text("# ok\nshoot = spce\n")
    with pytest.raises(ValueError, match="^keys.conf line 2: unknown key name 'spce'$"):
        load_keymap(bad)
    d = tmp_path / "dir.conf"
    d.mkdir()
    with pytest.raises(ValueError, match="^cannot read key map '.*dir.conf': Is a directory"):
        load_keymap(d)


# ----------------------------------------------------------------------------- aiming


def hold_times(delay: float, rate: float, duration: float, t0: float = 0.0) -> list[float]:
    """Event times of a key held `duration` s: the press, then auto-repeats."""
    times = [t0]
    k = 0
    while (t := t0 + delay + k * rate) < t0 + duration:
        times.append(t)
        k += 1
    return times


def test_aim_taps_and_fine_steps():
    aim = AimControl()
    assert aim.step(K("left"), 0.0) == pytest.approx(0.5)
    assert aim.step(K("right"), 1.0) == pytest.approx(-0.5)
    assert aim.step(K("up"), 2.0) == pytest.approx(0.1)
    assert aim.step(K("down"), 3.0) == pytest.approx(-0.1)
    assert aim.step(K("left", shift=True), 4.0) == pytest.approx(0.1)
    assert aim.step(K("right", shift=True), 5.0) == pytest.approx(-0.1)
    assert aim.step(K("q"), 6.0) == 0.0
    assert aim.step(K("left", "release"), 7.0) == 0.0
    # taps a human makes (a quarter second apart) never accelerate
    assert [aim.step(K("left"), 8 + 0.25 * i) for i in range(6)] == [0.5] * 6


@pytest.mark.parametrize("rate", [0.02, 0.033, 0.05])
def test_aim_hold_accelerates_to_several_degrees_per_repeat(rate):
    aim = AimControl()
    steps = [aim.step(K("left"), t) for t in hold_times(0.5, rate, 2.5)]
    assert steps[0] == pytest.approx(0.5)
    assert all(s > 0 for s in steps)
    assert all(b >= a - 1e-12 for a, b in zip(steps[2:], steps[3:], strict=False))  # speeds up
    assert steps[-1] > 4 * steps[2]
    assert steps[-1] >= 100 * rate  # at least 100 deg/s at the end: 3.3 deg per 33 ms repeat


def test_aim_turn_rate_does_not_depend_on_the_repeat_rate():
    totals = []
    for delay, rate in [(0.5, 0.033), (0.5, 0.02), (0.5, 0.05)]:
        aim = AimControl()
        totals.append(sum(aim.step(K("right"), t) for t in hold_times(delay, rate, 2.5)))
    assert all(t < -100 for t in totals)  # held 2.5 s: a real sweep
    assert max(totals) - min(totals) < 0.2 * abs(min(totals))


def test_aim_kitty_repeats_and_legacy_presses_turn_alike():
    times = hold_times(0.5, 0.033, 2.0)
    legacy, kitty = AimControl(), AimControl()
    a = sum(legacy.step(K("left"), t) for t in times)
    b = kitty.step(K("left"), times[0]) + sum(kitty.step(K("left", "repeat"), t)
                                             for t in times[1:])
    assert a == pytest.approx(b, rel=0.05)


def test_aim_direction_change_and_release_reset_the_hold():
    aim = AimControl()
    for t in hold_times(0.3, 0.03, 1.5):
        aim.step(K("left"), t)
    assert aim.step(K("right"), 1.52) == pytest.approx(-0.5)  # new direction: a tap
    for t in hold_times(0.3, 0.03, 1.5, t0=2.0):
        aim.step(K("left", "repeat" if t > 2.0 else "press"), t)
    aim.step(K("left", "release"), 3.5)
    assert aim.step(K("left", "repeat"), 3.52) == pytest.approx(0.5)
    # a fine key held speeds up too, but stays a fine key (see the test below)
    fine = [aim.step(K("up"), t) for t in hold_times(0.3, 0.03, 2.0, t0=5.0)]
    assert fine[0] == pytest.approx(0.1) and all(0 < f < 0.5 for f in fine)


@pytest.mark.parametrize("rate", [0.02, 0.033, 0.05])
def test_a_held_fine_key_turns_a_few_degrees_a_second_and_taps_stay_a_tenth(rate):
    aim = AimControl()
    # Held a second (auto-repeat as presses, as in tmux): the few degrees between a rough
    # aim and a pot, where 0.1 degree an event took 20-30 presses; and as much whatever
    # the terminal's repeat rate (the hold's time counts, not its events).
    turned = sum(aim.step(K("up"), t) for t in hold_times(0.5, rate, 1.5))
    at_50hz = sum(AimControl().step(K("up"), t) for t in hold_times(0.5, 0.02, 1.5))
    assert 4.0 <= turned <= 12.0 and turned == pytest.approx(at_50hz, rel=0.15)
    # Taps a human makes stay a tenth of a degree each, either way.
    assert [aim.step(K("down"), 10 + 0.25 * i) for i in range(5)] == [pytest.approx(-0.1)] * 5
    # A fine hold never outruns a coarse one.
    coarse = sum(AimControl().step(K("left"), t) for t in hold_times(0.5, rate, 1.5))
    assert coarse > 2 * turned


# ----------------------------------------------------------------------------- power


def run_power(pc: PowerCharge, events, frames: float | None = 1 / 60, until: float = 6.0):
    """Feed (t, Key) events, polling every `frames` s in between (None: once, at `until`);
    return [(t, power)]."""
    shots = []
    ev = sorted(events, key=lambda e: e[0])
    i = 0
    t = 0.0
    while True:
        next_ev = ev[i][0] if i < len(ev) else None
        next_poll = t if frames is not None else None
        if next_ev is not None and (next_poll is None or next_ev <= next_poll):
            p = pc.key(ev[i][1], next_ev)
            if p is not None:
                shots.append((next_ev, p))
            i += 1
            continue
        if next_poll is None:
            p = pc.poll(until)
            if p is not None:
                shots.append((until, p))
            break
        if next_poll > until:
            break
        p = pc.poll(next_poll)
        if p is not None:
            shots.append((next_poll, p))
        t = next_poll + frames
    return shots


def legacy_hold(delay, rate, duration, t0=0.0):
    return [(t, SPACE) for t in hold_times(delay, rate, duration, t0)]


def kitty_hold(delay, rate, duration, t0=0.0):
    times = hold_times(delay, rate, duration, t0)
    return ([(times[0], SPACE)] + [(t, K("space", "repeat")) for t in times[1:]]
            + [(t0 + duration, K("space", "release"))])


def test_release_mode_fires_on_the_release_event():
    for duration, power in [(0.6, 0.5), (0.9, 0.75), (1.8, 1.0), (0.3, 0.25)]:
        pc = PowerCharge("release", full_time=1.2)
        shots = run_power(pc, kitty_hold(0.5, 0.033, duration))
        assert shots == [(duration, pytest.approx(power))]
    pc = PowerCharge("release")
    assert pc.label == "hold space, release to shoot"
    pc.key(SPACE, 1.0)
    assert pc.active and pc.label == "release space to shoot"
    assert pc.level(1.3) == pytest.approx(0.25) and pc.level(5.0) == 1.0
    assert pc.key(K("space", "repeat"), 1.5) is None and pc.poll(9.0) is None
    assert pc.key(K("space", "release"), 1.6) == pytest.approx(0.5)
    assert not pc.active and pc.level(2.0) == 0.0
    assert pc.key(K("space", "release"), 3.0) is None  # no charge: no shot


def test_release_mode_press_while_charging_restarts_the_charge():
    pc = PowerCharge("release", full_time=1.0)
    pc.key(SPACE, 0.0)
    pc.key(SPACE, 2.0)  # the release of the first press was lost
    assert pc.key(K("space", "release"), 2.5) == pytest.approx(0.5)


def test_classic_mode_ping_pong_meter():
    pc = PowerCharge("classic", full_time=1.2)
    assert pc.label == "space to start, space to strike"
    assert pc.key(SPACE, 0.0) is None and pc.active
    assert pc.label == "space to strike"
    levels = [pc.level(t) for t in (0.0, 0.6, 1.2, 1.8, 2.4, 3.0)]
    assert levels == pytest.approx([0.0, 0.5, 1.0, 0.5, 0.0, 0.5])
    assert pc.key(K("space", "release"), 1.0) is None  # only presses count
    assert pc.key(K("space", "repeat"), 1.0) is None
    assert pc.poll(1.5) is None
    assert pc.key(SPACE, 1.8) == pytest.approx(0.5)
    assert not pc.active
    pc.key(SPACE, 10.0)
    assert pc.key(SPACE, 12.4) == PowerCharge.MIN_POWER  # the meter was at the bottom


TERMINALS = {  # initial delay, repeat interval
    "xterm": (0.5, 0.033), "fast": (0.2, 0.02), "slow": (0.6, 0.05), "mac": (0.25, 0.03),
}


@pytest.mark.parametrize("term", sorted(TERMINALS))
@pytest.mark.parametrize("duration", [0.65, 0.8, 1.0, 1.15, 2.0])
def test_repeat_mode_infers_the_release(term, duration):
    delay, rate = TERMINALS[term]
    pc = PowerCharge("repeat", full_time=1.2)
    events = legacy_hold(delay, rate, duration)
    shots = run_power(pc, events)
    assert len(shots) == 1
    t_fire, power = shots[0]
    last = events[-1][0]
    # the strike follows the last repeat within two intervals and a frame (0.1 s at 25
    # repeats a second)
    gap = max(PowerCharge.GAP_MIN, PowerCharge.GAP_INTERVALS * rate)
    assert duration <= t_fire <= last + gap + 1 / 60
    # The charge runs from the first repeat (the first sign of a hold); the inferred release
    # is within one repeat interval of the real one.
    assert abs(power - max(PowerCharge.MIN_POWER, min(1.0, (duration - delay) / 1.2))) \
        <= rate / 1.2 + 1e-9


@pytest.mark.parametrize("term", sorted(TERMINALS))
def test_repeat_mode_meter_shows_the_power_that_strikes(term):
    # A legacy terminal: after the last repeat the meter must not run on to the inferred
    # release and then strike less; from one interval after that repeat it holds at the
    # power the release will strike, and each frame up to the strike shows it.
    delay, rate = TERMINALS[term]
    for duration in (0.7, 1.0, 1.1):
        pc = PowerCharge("repeat", full_time=1.2)
        events = legacy_hold(delay, rate, duration)
        for t, k in events:
            assert pc.key(k, t) is None
        last = events[-1][0]
        shown = []
        t = last
        while (p := pc.poll(t)) is None:
            shown.append((t, pc.level(t)))
            t += 1 / 240
        # rising while repeats may still come, then held at the strike's power
        assert shown[0][1] < p and [x for _, x in shown] == sorted(x for _, x in shown)
        assert all(x == p for u, x in shown if u >= last + rate + 1e-9)
        assert shown[-1][1] == p


def test_a_terminal_with_key_kinds_in_repeat_mode_keeps_its_meter_running():
    # Repeat mode, but the terminal says which events are repeats and releases: the
    # release is real, so the meter runs until it comes.
    pc = PowerCharge("repeat", full_time=1.2)
    events = kitty_hold(0.5, 0.033, 1.0)
    for t, k in events[:-1]:
        assert pc.key(k, t) is None
    last = events[-2][0]
    assert pc.level(last + 0.1) == pytest.approx((last + 0.1) / 1.2)
    assert pc.key(*events[-1][::-1]) == pytest.approx(1.0 / 1.2)


def test_repeat_mode_with_jitter_never_fires_early():
    rng = random.Random(5)
    for trial in range(40):
        delay, rate = rng.uniform(0.2, 0.7), rng.uniform(0.02, 0.04)
        duration = rng.uniform(delay + 0.1, 2.0)
        times = [0.0]
        t = delay
        while t < duration:
            times.append(t + rng.uniform(-0.2, 0.2) * rate)  # each repeat late or early
            t += rate
        times.sort()
        pc = PowerCharge("repeat", full_time=1.2)
        shots = run_power(pc, [(t, SPACE) for t in times])
        assert len(shots) == 1, trial
        assert shots[0][0] >= times[-1] + PowerCharge.GAP_MIN - 1e-9
        assert abs(shots[0][1] - max(PowerCharge.MIN_POWER, min(1.0, (duration - times[1])
                                                                / 1.2))) <= 2.0 * rate / 1.2


@pytest.mark.parametrize("delay", [0.25, 0.5, 0.66])
@pytest.mark.parametrize("rate", [0.02, 0.033, 0.04])
def test_legacy_softest_hold_is_a_gentle_shot_and_strikes_promptly(delay, rate):
    # A legacy terminal (presses and repeats only): the softest hold that can be told from
    # a tap is the press and its first repeat; it must be a gentle shot, and every hold
    # strikes within 0.1 s of its last repeat, polled at 60 frames a second.
    for n_repeats in (1, 2, 3):
        duration = delay + (n_repeats - 0.5) * rate
        events = legacy_hold(delay, rate, duration)
        assert len(events) == 1 + n_repeats
        pc = PowerCharge("repeat", full_time=1.2)
        (t_fire, power), = run_power(pc, events)
        assert power <= 0.15
        assert t_fire - events[-1][0] <= 0.1
    for duration in (1.0, 1.6):  # longer holds: the same promptness
        events = legacy_hold(delay, rate, duration)
        (t_fire, _), = run_power(PowerCharge("repeat", full_time=1.2), events)
        assert t_fire - events[-1][0] <= 0.1


def test_a_slow_repeating_terminal_is_learnt_from_the_repeats_after_the_strike():
    # 10 repeats a second: the first hold's gap is too short and it strikes after one
    # repeat; the repeats that follow teach the interval, and the next hold is read whole.
    pc = PowerCharge("repeat", full_time=1.2)
    first = legacy_hold(0.5, 0.1, 1.2)
    shots = run_power(pc, first[:2])
    assert len(shots) == 1
    for t, k in first[2:]:
        pc.observe(k, t)  # the app passes the shoot key's events on while the balls run
    second = legacy_hold(0.5, 0.1, 1.3, t0=5.0)
    (t_fire, power), = run_power(pc, second, until=8.0)
    assert power == pytest.approx((1.3 - 0.5) / 1.2, abs=0.1 / 1.2 + 1e-9)
    assert t_fire >= second[-1][0]


def test_repeat_mode_power_does_not_depend_on_poll_timing():
    events = legacy_hold(0.5, 0.033, 0.93) + legacy_hold(0.3, 0.025, 0.71, t0=3.0)
    results = []
    for frames in (1 / 120, 1 / 60, 1 / 7, 0.5, None):  # None: polled once, at the end
        pc = PowerCharge("repeat", full_time=1.2)
        results.append([p for _, p in run_power(pc, events, frames)])
    # unpolled, the first shot fires at the next key event (the second hold's press)
    assert len(results[0]) == 2
    assert all(r == results[0] for r in results)


def test_repeat_mode_single_tap_falls_back_to_the_meter():
    pc = PowerCharge("repeat", full_time=1.2)
    assert pc.label == "hold space, release to shoot"
    pc.key(SPACE, 0.0)
    assert pc.label == "keep space down to charge, or let go for a meter"
    assert all(pc.poll(t / 100) is None for t in range(0, 300))  # never a feeble shot
    assert pc.fallback and pc.active
    assert "again to strike" in pc.label
    # The meter goes up and down from 0 at the moment the tap was known.
    known = pc.INITIAL_DELAY_MAX
    assert pc.level(known + 1.2 + 0.6) == pytest.approx(0.5)
    assert pc.key(SPACE, known + 1.8) == pytest.approx(0.5)
    assert not pc.active and not pc.fallback


def test_repeat_mode_release_before_the_first_repeat():
    # legacy: a short hold sends one press and nothing else, like a tap: meter fallback
    pc = PowerCharge("repeat")
    assert run_power(pc, [(0.0, SPACE)], until=2.0) == []
    assert pc.fallback
    # a terminal that does send releases: the release counts
    pc = PowerCharge("repeat", full_time=1.2)
    assert run_power(pc, [(0.0, SPACE), (0.3, K("space", "release"))]) == [
        (0.3, pytest.approx(0.25))]


def test_repeat_mode_with_kitty_events_fires_on_the_real_release():
    pc = PowerCharge("repeat", full_time=1.2)
    shots = run_power(pc, kitty_hold(0.5, 0.033, 0.9))
    assert shots == [(0.9, pytest.approx(0.75))]


def test_cancel_and_bad_arguments():
    pc = PowerCharge("repeat")
    for t, k in legacy_hold(0.5, 0.033, 0.8):
        pc.key(k, t)
    pc.cancel()
    assert not pc.active and pc.poll(5.0) is None and pc.level(1.0) == 0.0
    with pytest.raises(ValueError, match="power mode .* not 'hold'"):
        PowerCharge("hold")
    with pytest.raises(ValueError, match="full_time"):
        PowerCharge("release", full_time=0)


def test_power_is_bit_identical_for_the_same_stream():
    ev = legacy_hold(0.43, 0.031, 1.07) + legacy_hold(0.5, 0.033, 0.3, t0=3.0)
    a = run_power(PowerCharge("repeat"), ev)
    b = run_power(PowerCharge("repeat"), ev)
    assert a == b and len(a) == 1  # the second "hold" was a tap: meter, no strike yet


@settings(max_examples=150, deadline=None)
@given(mode=st.sampled_from(["release", "repeat", "classic"]),
       stream=st.lists(st.tuples(st.floats(0.0, 0.8), st.sampled_from(["press", "repeat",
                                                                       "release"])),
                       max_size=30))
def test_any_fired_power_is_in_range(mode, stream):
    pc = PowerCharge(mode)
    t = 0.0
    for dt, kind in stream:
        t += dt
        for p in (pc.poll(t), pc.key(K("space", kind), t)):
            assert p is None or PowerCharge.MIN_POWER <= p <= 1.0
        assert 0.0 <= pc.level(t) <= 1.0


def test_scripts_drive_power_in_both_terminal_kinds():
    ev = parse_script("wait 1 space-hold 0.9", repeat_delay=0.5, repeat_rate=0.033)
    assert run_power(PowerCharge("release", full_time=1.2), ev) == [(1.9, pytest.approx(0.75))]
    shots = run_power(PowerCharge("repeat", full_time=1.2), legacy_events(ev))
    assert len(shots) == 1 and abs(shots[0][1] - 0.4 / 1.2) <= 0.033 / 1.2 + 1e-9


def test_repeat_mode_quick_tap_tap_is_the_softest_hold() -> None:
    # Press, press 0.4 s later, then nothing (tmux send-keys, a quick double tap): on a
    # terminal with a 0.4 s repeat delay this is a hold released at its first repeat, so it
    # strikes softly, and at once.
    pc = PowerCharge("repeat")
    assert pc.key(Key("space"), 10.0) is None
    assert pc.key(Key("space"), 10.4) is None
    fired = None
    t = 10.4
    while fired is None:
        t += 1 / 60
        fired = pc.poll(t)
    assert fired <= 0.15 and t - 10.4 <= 0.1
    assert not pc.active


def test_set_power_strikes_at_once_at_the_level_set():
    for mode in ("release", "repeat", "classic"):
        pc = PowerCharge(mode)
        pc.preset(0.3)
        assert pc.mode_name == "set 30%" and "30%" in pc.label
        assert pc.key(K("space", "release"), 0.5) is None
        assert pc.key(SPACE, 1.0) == pytest.approx(0.3)
        assert pc.preset_level == pytest.approx(0.3)  # it stays set for the next shot
        pc.preset(None)
        assert pc.preset_level is None and pc.mode_name.startswith(("hold", "meter"))


def test_scripts_set_the_emulated_repeat_delay_and_interval():
    ev = parse_script("space-hold 0.4 repeat 0.5 0.05 space-hold 0.62")
    reps = [round(t, 6) for t, k in ev if k.kind == "repeat"]
    # the first hold with the defaults (0.3 s, 33 ms), the second as the token says
    assert reps[:4] == [0.3, 0.333, 0.366, 0.399]
    second = 0.4 + 0.05  # the hold and one tap gap
    assert reps[4:] == [round(second + 0.5 + k * 0.05, 6) for k in range(3)]
    for bad, needle in [("repeat 0.5", "repeat needs"), ("repeat 0 0.03", "delay must"),
                        ("repeat 0.5 0.001", "interval at least"),
                        ("repeat x 0.03", "repeat delay: 'x' is not a number"),
                        ("repeat 0.5 9", "at most 2 seconds")]:
        with pytest.raises(ValueError, match=needle):
            parse_script(bad)
