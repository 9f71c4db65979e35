"""Key events: one `Key` type for every terminal, decoders, and headless key scripts.

A `Key` is the same whatever the terminal sent: `Key("left")`, `Key("a", shift=True)` (typed
"A"), `Key("space", kind="release")` (kitty protocol only). Names are "left" "right" "up"
"down" "home" "end" "pageup" "pagedown" "insert" "delete" "space" "enter" "esc" "tab"
"backspace" "f1".."f12", or one lowercase character ("a", "1", "?"). A letter typed with
shift is its lowercase name with shift=True; other characters are what was typed ("?" is "?",
and shift may or may not be set, depending on the terminal).

- `decode(text)`: raw terminal input -> keys. Reads legacy control characters, ESC+char (alt),
  CSI/SS3 arrows and function keys with xterm modifiers (CSI 1;mod X, CSI n;mod ~), rxvt and
  linux-console variants, xterm modifyOtherKeys (CSI 27;mod;code ~) and the kitty keyboard
  protocol (CSI code[:shifted[:base]];mod[:event][;text] u) with press/repeat/release.
  Unknown sequences, mouse reports, focus events and bare modifier keys give no key; a
  bracketed paste is skipped whole.
- `from_keystroke(ks)`: a blessed `Keystroke` (what `Terminal.inkey()` returns) -> Key or None.
  A Keystroke is the raw text it was read from, so it goes through `decode`; blessed's own
  name is used only for sequences decode does not know (terminfo-specific ones).
- `parse_key(spec)`: "shift+left", "q", "?", "ctrl+c" -> Key (config files and scripts).
- `decode_input(text)`: like `decode`, plus SGR mouse reports as `Mouse` events, in order.
- `parse_script(text)`: "right*5 wait 0.2 space-hold 1.5 q y" -> [(t, Key), ...] on a virtual
  clock, as a kitty terminal with event reports would deliver them (taps are press+release,
  holds press, auto-repeats, release; `click COL ROW` is a left click, as `Mouse` events).
  `legacy_events` turns that into what a legacy terminal delivers (presses only).

Kitty protocol: key releases reach the program only with "report event types" and "report
all keys as escape codes" both on (text keys such as space otherwise arrive as plain text, with
no release). `KITTY_FLAGS` holds the keyword arguments for blessed's
`Terminal.enable_kitty_keyboard(**KITTY_FLAGS)`.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

KINDS = ("press", "repeat", "release")
NAMED_KEYS = (
    "left", "right", "up", "down", "home", "end", "pageup", "pagedown", "insert", "delete",
    "space", "enter", "esc", "tab", "backspace",
) + tuple(f"f{i}" for i in range(1, 13))
MODIFIERS = ("ctrl", "alt", "shift")
# spellings accepted in specs besides the names above; the characters a config line uses for
# its own syntax (",", "#", "+", "=") have word names too
KEY_ALIASES = {
    "escape": "esc", "return": "enter", "pgup": "pageup", "pgdn": "pagedown", "del": "delete",
    "ins": "insert", "comma": ",", "hash": "#", "plus": "+", "equal": "=",
}
SPEC_NAMES = {",": "comma", "#": "hash", "+": "plus", "=": "equal"}

KITTY_FLAGS = {"disambiguate": True, "report_events": True, "report_alternates": True,
               "report_all_keys": True}


@dataclass(frozen=True)
class Key:
    """One input event: a key name, the event kind and the modifiers held."""

    name: str
    kind: str = "press"  # "press" | "repeat" | "release"
    shift: bool = False
    ctrl: bool = False
    alt: bool = False

    @property
    def digit(self) -> str | None:
        """The digit 0-9 the key types (without Ctrl or Alt), else None."""
        plain = len(self.name) == 1 and self.name in "0123456789"
        return self.name if plain and not (self.ctrl or self.alt) else None

    @property
    def spec(self) -> str:
        """The key as written in keys.conf and scripts: "ctrl+alt+shift+name" (no kind)."""
        mods = [m for m in MODIFIERS if getattr(self, m)]
        return "+".join(mods + [SPEC_NAMES.get(self.name, self.name)])


# ----------------------------------------------------------------------------- specs


def parse_key(spec: str) -> Key:
    """A key spec ("left", "shift+left", "Q", "?", "ctrl+c", "plus") -> a press Key.

    Raises ValueError naming the spec for an unknown key name or modifier.
    """
    text = spec.strip()
    if not text:
        raise ValueError("empty key name")
    if text == "+":
        parts = ["+"]
    elif text.endswith("++"):  # "shift++" is shift and the "+" key
        parts = text[:-2].split("+") + ["+"]
    else:
        parts = text.split("+")
    *mods, name = (p.strip() for p in parts)
    flags = dict.fromkeys(MODIFIERS, False)
    for mod in mods:
        m = "ctrl" if mod.lower() == "control" else mod.lower()
        if m not in flags:
            raise ValueError(f"unknown modifier '{mod}' in key '{spec}'")
        flags[m] = True
    if not name:
        raise ValueError(f"no key name in key '{spec}'")
    where = "" if name == text else f" in key '{spec}'"
    if len(name) == 1:
        if name.isupper():
            return Key(name.lower(), shift=True, ctrl=flags["ctrl"], alt=flags["alt"])
        if not name.isprintable() or name == " ":
            raise ValueError(f"unknown key name '{name}'{where}")
        return Key(name, **flags)
    low = KEY_ALIASES.get(name.lower(), name.lower())
    if low not in NAMED_KEYS and len(low) != 1:
        raise ValueError(f"unknown key name '{name}'{where}")
    return Key(low, **flags)


# ----------------------------------------------------------------------------- decoding

_CSI_LETTERS = {"A": "up", "B": "down", "C": "right", "D": "left", "H": "home", "F": "end",
                "P": "f1", "Q": "f2", "R": "f3", "S": "f4"}
_TILDE_NUMBERS = {1: "home", 2: "insert", 3: "delete", 4: "end", 5: "pageup", 6: "pagedown",
                  7: "home", 8: "end", 11: "f1", 12: "f2", 13: "f3", 14: "f4", 15: "f5",
                  17: "f6", 18: "f7", 19: "f8", 20: "f9", 21: "f10", 23: "f11", 24: "f12"}
_RXVT_SHIFT = {"a": "up", "b": "down", "c": "right", "d": "left"}  # CSI a..d, SS3 a..d = ctrl
_KEYPAD_SS3 = {c: str(i) for i, c in enumerate("pqrstuvwxy")} | {
    "j": "*", "k": "+", "m": "-", "n": ".", "o": "/", "X": "=", "M": "enter"}
# kitty's private-use code points for keypad keys (the ones a game cares about)
_KITTY_PUA = {57399 + i: str(i) for i in range(10)} | {
    57409: ".", 57410: "/", 57411: "*", 57412: "-", 57413: "+", 57414: "enter", 57415: "=",
    57417: "left", 57418: "right", 57419: "up", 57420: "down", 57421: "pageup",
    57422: "pagedown", 57423: "home", 57424: "end", 57425: "insert", 57426: "delete"}
_KITTY_CODES = {27: "esc", 13: "enter", 9: "tab", 127: "backspace", 8: "backspace", 32: "space"}
# what shift gives on a US layout: kitty without "report alternates" sends the unshifted key
_US_SHIFTED = dict(zip("`1234567890-=[]\\;',./", "~!@#$%^&*()_+{}|:\"<>?", strict=True))
_KIND_CODES = {1: "press", 2: "repeat", 3: "release"}
_PASTE_END = "\x1b[201~"


def _char_key(ch: str, **mods: bool) -> Key | None:
    """A key for one character of plain input (control characters included)."""
    o = ord(ch)
    if ch in "\r\n":
        return Key("enter", **mods)
    if ch == "\t":
        return Key("tab", **mods)
    if ch in "\x7f\x08":
        return Key("backspace", **mods)
    if ch == " ":
        return Key("space", **mods)
    if o == 0:
        return Key("space", **(mods | {"ctrl": True}))
    if o < 27:
        return Key(chr(o + 96), **(mods | {"ctrl": True}))
    if 28 <= o < 32:
        return Key("\\]^_"[o - 28], **(mods | {"ctrl": True}))
    if o == 27:
        return Key("esc", **mods)
    if not ch.isprintable():
        return None
    if ch.isupper():
        return Key(ch.lower(), **(mods | {"shift": True}))
    return Key(ch, **mods)


def _mods(value: int) -> dict[str, bool]:
    """xterm/kitty modifier parameter (1 + bits: shift 1, alt 2, ctrl 4) -> flags."""
    bits = max(0, value - 1)
    return {"shift": bool(bits & 1), "alt": bool(bits & 2), "ctrl": bool(bits & 4)}


def _int(text: str, default: int) -> int:
    """A decimal parameter; the default when empty or not a plain (short) number."""
    ok = 0 < len(text) <= 9 and all("0" <= c <= "9" for c in text)
    return int(text) if ok else default


def _chr(code: int) -> str | None:
    return chr(code) if 0 <= code < 0x110000 else None


def _mod_field(field: str) -> tuple[dict[str, bool], str]:
    """A "mod[:event]" parameter -> (modifier flags, kind)."""
    mod, _, event = field.partition(":")
    return _mods(_int(mod, 1)), _KIND_CODES.get(_int(event, 1), "press")


def _kitty_key(params: str) -> Key | None:
    """CSI code[:shifted[:base]];mod[:event][;text] u -> Key (modifier-only keys: None)."""
    fields = params.split(";")
    codes = fields[0].split(":")
    code = _int(codes[0], -1)
    shifted = _int(codes[1], 0) if len(codes) > 1 else 0
    mods, kind = _mod_field(fields[1] if len(fields) > 1 else "")
    if code in _KITTY_CODES:
        name = _KITTY_CODES[code]
    elif code in _KITTY_PUA:
        name = _KITTY_PUA[code]
    elif 32 < code < 0xE000 or code > 0xF8FF:
        ch = _chr(code)
        if ch is None or not ch.isprintable():
            return None
        name = ch.lower()
        if mods["shift"] and not ch.isalpha():  # "?" is shift+"/": report the character
            alt = _chr(shifted) if shifted else _US_SHIFTED.get(ch, ch)
            name = alt if alt and alt.isprintable() else ch
    else:
        return None  # modifier keys alone, media keys, caps lock ...
    return Key(name, kind, **mods)


def _csi_key(params: str, final: str) -> Key | None:
    if params.startswith(("<", "?", ">", "=")):
        return None  # mouse reports and replies to queries
    fields = params.split(";") if params else []
    if final == "u":
        return _kitty_key(params) if fields else None
    if final == "~":
        if len(fields) >= 3 and fields[0] == "27":  # xterm modifyOtherKeys
            ch = _chr(_int(fields[2], -1))
            key = _char_key(ch) if ch else None
            if key is None:
                return None
            mods = _mods(_int(fields[1], 1))
            return replace(key, shift=key.shift or mods["shift"], ctrl=key.ctrl or mods["ctrl"],
                           alt=mods["alt"])
        name = _TILDE_NUMBERS.get(_int(fields[0], -1)) if fields else None
        if name is None:
            return None
        mods, kind = _mod_field(fields[1]) if len(fields) > 1 else ({}, "press")
        return Key(name, kind, **mods)
    if final == "Z":
        return Key("tab", shift=True)
    if final in _RXVT_SHIFT and not fields:
        return Key(_RXVT_SHIFT[final], shift=True)
    if final in _CSI_LETTERS:
        mods, kind = _mod_field(fields[1]) if len(fields) > 1 else ({}, "press")
        return Key(_CSI_LETTERS[final], kind, **mods)
    return None


def _ss3_key(rest: str) -> tuple[Key | None, int]:
    """SS3 (ESC O) sequences: the key and how many characters after ESC O it used."""
    if "1" <= rest[0] <= "9" and len(rest) >= 2 and rest[1] in "PQRS":  # Konsole: ESC O 2 P
        return Key(_CSI_LETTERS[rest[1]], **_mods(int(rest[0]))), 2
    ch = rest[0]
    if ch in _CSI_LETTERS:
        return Key(_CSI_LETTERS[ch]), 1
    if ch in _RXVT_SHIFT:
        return Key(_RXVT_SHIFT[ch], ctrl=True), 1
    if ch in _KEYPAD_SS3:
        return Key(_KEYPAD_SS3[ch]), 1
    return None, 1


def _read_csi(text: str, i: int) -> tuple[str, str, int]:
    """Parameters, final character and end index of the CSI sequence whose body starts at i.

    The final is "" if the text ends first, and "?" plus the bad character's index if a
    character that cannot be in a CSI sequence comes first.
    """
    j = i
    while j < len(text) and "\x30" <= text[j] <= "\x3f":
        j += 1
    params = text[i:j]
    while j < len(text) and "\x20" <= text[j] <= "\x2f":
        j += 1
    if j >= len(text):
        return params, "", j
    if not "\x40" <= text[j] <= "\x7e":
        return params, "?", j
    return params, text[j], j + 1


def _decode_one(text: str, i: int) -> tuple[Key | None, int]:
    """The key at text[i] (None for input that is no key) and the index after it."""
    ch = text[i]
    if ch != "\x1b":
        return _char_key(ch), i + 1
    if i + 1 >= len(text):
        return Key("esc"), i + 1
    nxt = text[i + 1]
    if nxt == "[" and i + 2 < len(text):
        if text[i + 2] == "[" and i + 3 < len(text) and text[i + 3] in "ABCDE":
            return Key(f"f{'ABCDE'.index(text[i + 3]) + 1}"), i + 4  # linux console F1-F5
        params, final, end = _read_csi(text, i + 2)
        if final == "":
            return None, end  # cut off: nothing usable follows
        if final == "?":
            return None, end  # broken: drop it, decode on from the character that broke it
        if final == "~" and params == "200":  # bracketed paste: skip the pasted text
            stop = text.find(_PASTE_END, end)
            return None, len(text) if stop < 0 else stop + len(_PASTE_END)
        return _csi_key(params, final), end
    if nxt == "O" and i + 2 < len(text):
        key, used = _ss3_key(text[i + 2:])
        return key, i + 2 + used
    if nxt == "\x1b":
        if text.startswith(("[", "O"), i + 2):  # ESC + a sequence: alt+that key (rxvt)
            key, end = _decode_one(text, i + 1)
            return (replace(key, alt=True) if key else None), end
        return Key("esc"), i + 1  # two Esc presses, not alt+Esc
    key = _char_key(nxt)
    return (replace(key, alt=True) if key else None), i + 2


def decode(text: str) -> list[Key]:
    """Raw terminal input -> the keys in it, in order (see the module docstring)."""
    keys: list[Key] = []
    i = 0
    while i < len(text):
        key, i = _decode_one(text, i)
        if key is not None:
            keys.append(key)
    return keys


_BLESSED_NAMES = {"PGUP": "pageup", "PGDOWN": "pagedown", "ESCAPE": "esc", "EXIT": "esc",
                  "DC": "delete", "IC": "insert", "PPAGE": "pageup", "NPAGE": "pagedown",
                  "SLEFT": "shift+left", "SRIGHT": "shift+right", "SUP": "shift+up",
                  "SR": "shift+up", "SDOWN": "shift+down", "SF": "shift+down",
                  "BTAB": "shift+tab", "KP_ENTER": "enter"}


def _from_blessed_name(ks: object) -> Key | None:
    """Key from a blessed keystroke's name ("KEY_SHIFT_LEFT_REPEATED") when decode knew none."""
    name = getattr(ks, "name", None)
    if not name or not name.startswith("KEY_"):
        return None
    base = name[4:]
    kind = "press"
    for suffix, k in (("_REPEATED", "repeat"), ("_RELEASED", "release")):
        if base.endswith(suffix):
            base, kind = base[: -len(suffix)], k
    mods = dict.fromkeys(MODIFIERS, False)
    parts = base.split("_")
    while len(parts) > 1 and parts[0].lower() in mods:
        mods[parts.pop(0).lower()] = True
    base = "_".join(parts)
    spec = _BLESSED_NAMES.get(base, base.lower())
    try:
        key = parse_key(spec)
    except ValueError:
        return None
    return replace(key, kind=kind, shift=key.shift or mods["shift"], ctrl=mods["ctrl"],
                   alt=mods["alt"])


