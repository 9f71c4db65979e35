"""Game controls: the key map (and its config file), aim acceleration, power charging.

Everything here is a pure function of the (Key, t) stream it is fed; no clock is read, so
headless key scripts (`keys.parse_script`) replay bit for bit.

- `KeyMap`: action <-> keys. `action(key)` does not look at `key.kind`: the app sends the
  shoot key's events (all kinds) to `PowerCharge`, aim keys' press/repeat events to
  `AimControl`, and ignores releases of everything else (kitty terminals send them).
  A key with shift that has no binding of its own falls back to the key without shift
  ("?" typed as shift+"/" on a kitty terminal, "A" with caps lock on).
- `load_keymap(path=None)`: defaults, overridden by `$XDG_CONFIG_HOME/termpool/keys.conf`
  (else ~/.config/termpool/keys.conf) if it exists: `action = key, key` lines, `#` comments.
  Errors are `ValueError("keys.conf line 3: ...")`.
- `AimControl.step(key, t)`: degrees to turn (counter-clockwise positive) for one event.
- `PowerCharge(mode)`: hold the shoot key to charge, release to shoot; modes "release" (kitty
  protocol: real release events), "repeat" (legacy terminals: the hold is inferred from the
  auto-repeat stream), "classic" (tap to start an oscillating meter, tap again to strike).
  The app calls `key(key, t)` for shoot-key events and `poll(t)` every frame; either returns
  the power in (0, 1] when the shot fires.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import ClassVar

from termpool.files import MAX_CONFIG_BYTES, FileError, read_text
from termpool.ui.keys import Key, parse_key

# action -> (help text); the order is the order of the help screen
ACTIONS: dict[str, str] = {
    "aim_ccw": "aim ↺ counter-clockwise (hold: faster)",
    "aim_cw": "aim ↻ clockwise (hold: faster)",
    "aim_fine_ccw": "fine aim ↺ (hold: faster)",
    "aim_fine_cw": "fine aim ↻ (hold: faster)",
    "shoot": "shoot (hold to charge)",
    "spin_up": "cue tip up (follow)",
    "spin_down": "cue tip down (draw)",
    "spin_left": "cue tip left (left english)",
    "spin_right": "cue tip right (right english)",
    "spin_reset": "cue tip to the center",
    "next_ball": "aim at the next ball you may hit, going ↻",
    "previous_ball": "aim at the next ball you may hit, going ↺",
    "place": "ball in hand: place the cue ball (arrows move it)",
    "confirm": "confirm",
    "cancel": "cancel a charge; ball in hand: leave it where it lies",
    "help": "this help",
    "pause": "pause",
    "quit": "quit",
    "fast_forward": "fast forward the shot",
    "aim_aid": "aim aid: every path, then the ghost ball only, then off (cycles)",
    "call_pocket": "next called pocket",
    "push_out": "push out (9-ball)",
    "bell": "bell on/off (a pot or a foul rings it)",
    "undo": "undo the shot (practice)",
    "rerack": "rerack (practice)",
}


# Actions a game cannot do without: it could not be played, answered or left.
REQUIRED = ("shoot", "confirm", "quit")
# Keys the terminal or the game keeps for itself; a binding could never fire.
RESERVED = {"c": "Ctrl-C interrupts the game", "z": "Ctrl-Z suspends the game",
            "\\": "Ctrl-\\ quits the game"}


def _check_bindable(key: Key, spec: str) -> None:
    if key.ctrl and key.name in RESERVED:  # with any other modifier it is the same byte
        raise ValueError(f"key '{spec}' cannot be bound: {RESERVED[key.name]}")


def _conf_name(path: Path) -> str:
    return path.name or str(path)


class KeyMap:
    """Which action each key triggers, from the defaults and optional overrides.

    `bindings` maps an action to its key specs ("shift+left", "q", "?") and replaces that
    action's default keys; an empty list unbinds it. A key bound explicitly is taken away
    from any action that had it by default; a key bound explicitly to two actions is an error.
    """

    DEFAULTS: ClassVar[dict[str, list[str]]] = {
        "aim_ccw": ["left"], "aim_cw": ["right"],
        "aim_fine_ccw": ["up", "shift+left"], "aim_fine_cw": ["down", "shift+right"],
        "next_ball": ["tab"], "previous_ball": ["shift+tab"],
        "shoot": ["space"],
        "spin_up": ["w"], "spin_down": ["s"], "spin_left": ["a"], "spin_right": ["d"],
        "spin_reset": ["x"], "place": ["b"], "confirm": ["enter"], "cancel": ["esc"],
        "help": ["h", "?"], "pause": ["p"], "quit": ["q"], "fast_forward": ["f"],
        "aim_aid": ["g"], "call_pocket": ["c"], "push_out": ["o"], "bell": ["n"],
        "undo": ["u"], "rerack": ["r"],
    }

    def __init__(self, bindings: Mapping[str, Sequence[str]] | None = None) -> None:
        bindings = dict(bindings or {})
        for action in bindings:
            if action not in ACTIONS:
                raise ValueError(f"unknown action '{action}'")
        explicit: dict[tuple, str] = {}
        for action, specs in bindings.items():
            for spec in specs:
                key = parse_key(spec)
                _check_bindable(key, spec)
                ident = _ident(key)
                other = explicit.get(ident)
                if other is not None and other != action:
                    raise ValueError(f"key '{spec}' is bound to both {other} and {action}")
                explicit[ident] = action
        self._keys: dict[str, list[Key]] = {}
        for action in ACTIONS:
            if action in bindings:
                keys = [parse_key(s) for s in bindings[action]]
            else:
                keys = [k for k in map(parse_key, self.DEFAULTS[action])
                        if _ident(k) not in explicit]
            self._keys[action] = list(dict.fromkeys(keys))  # drop repeats, keep the order
        missing = [a for a in REQUIRED if not self._keys[a]]
        if missing:
            raise ValueError(f"no key left for {' and '.join(missing)}: a game cannot be played "
                             "or left without shoot, confirm and quit")
        self._index = {_ident(k): a for a, keys in self._keys.items() for k in keys}

    def action(self, key: Key) -> str | None:
        """The action bound to this key (any kind), or None."""
        ident = _ident(key)
        found = self._index.get(ident)
        if found is None and key.shift:
            found = self._index.get((key.name, False, key.ctrl, key.alt))
        return found

    def keys_for(self, action: str) -> list[str]:
        """The key specs bound to an action, e.g. ["up", "shift+left"]."""
        if action not in ACTIONS:
            raise ValueError(f"unknown action '{action}'")
        return [k.spec for k in self._keys[action]]

    def help_lines(self) -> list[str]:
        """One line per bound action: its keys, then what it does."""
        rows = [(", ".join(self.keys_for(a)), text) for a, text in ACTIONS.items()
                if self._keys[a]]
        width = max(len(keys) for keys, _ in rows)
        return [f"{keys:<{width}}  {text}" for keys, text in rows]


def _ident(key: Key) -> tuple[str, bool, bool, bool]:
    return (key.name, key.shift, key.ctrl, key.alt)


def config_path(env: Mapping[str, str] | None = None) -> Path:
    """Where the key config lives: $XDG_CONFIG_HOME/termpool/keys.conf or ~/.config/..."""
    env = os.environ if env is None else env
    base = env.get("XDG_CONFIG_HOME") or str(Path(env.get("HOME", "~")).expanduser() / ".config")
    return Path(base) / "termpool" / "keys.conf"


def parse_keymap(text: str, name: str = "keys.conf") -> KeyMap:
    """A keys.conf text -> KeyMap. Bad lines raise ValueError(f"{name} line N: ...")."""
    bindings: dict[str, list[str]] = {}
    seen: dict[str, int] = {}  # action -> line
    owner: dict[tuple, tuple[str, int]] = {}  # key -> (action, line)
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        where = f"{name} line {n}"
        action, eq, value = line.partition("=")
        action = action.strip()
        if not eq or not action:
            raise ValueError(f"{where}: expected 'action = key, key', got '{line}'")
        if action not in ACTIONS:
            raise ValueError(f"{where}: unknown action '{action}' (known: "
                             f"{', '.join(ACTIONS)})")
        if action in seen:
            raise ValueError(f"{where}: {action} is already set on line {seen[action]}")
        seen[action] = n
        specs = [s.strip() for s in value.split(",")] if value.strip() else []
        for spec in specs:
            try:
                key = parse_key(spec)
                _check_bindable(key, spec)
            except ValueError as e:
                raise ValueError(f"{where}: {e}") from None
            prev = owner.get(_ident(key))
            if prev is not None and prev[0] != action:
                raise ValueError(f"{where}: key '{spec}' is already bound to {prev[0]} "
                                 f"on line {prev[1]}")
            owner[_ident(key)] = (action, n)
        bindings[action] = specs
    try:
        return KeyMap(bindings)
    except ValueError as e:
        raise ValueError(f"{name}: {e}") from None


def load_keymap(path: str | os.PathLike[str] | None = None,
                env: Mapping[str, str] | None = None,
                warn: Callable[[str], None] | None = None) -> KeyMap:
    """The key map: defaults, overridden by the config file.

    Without `path`, the file at `config_path(env)` is read if it exists (missing: defaults).
    One that cannot be read (e.g. a config directory that cannot be entered) or has a
    mistake gives the defaults, and `warn` is told why: a slip in a file written long ago
    should not keep the game from starting, as the settings file's do not. A `path` given
    explicitly must be readable and right. Errors are one-line ValueErrors naming the file
    (and line).
    """
    explicit = path is not None
    p = Path(path) if explicit else config_path(env)
    try:
        text = read_text(p, MAX_CONFIG_BYTES, "key map")
        return parse_keymap(text, _conf_name(p))
    except (FileError, ValueError) as e:
        if explicit or (isinstance(e, FileError) and not e.unreadable):
            raise ValueError(str(e)) from None
        if not (isinstance(e, FileError) and e.missing) and warn is not None:
            warn(f"{e}; playing with the default keys")
        return KeyMap()


# ----------------------------------------------------------------------------- aiming

_AIM = {"aim_ccw": (1.0, False), "aim_cw": (-1.0, False),
        "aim_fine_ccw": (1.0, True), "aim_fine_cw": (-1.0, True)}


class HoldRamp:
    """How far one event of a held key moves something (an aim, a ball in hand).

    A tap (or the first event of a hold) moves `tap`. While held, each event moves speed * dt,
    dt being the time since the previous event (at most DT_MAX), and the speed ramps from
    `speed0` to `speed_max` over `ramp` seconds of holding (counted from the first repeat, or
    with `from_press` from the press): the rate depends on how long the key is held, not on the
    terminal's repeat rate. A repeat is a "repeat" event (kitty) or, on legacy terminals where
    every event is a press, the same key again within HOLD_GAP seconds.
    """

    HOLD_GAP = 0.12
    DT_MAX = 0.05

    def __init__(self, tap: float, speed0: float, speed_max: float, ramp: float,
                 from_press: bool = False) -> None:
        self.tap, self.speed0, self.speed_max, self.ramp = tap, speed0, speed_max, ramp
        self.from_press = from_press
        self.reset()

    def reset(self) -> None:
        """Forget the current hold."""
        self._what: str | None = None
        self._last = 0.0
        self._start: float | None = None

    def release(self, what: str) -> None:
        """`what` was let go: its next press is a tap."""
        if what == self._what:
            self.reset()

    def step(self, what: str, kind: str, t: float) -> float:
        """The distance for one press or repeat of `what` at time t."""
        held = what == self._what and (kind == "repeat" or 0.0 <= t - self._last <= self.HOLD_GAP)
        if not held:
            self._what, self._last = what, t
            self._start = t if self.from_press else None
            return self.tap
        if self._start is None:
            self._start = t
        dt = min(max(t - self._last, 0.0), self.DT_MAX)
        ramp = min(1.0, (t - self._start) / self.ramp)
        self._last = t
        return (self.speed0 + (self.speed_max - self.speed0) * ramp) * dt


class AimControl:
    """Aim steps that speed up while an aim key is held (`HoldRamp`s in degrees).

    A tap turns TAP degrees and, held, the turn speeds up from SPEED0 to SPEED_MAX deg/s over
    RAMP seconds (a sweep across the table). A fine key's tap turns FINE degrees and, held,
    from FINE_SPEED0 to FINE_SPEED_MAX deg/s over FINE_RAMP seconds: the few degrees between
    a rough aim and a pot take a second of holding, not thirty taps, and stay slower than the
    coarse keys' taps until the last half second.
    """

    TAP = 0.5
    FINE = 0.1
    SPEED0 = 15.0
    SPEED_MAX = 120.0
    RAMP = 1.2
    FINE_SPEED0 = 2.0
    FINE_SPEED_MAX = 12.0
    FINE_RAMP = 1.5
    HOLD_GAP = HoldRamp.HOLD_GAP
    DT_MAX = HoldRamp.DT_MAX

    def __init__(self, keymap: KeyMap | None = None) -> None:
        self.keymap = keymap if keymap is not None else KeyMap()
        self._ramp = HoldRamp(self.TAP, self.SPEED0, self.SPEED_MAX, self.RAMP)
        self._fine = HoldRamp(self.FINE, self.FINE_SPEED0, self.FINE_SPEED_MAX, self.FINE_RAMP)

    def reset(self) -> None:
        """Forget the current hold (e.g. after a shot)."""
        self._ramp.reset()
        self._fine.reset()

    def step(self, key: Key, t: float) -> float:
        """Degrees to turn the aim for this event (0 for non-aim keys and releases)."""
        action = self.keymap.action(key)
        if action not in _AIM:
            return 0.0
        if key.kind == "release":
            self._ramp.release(action)
            self._fine.release(action)
            return 0.0
        sign, fine = _AIM[action]
        held, other = (self._fine, self._ramp) if fine else (self._ramp, self._fine)
        other.reset()  # the other kind of key ends its hold
        return sign * held.step(action, key.kind, t)


# ----------------------------------------------------------------------------- power

POWER_MODES = ("release", "repeat", "classic")


class PowerCharge:
    """Hold the shoot key to charge, release to shoot (see the module docstring for modes).

    Charging ramps the level linearly to 1 over `full_time` and holds it there; the classic
    meter goes up and down (period 2 * full_time). A fired shot has power in [MIN_POWER, 1].

    Repeat mode: after the press, a legacy terminal auto-repeats after an initial delay
    (0.2-0.7 s), then every 20-50 ms. A hold can only be told from a tap at its first repeat,
    so the charge starts there: however long the terminal's delay, the softest hold is a soft
    shot. The repeat interval is the median of the gaps seen so far (kept from hold to hold:
    it is the terminal's, and `observe` learns it from repeats that go on after a strike too);
    the release is inferred when no repeat came for GAP_INTERVALS intervals (bounded to
    GAP_MIN..GAP_MAX s) and placed one interval after the last repeat, so the power does not
    depend on when `poll` is called; the meter holds there meanwhile, showing what strikes.
    A press with no repeat within INITIAL_DELAY_MAX s was a tap (or the terminal does not
    repeat): that shot falls back to the classic meter, rising from 0 at that moment (press
    again to strike), and `label` says so. Until then `waiting` is true and the level 0.

    Set power (any mode): `preset(level)` (the digit keys) makes the next press strike at
    once at that level, until `preset(None)`.
    """

    MIN_POWER = 0.02
    INITIAL_DELAY_MAX = 0.75
    # The release is inferred after GAP_INTERVALS repeat intervals of silence (within
    # GAP_MIN..GAP_MAX s): 67 ms at 30 repeats a second, 80 ms at 25, so the strike follows
    # the last repeat within 0.1 s even polled at 60 frames a second; the price is that a
    # repeat late by a whole interval reads as a release.
    GAP_MIN = 0.05
    GAP_MAX = 0.3
    GAP_INTERVALS = 2.0
    DEFAULT_INTERVAL = 0.033
    INTERVAL_SAMPLES = 16

    def __init__(self, mode: str, full_time: float = 1.2, key_label: str = "space") -> None:
        if mode not in POWER_MODES:
            raise ValueError(f"power mode must be one of {', '.join(POWER_MODES)}, not '{mode}'")
        if not full_time > 0:
            raise ValueError(f"full_time must be positive, not {full_time}")
        self.mode = mode
        self.full_time = float(full_time)
        self.key_label = key_label
        self.preset_level: float | None = None
        self._gaps: list[float] = []  # repeat intervals seen, from hold to hold
        self._tail: float | None = None  # the last repeat of a hold that has struck
        self._kinds = False  # repeat mode: the terminal has sent a repeat or release event
        self.cancel()

    # -- state

    def cancel(self) -> None:
        """Drop any charge or meter in progress."""
        self._phase = "idle"  # "idle" | "charge" (ramp) | "meter" (ping-pong)
        self._t0 = 0.0
        self._last = 0.0
        self._repeats = 0
        self.fallback = False  # repeat mode: this shot fell back to the classic meter

    def preset(self, level: float | None) -> None:
        """Set power: the next press strikes at once at `level` (0..1); None: hold again."""
        self.cancel()
        self.preset_level = None if level is None else min(1.0, max(self.MIN_POWER, level))

    @property
    def way(self) -> str:
        """How the key gives power without a level set: "hold" it, or the "meter"."""
        return "meter" if self.mode == "classic" else "hold"

    @property
    def active(self) -> bool:
        """Whether a charge or a meter is running."""
        return self._phase != "idle"

    @property
    def mode_name(self) -> str:
        """How power is given now, in words: "set 30%", "hold (key releases)", "hold (key
        repeat)", "meter"."""
        if self.preset_level is not None:
            return f"set {round(100 * self.preset_level)}%"
        return {"release": "hold (key releases)", "repeat": "hold (key repeat)",
                "classic": "meter"}[self.mode]

    @property
    def label(self) -> str:
        """What to show on screen."""
        k = self.key_label
        if self.preset_level is not None:
            return f"{k} strikes at {round(100 * self.preset_level)}%"
        if self._phase == "meter":
            if self.fallback:
                return f"a tap: the meter runs, {k} again to strike"
            return f"{k} to strike"
        if self.mode == "classic":
            return f"{k} to start, {k} to strike"
        if self.waiting:
            return f"keep {k} down to charge, or let go for a meter"
        if self._phase == "charge":
            return f"release {k} to shoot"
        return f"hold {k}, release to shoot"

    @property
    def waiting(self) -> bool:
        """Repeat mode: pressed, and no repeat yet to tell a hold from a tap (no power yet)."""
        return (self.mode == "repeat" and self._phase == "charge" and self._repeats == 0
                and not self._kinds)

    def level(self, t: float) -> float:
        """The meter's level in [0, 1] at time t (0 when idle)."""
        if self._phase == "idle":
            return 0.0
        if self.waiting:
            return 0.0  # the charge starts at the first repeat
        if self._phase == "charge":
            hold = self.hold_at()
            if hold is not None:
                t = min(t, hold)
            return min(1.0, max(0.0, t - self._t0) / self.full_time)
        x = max(0.0, t - self._t0) / self.full_time
        x %= 2.0
        return x if x <= 1.0 else 2.0 - x

    # -- events

    def key(self, key: Key, t: float) -> float | None:
        """Feed one shoot-key event; returns the power if a shot fires."""
        fired = self._advance(t)
        now = self._event(key, t)
        return fired if fired is not None else now

    def poll(self, t: float) -> float | None:
        """Call every frame: fires (returns the power) when repeat mode infers a release."""
        return self._advance(t)

    def _fire(self, t: float) -> float:
        power = min(1.0, max(self.MIN_POWER, self.level(t)))
        self._tail = self._last if self.mode == "repeat" and self._repeats else None
        self.cancel()
        return power

    def observe(self, key: Key, t: float) -> None:
        """A shoot-key event after the strike (the balls are running): repeats that go on
        are the key still held, and their spacing is the terminal's repeat interval (a
        terminal that repeats more slowly than the release gap assumed is learnt this way)."""
        if self._tail is None or key.kind == "release":
            self._tail = None
            return
        if 0.0 < t - self._tail <= self.GAP_MAX:
            self._gaps.append(t - self._tail)
            del self._gaps[:-self.INTERVAL_SAMPLES]
            self._tail = t
        else:
            self._tail = None

    def hold_at(self) -> float | None:
        """Repeat mode on a terminal that tells no key kinds, charging from its repeats (its
        release will be inferred): when the meter stops, one interval after the last repeat.
        The key may be up already, and an inferred release strikes at that level, so the
        meter holds there and shows what strikes (None: no such time)."""
        if self.mode != "repeat" or self._phase != "charge" or not self._repeats \
                or self._kinds:
            return None
        return self._inferred()

    def _inferred(self) -> float:
        """When an inferred release is placed: one interval after the last repeat."""
        return self._last + self._interval()

    def release_due(self) -> float | None:
        """Repeat mode: the time at which silence will mean a release (None: no such time),
        so a driver can wake then rather than at its next frame."""
        if self.mode != "repeat" or self._phase != "charge" or self._repeats == 0:
            return None
        return self._last + self._release_gap() + 1e-6

    def _start(self, phase: str, t: float) -> None:
        self.cancel()
        self._phase, self._t0, self._last = phase, t, t

    def _interval(self) -> float:
        if not self._gaps:
            return self.DEFAULT_INTERVAL
        recent = sorted(self._gaps[-self.INTERVAL_SAMPLES:])
        mid = len(recent) // 2
        return recent[mid] if len(recent) % 2 else 0.5 * (recent[mid - 1] + recent[mid])

    def _release_gap(self) -> float:
        return min(self.GAP_MAX, max(self.GAP_MIN, self.GAP_INTERVALS * self._interval()))

    def _advance(self, t: float) -> float | None:
        """Repeat mode: what the silence up to time t tells (an inferred release, or a tap)."""
        if self.mode != "repeat" or self._phase != "charge":
            return None
        if self._repeats == 0:
            if t - self._t0 > self.INITIAL_DELAY_MAX:
                # The meter starts from nothing when the tap is known, not from the press:
                # it rises from 0% as a soft shot is wanted as often as a hard one.
                self._phase, self.fallback = "meter", True
                self._t0 += self.INITIAL_DELAY_MAX
            return None
        if t - self._last > self._release_gap():
            return self._fire(self._inferred())
        return None

    def _event(self, key: Key, t: float) -> float | None:
        if self.preset_level is not None:
            return self.preset_level if key.kind == "press" else None
        if self.mode == "release":
            if key.kind == "press":
                self._start("charge", t)  # a press while charging: the release was lost
            elif key.kind == "release" and self._phase == "charge":
                return self._fire(t)
            return None
        if self.mode == "classic":
            if key.kind != "press":
                return None
            if self._phase == "idle":
                self._start("meter", t)
                return None
            return self._fire(t)
        # repeat mode: every press or repeat is part of the stream; a real release also counts
        if key.kind != "press":
            self._kinds = True  # this terminal tells events apart: charge from the press
        if key.kind == "release":
            return self._fire(t) if self._phase == "charge" else None
        if self._phase == "idle":
            self._start("charge", t)
        elif self._phase == "meter":
            return self._fire(t)
        else:
            if self._repeats > 0:
                self._gaps.append(t - self._last)
                del self._gaps[:-self.INTERVAL_SAMPLES]
            elif not self._kinds:
                self._t0 = t  # the first repeat: a hold, and the charge starts now
            self._repeats += 1
            self._last = t
        return None