def from_keystroke(ks: object) -> Key | None:
    """A blessed `Keystroke` (from `Terminal.inkey()`) -> Key, or None (timeout, no key).

    The keystroke's text is decoded; when that does not give exactly one key (a sequence
    only the terminfo entry knows), blessed's name for it is used instead.
    """
    keys = decode(str(ks))
    if len(keys) == 1:
        return keys[0]
    named = _from_blessed_name(ks)
    if named is not None:
        return named
    return keys[0] if keys else None


# ----------------------------------------------------------------------------- scripts


# Limits of a key script, so that a script file cannot ask for unbounded time or memory.
MAX_TAPS = 1000  # NAME*N
MAX_HOLD_S = 60.0  # NAME-hold SECONDS
MAX_SCRIPT_S = 3600.0  # the whole script, on the virtual clock
MAX_SCRIPT_EVENTS = 200_000
MIN_REPEAT_S, MAX_REPEAT_S = 0.005, 2.0  # the auto-repeat a script may emulate (`repeat D I`)


def _seconds(text: str, what: str, most: float = MAX_SCRIPT_S) -> float:
    try:
        val = float(text)
    except ValueError:
        raise ValueError(f"{what}: '{text[:20]}' is not a number of seconds") from None
    if not math.isfinite(val) or val < 0:
        raise ValueError(f"{what}: seconds must be finite and not negative, not '{text[:20]}'")
    if val > most:
        raise ValueError(f"{what}: at most {most:g} seconds, not {val:g}")
    return val


def _cell(text: str) -> bool:
    """A whole number a script may hold: ASCII digits, below 10000."""
    return text.isascii() and text.isdigit() and len(text) <= 4


@dataclass(frozen=True)
class Mouse:
    """A mouse report (SGR mode): the cell (0-based), what happened and with which button."""

    col: int
    row: int
    kind: str = "press"  # "press" | "drag" | "release" | "move" | "wheel_up" | "wheel_down"
    button: int = 0  # 0 left, 1 middle, 2 right


_SGR_MOUSE = re.compile(r"\x1b\[<(\d+);(\d+);(\d+)([Mm])")


def _mouse(code: int, col: int, row: int, final: str) -> Mouse:
    if code & 64:
        return Mouse(col - 1, row - 1, "wheel_down" if code & 1 else "wheel_up", 3)
    button = code & 3
    if final == "m":
        kind = "release"
    elif code & 32:
        kind = "move" if button == 3 else "drag"
    else:
        kind = "press"
    return Mouse(col - 1, row - 1, kind, button)


def decode_input(text: str) -> list:
    """Raw terminal input -> keys and SGR mouse reports (`Mouse`), in the order they came."""
    out: list = []
    at = 0
    for m in _SGR_MOUSE.finditer(text):
        out += decode(text[at:m.start()])
        out.append(_mouse(int(m.group(1)), int(m.group(2)), int(m.group(3)), m.group(4)))
        at = m.end()
    out += decode(text[at:])
    return out


def _check_length(t: float, events: list) -> None:
    if t > MAX_SCRIPT_S or len(events) > MAX_SCRIPT_EVENTS:
        raise ValueError(f"script: longer than the limit of {MAX_SCRIPT_S:g} seconds or "
                         f"{MAX_SCRIPT_EVENTS} key events")


def read_script(path: str) -> str:
    """The text of the key script in the file at `path` ('-': standard input); a FileError
    whose one line says so too where the keys themselves were given in place of a file."""
    from termpool.files import MAX_SCRIPT_BYTES, FileError, read_text

    try:
        return read_text(path, MAX_SCRIPT_BYTES, "key script")
    except FileError as e:
        if e.missing and " " in path.strip():
            raise FileError(f"{e} (--keys takes a file of keys, or '-' to read them from "
                            "standard input)") from None
        raise


def parse_script(text: str, tap_gap: float = 0.05, repeat_delay: float = 0.3,
                 repeat_rate: float = 0.033) -> list[tuple[float, Key]]:
    """A headless key script -> [(time, Key)] on a virtual clock starting at 0.

    Tokens (whitespace separated): NAME (a key spec: "q", "shift+left", "?"): press at t,
    release at t + tap_gap/2, next token at t + tap_gap; NAME*N: N such taps; wait SECONDS:
    advance the clock; NAME-hold SECONDS: press at t, repeats at t + repeat_delay + k *
    repeat_rate while before t + SECONDS, release at t + SECONDS, next token tap_gap later;
    repeat DELAY INTERVAL: the holds after it repeat like a terminal with that initial delay
    and interval (seconds; `legacy_events` then gives what a legacy terminal sends).
    A bad token raises ValueError("script token 3 'spce': ..."), and so does a script beyond
    the limits (MAX_TAPS taps in a token, holds of MAX_HOLD_S, MAX_SCRIPT_S seconds in all,
    MAX_SCRIPT_EVENTS events).
    """
    if not (tap_gap > 0 and repeat_delay > 0 and repeat_rate > 0):
        raise ValueError("script: tap_gap, repeat_delay and repeat_rate must be positive")
    tokens = text.split()
    events: list[tuple[float, Key]] = []
    t = 0.0
    i = 0
    while i < len(tokens):
        _check_length(t, events)
        tok = tokens[i]
        where = f"script token {i + 1} '{tok if len(tok) <= 40 else tok[:40] + '...'}'"
        try:
            if tok.lower() == "click":  # click COL ROW: a left click on that cell (0-based)
                if i + 2 >= len(tokens) or not all(_cell(v) for v in tokens[i + 1:i + 3]):
                    raise ValueError("click needs a column and a row (whole numbers below "
                                     "10000) after it")
                col, row = int(tokens[i + 1]), int(tokens[i + 2])
                events.append((t, Mouse(col, row, "press")))
                events.append((t + tap_gap / 2, Mouse(col, row, "release")))
                t += tap_gap
                i += 3
                continue
            if tok.lower() == "repeat":  # repeat DELAY INTERVAL: the terminal's auto-repeat
                if i + 2 >= len(tokens):
                    raise ValueError("repeat needs the initial delay and the interval in "
                                     "seconds after it, e.g. 'repeat 0.5 0.033'")
                repeat_delay = _seconds(tokens[i + 1], "repeat delay", MAX_REPEAT_S)
                repeat_rate = _seconds(tokens[i + 2], "repeat interval", MAX_REPEAT_S)
                if repeat_delay <= 0 or repeat_rate < MIN_REPEAT_S:
                    raise ValueError(f"repeat: the delay must be above 0 and the interval at "
                                     f"least {MIN_REPEAT_S:g} s")
                i += 3
                continue
            if tok.lower() == "wait":
                if i + 1 >= len(tokens):
                    raise ValueError("wait needs a number of seconds after it")
                t += _seconds(tokens[i + 1], "wait")
                i += 2
                continue
            if tok.lower().endswith("-hold") and len(tok) > 5:
                if i + 1 >= len(tokens):
                    raise ValueError("a hold needs a number of seconds after it")
                key = parse_key(tok[:-5])
                hold = _seconds(tokens[i + 1], "hold", MAX_HOLD_S)
                events.append((t, key))
                k = 0
                while (rt := t + repeat_delay + k * repeat_rate) < t + hold:
                    events.append((rt, replace(key, kind="repeat")))
                    k += 1
                events.append((t + hold, replace(key, kind="release")))
                t += hold + tap_gap
                i += 2
                continue
            name, star, count = tok.rpartition("*") if "*" in tok[1:] else ("", "", "")
            if star:
                if not (_cell(count) and 1 <= int(count) <= MAX_TAPS):
                    raise ValueError(f"repeat count must be a whole number from 1 to "
                                     f"{MAX_TAPS}, not '{count[:20]}'")
                n = int(count)
            else:
                name, n = tok, 1
            key = parse_key(name)
            for _ in range(n):
                events.append((t, key))
                events.append((t + tap_gap / 2, replace(key, kind="release")))
                t += tap_gap
            i += 1
        except ValueError as e:
            raise ValueError(f"{where}: {e}") from None
    _check_length(t, events)
    # rounded so that sums like 0.1 + 0.2 print as written; still a pure function of the text
    return [(round(et, 9), k) for et, k in events]


def legacy_events(events: list[tuple[float, Key]]) -> list[tuple[float, Key]]:
    """What a legacy terminal delivers for these events: no releases, repeats as presses."""
    out = []
    for t, e in events:
        if isinstance(e, Mouse):
            out.append((t, e))  # mouse reports are the same on every terminal
        elif e.kind != "release":
            out.append((t, replace(e, kind="press")))
    return out
