"""Watching a saved match (`termpool replay FILE --watch`, and W at the end of a game).

`Watch` is an app like `ui.app.App` (keys and clock ticks in, screen cells out), so it runs on
a terminal (`ui.term.run`), headless from a key script (`ui.headless.play`) and inside the game.
Each shot is played again from its record: the scene before it, the stick on the shot's line
for a moment, the balls in real time frame by frame, then the referee's verdict. The frames are
the engine's own steps, taken exactly as the game took them live (`game.turn.advance` at the
game's frame rate), and drawn by the same table view, so a watched shot looks as it did.

Keys: Space pauses and resumes, ← and → go back and forward one shot, F plays at ×4 (again:
×1), H shows the keys and the rules of the game watched, Q (or Esc) quits.
"""

from __future__ import annotations

import os
import sys
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from termpool.files import FileError
from termpool.game.record import (
    ReplayError,
    check_records,
    first_difference,
    read_replay,
    results,
    run_to_rest,
    start_engine,
    still_moving,
)
from termpool.game.turn import advance
from termpool.physics.engine import POCKETED
from termpool.physics.params import BALL_RADIUS
from termpool.physics.results import DT
from termpool.rules import words
from termpool.rules.codes import Choice
from termpool.rules.common import GROUPS, MODE_BALLS, MODES
from termpool.rules.referee import verdict
from termpool.rules.words import MODE_NAMES, THEMES, group_label
from termpool.scene import Scene
from termpool.text import shown
from termpool.ui import overlay as ov
from termpool.ui import term
from termpool.ui.headless import play, screen_size
from termpool.ui.help import help_pages, page_key
from termpool.ui.keys import parse_script, read_script
from termpool.ui.output import resolve_depth
from termpool.ui.panel import (
    PanelInfo,
    PlayerLine,
    draw_box,
    draw_panel,
    message_cells,
    too_small_lines,
)
from termpool.ui.shots import MAX_SHOT_FRAMES, Clock, speed_to_power
from termpool.ui.table_view import Geometry

AIM_S = 1.0  # the stick is shown on the shot's line this long before the strike ...
VERDICT_S = 2.5  # ... and the verdict this long after the balls stop, before the next shot
CACHE_SHOTS = 8  # shots whose frames are kept (stepping back and forth costs nothing)
QUIT_KEYS = ("q", "esc")
PAUSE_KEYS = ("space", "p")
HELP_KEYS = ("h", "?")
WATCH_KEYS = [("Space", "pause, and play on"), ("← →", "back or forward one shot"),
              ("F", "×4 (again: ×1)"), ("H", "this help"), ("Q, Esc", "stop watching")]


@dataclass
class Played:
    """One shot played again: its frames as the game showed them, the table at rest, and
    where it strays from its record (None when it is identical)."""

    frames: list  # (pos, state) of the scene's balls after each frame of 1/60 s
    final: tuple  # (pos, state) at rest
    differs: str | None


def play_shot(scene: Scene, dt: float, rec: dict) -> Played:
    """Simulate one recorded shot frame by frame as the game does (at most MAX_SHOT_FRAMES;
    a longer shot runs to rest at once, as it does live) and compare it with its record."""
    engine = start_engine(scene)
    frames, owed = [], 0.0
    steps = rec["steps"]  # the work budget of a replay (a frame may take a few steps more)
    try:
        while not engine.at_rest()[0] and len(frames) < MAX_SHOT_FRAMES \
                and engine.steps < steps:
            owed = advance(engine, dt, owed + DT)
            frames.append((engine.pos[0].copy(), engine.state[0].copy()))
        rested = run_to_rest(engine, dt, max_steps=steps)
    except RuntimeError as e:  # the engine's work limit
        return Played(frames, (engine.pos[0].copy(), engine.state[0].copy()), str(e))
    if not rested:
        return Played(frames, (engine.pos[0].copy(), engine.state[0].copy()),
                      still_moving(steps))
    fresh = results(scene, engine, dt)
    differs = None
    for key in ("time", "steps", "events", "final"):
        differs = first_difference(rec[key], fresh[key], key)
        if differs:
            break
    return Played(frames, (engine.pos[0].copy(), engine.state[0].copy()), differs)


def _names(data: dict) -> tuple[str, str]:
    """The players' names as the screen may show them (control characters escaped)."""
    names = data.get("match", {}).get("players", ["", ""])
    return tuple(shown(n) if n.strip() else f"Player {k + 1}" for k, n in enumerate(names))


def _choices(data: dict) -> dict[int, list[dict]]:
    """The options answered, by the number of the shot they followed (entries that are not
    well formed are left out: they only add words to a verdict)."""
    out: dict[int, list[dict]] = {}
    raw = data.get("choices", [])
    for c in raw if isinstance(raw, list) else []:
        if (isinstance(c, dict) and type(c.get("after_shot")) is int
                and c.get("player") in (0, 1) and c.get("choice") in tuple(Choice)):
            out.setdefault(c["after_shot"], []).append(c)
    return out


class Watch:
    """A saved match played again on screen. `data` is a parsed replay (`read_replay`); its
    records are checked here (ReplayError, one line naming the shot and key)."""

    def __init__(self, data: dict, colors: str = "auto", env=None) -> None:
        self.scenes = check_records(data)
        if not self.scenes:
            raise ReplayError("no shots to watch")
        match = data.get("match", {})
        self.theme = match.get("theme", "standard")
        if not isinstance(self.theme, str) or self.theme not in THEMES:
            raise ReplayError(f"match.theme: must be one of {', '.join(THEMES)}")
        race = match.get("frames", 1)
        self.race = race if type(race) is int and race > 1 else None
        self.shots = data["shots"]
        self.players = _names(data)
        self.choices = _choices(data)
        self.scores = self._scores()
        self.depth = resolve_depth(colors, env)
        self.done = False
        self.dirty = True
        self.bells = 0
        self.overlay: str | None = None  # "help"
        self.help_page, self.help_count = 0, 1
        self.eight_break = match.get("eight_break")
        self.paused = False
        self.fast = False
        self._played: OrderedDict[int, Played] = OrderedDict()
        self.geometry = Geometry()  # the layout and table view for the screen's size
        self.clock = Clock()  # the wall-clock time owed to the shot on show
        # Drawn and named as the game was (9-ball keeps the standard colours).
        self.theme = words.shown_theme(self.theme, self.ids_rows(0)[0])
        self.go_to(0)

    @classmethod
    def from_file(cls, path: str, colors: str = "auto", env=None) -> Watch:
        return cls(read_replay(path), colors, env)

    def _scores(self) -> list[tuple[int, int]]:
        """Frames won by each player before each shot (and after the last)."""
        won = [0, 0]
        out = []
        for rec in self.shots:
            out.append(tuple(won))
            winner = (rec.get("outcome") or {}).get("winner")
            if winner in (0, 1):
                won[winner] += 1
        out.append(tuple(won))
        return out

    # ------------------------------------------------------------------------ the timeline
    @property
    def n(self) -> int:
        return len(self.shots)

    def played(self, i: int) -> Played:
        """Shot i played again (kept for a few shots either way)."""
        got = self._played.get(i)
        if got is None:
            scene, dt = self.scenes[i]
            got = self._played[i] = play_shot(scene, dt, self.shots[i])
            while len(self._played) > CACHE_SHOTS:
                self._played.popitem(last=False)
        self._played.move_to_end(i)
        return got

    def go_to(self, i: int) -> None:
        """The start of shot i (0-based): the table before it, the stick on its line."""
        self.i = min(max(i, 0), self.n - 1)
        self.phase = "aim"
        self.frames = self.played(self.i).frames
        self.shown = 0
        self.clock = Clock()
        self.dirty = True

    def _next_phase(self) -> None:
        self.clock = Clock(self.clock.last)
        if self.phase == "aim":
            self.phase = "run"
        elif self.phase == "run":
            self.phase = "rest"
        elif self.phase == "rest":
            if self.i + 1 < self.n:
                self.go_to(self.i + 1)
                return
            self.phase = "end"
        self.dirty = True

    @property
    def shot_clock(self) -> float:
        """Simulated seconds of the shot on show (0 before the strike)."""
        return self.shown * DT

    # --------------------------------------------------------------------------- the clock
    def wake_in(self, t: float) -> float | None:
        if self.overlay is not None or self.paused or self.phase == "end":
            return None
        return 0.0

    def tick(self, t: float) -> None:
        if self.overlay is not None or self.paused or self.phase == "end":
            self.clock = self.clock.stopped()  # time stands still
            return
        started = self.clock.started()
        self.clock = self.clock.at(t, self.fast)
        if not started:
            return
        if self.phase == "run":  # frames as the game shows them (ui.shots)
            n, self.clock = self.clock.frames()
            if n:
                self.shown = min(self.shown + n, len(self.frames))
                self.dirty = True
            if self.shown >= len(self.frames):
                self._next_phase()
        elif self.clock.owed >= (AIM_S if self.phase == "aim" else VERDICT_S):
            self._next_phase()

    # ---------------------------------------------------------------------------- keys
    def key(self, key, t: float) -> None:
        if key.kind == "release":
            return
        name = key.name
        if self.overlay == "help":
            self.help_page, close = page_key(name, self.help_page, self.help_count)
            if close:
                self.overlay = None
            self.dirty = True
            return
        if name in QUIT_KEYS:
            self.done = True
        elif name in PAUSE_KEYS and key.kind == "press":
            self.paused = not self.paused
            self.clock = self.clock.stopped()
        elif name == "left":
            self.go_to(self.i - 1 if self.phase != "end" else self.i)
        elif name == "right":
            if self.i + 1 < self.n:
                self.go_to(self.i + 1)
            else:
                self.shown, self.phase = len(self.frames), "end"
        elif name == "f" and key.kind == "press":
            self.fast = not self.fast
        elif name in HELP_KEYS and key.kind == "press":
            self.overlay, self.help_page = "help", 0
        self.dirty = True

    def mouse(self, ev, t: float) -> None:
        pass

    # -------------------------------------------------------------------------- the screen
    def ids_rows(self, i: int) -> tuple[list[str], np.ndarray]:
        """The ball ids drawn for shot i (the game's: the cue ball and the mode's set) and the
        rows of them that the shot's scene holds."""
        scene = self.scenes[i][0]
        mode = (scene.game or {}).get("mode")
        ids = ["cue", *MODE_BALLS[mode]] if mode in MODES else list(scene.ids)
        if not set(scene.ids) <= set(ids):
            ids = list(scene.ids)
        return ids, np.array([ids.index(b) for b in scene.ids], dtype=int)

    def positions(self):
        """The ids, positions, states and radii on show (the game's arrays: a ball not in
        the shot's scene is pocketed)."""
        scene = self.scenes[self.i][0]
        ids, rows = self.ids_rows(self.i)
        pos = np.zeros((len(ids), 2))
        state = np.full(len(ids), POCKETED, dtype=np.int8)
        radius = np.full(len(ids), BALL_RADIUS)
        radius[rows] = scene.radius
        if self.phase in ("rest", "end"):
            p, st = self.played(self.i).final
        elif self.phase == "run" and self.shown > 0:
            p, st = self.frames[self.shown - 1]
        else:
            p, st = scene.pos, np.zeros(len(rows), dtype=np.int8)
        pos[rows] = p
        state[rows] = st
        return ids, pos, state, radius

    def cells(self, cols: int, rows: int):
        self.dirty = False
        mono = self.depth == "mono"
        lay, view = self.geometry.get(cols, rows, self.scenes[self.i][0].table, self.theme)
        if lay is None:
            out = message_cells(cols, rows, too_small_lines(cols, rows), mono)
        else:
            out = self._table_cells(lay, view, mono)
            draw_panel(out, lay, self.panel_info(), mono)
        if self.overlay == "help":
            pages = self._help_pages(cols, rows)
            self.help_count = len(pages)
            self.help_page = min(self.help_page, len(pages) - 1)
            title, lines = pages[self.help_page]
            draw_box(out, lines, title, wrap=False)
        return out

    def _table_cells(self, lay, view, mono: bool):
        """The table as the game draws it: the balls, their numbers, and before the strike
        the stick on the shot's line and the pocket called for the 8."""
        ids, pos, state, radius = self.positions()
        scene = self.scenes[self.i][0]
        shot = self.shots[self.i]["shot"]
        aiming = self.phase == "aim" and "cue" in scene.ids
        called = None
        if aiming and shot.get("called"):
            names = list(scene.table.hole_names)
            if shot["called"][1] in names:
                called = names.index(shot["called"][1])
        holes = scene.table.hole_c.reshape(-1, 2)

        def mark(chars) -> None:
            if called is not None:
                ov.mono_called_pocket(chars, lay, holes[called])

        def paint(cv) -> None:
            if called is not None:
                ov.draw_called_pocket(cv, lay, holes[called], scene.table.hole_r[called])
            if aiming:
                c = ids.index("cue")
                ov.draw_cue_stick(cv, lay, pos[c], radius[c], float(shot["angle"]))

        return view.cells(ids, pos, state, radius, mono, paint=paint, mark=mark)

    def voice(self) -> words.Voice:
        """How words name the players (as the screen may show them), pockets and groups."""
        return words.voice(self.players, self.theme)

    def mode(self) -> str | None:
        return (self.scenes[self.i][0].game or {}).get("mode")

    def verdict(self, i: int) -> list[tuple[str, str]]:
        """The referee's verdict on shot i as the game said it, and any option answered."""
        lines = []
        out = self._verdict(i)
        if out is not None:
            lines.append(words.verdict(out, self.voice(), self.shots[i]["player"]))
        for c in self.choices.get(i + 1, []):
            lines.append((words.chose(self.players[c["player"]], Choice(c["choice"])), "dim"))
        return lines

    def _verdict(self, i: int):
        """The referee's verdict on shot i: its recorded events judged again (the verdict
        the game gave, for a true record); None without a game block or with events that
        are not a shot's."""
        scene, rec = self.scenes[i][0], self.shots[i]
        if scene.game is None:
            return None
        try:
            return verdict(scene.game, scene.ids, rec["events"])
        except (KeyError, IndexError, TypeError, ValueError):
            return None

    def describe(self, i: int) -> str:
        """The shot in words: its power, the cue tip, the call, a push-out."""
        shot = self.shots[i]["shot"]
        parts = [f"power {round(100 * speed_to_power(shot['speed']))}%"]
        if shot["side"] or shot["top"]:
            parts.append(words.tip_words(shot['side'], shot['top']))
        if shot.get("called"):
            ball, pocket = shot["called"]
            parts.append(shown(words.calling(self.voice(), ball, pocket)))
        if shot.get("push_out"):
            parts.append("push-out")
        return " · ".join(parts)

    def ending(self) -> str:
        """What the end of the record is: the match won (frames in a race), or where the
        record stops."""
        won = self.scores[-1]
        need = self.race or 1
        for p in (0, 1):
            if won[p] >= need:
                return words.match_won(self.voice(), p, won if self.race else None)
        return "the record stops here"

    def status(self) -> list[tuple[str, str]]:
        rec = self.shots[self.i]
        who = self.players[rec["player"]] if rec["player"] in (0, 1) else "?"
        head = f"shot {self.i + 1} of {self.n} · {who}"
        if self.race is not None:
            head += f" · frame {rec['frame']}"
        if (self.scenes[self.i][0].game or {}).get("break"):
            head += " · the break"
        if self.phase == "end":
            head += f" · the end: {self.ending()}"
        lines = [(head, "turn")]
        if self.phase in ("rest", "end"):
            lines += self.verdict(self.i)
        else:
            lines.append((self.describe(self.i), "dim"))
        differs = self.played(self.i).differs
        if differs:
            lines.append((f"this shot plays differently from its record ({differs})", "foul"))
        if self.paused:
            lines.append(("paused · Space plays on", "dim"))
        elif self.fast:
            lines.append(("×4 · F: ×1", "dim"))
        return lines

    def panel_info(self) -> PanelInfo:
        ids, _pos, state, _r = self.positions()
        game = self.scenes[self.i][0].game or {}
        rec = self.shots[self.i]
        groups = game.get("groups")
        if self.phase in ("rest", "end"):
            groups = (rec.get("outcome") or {}).get("groups", groups)
        if not isinstance(groups, dict):  # a hand-made record's outcome may hold anything
            groups = {}
        scores = self.scores[self.i + (1 if self.phase in ("rest", "end") else 0)]
        players = []
        for p in range(2):
            group = groups.get(str(p))
            group = group if isinstance(group, str) else ""
            balls, down = [], []
            if group in GROUPS:
                mine = [k for k, b in enumerate(ids) if b in GROUPS[group]]
                balls = [k for k in mine if state[k] != POCKETED]
                down = [k for k in mine if state[k] == POCKETED]
            label = group_label(group, self.theme) if group in GROUPS else ""
            fouls = game.get("fouls", {}).get(str(p), 0) if game.get("mode") == "9ball" else 0
            score = f"{scores[p]}/{self.race}" if self.race else None
            players.append(PlayerLine(self.players[p], label, balls, down, score,
                                      p == rec["player"], fouls))
        if game.get("mode") == "practice":
            players = players[:1]
        title = "termpool · watching"
        if self.mode() in MODE_NAMES:
            title += f" {MODE_NAMES[self.mode()]}"
        hint = [("Space " + ("play" if self.paused else "pause"), 0), ("←→ shot", 0),
                ("F " + ("×1" if self.fast else "×4"), 0), ("H help", 1), ("Q quit", 0)]
        return PanelInfo(title, players, self.status(), hint, ids, theme=self.theme)

    def _help_pages(self, cols: int, rows: int) -> list[tuple[str, list[str]]]:
        mode, how = self.mode(), {"theme": self.theme}
        if mode == "9ball":
            how["three_foul"] = bool(self.scenes[self.i][0].game.get("three_foul"))
        elif mode == "8ball" and self.eight_break in ("respot", "rerack"):
            how["eight_break"] = self.eight_break
        return help_pages(WATCH_KEYS, mode, cols, rows, aid=False, **how)


# ------------------------------------------------------------------------------- the command
class WatchError(ValueError):
    """Options or a file `replay --watch` cannot use; the message is one line."""


WATCH_ONLY = ("--headless", "--size", "--keys", "--colors")


def colour_setting(flag: str | None) -> str:
    """The colour depth to watch in, as `play` picks it: --colors, else the settings file's
    (its warnings said, one line each; "auto" detects the terminal, NO_COLOR giving mono)."""
    if flag is not None:
        return flag
    from termpool.text import say
    from termpool.ui.settings import load_settings

    store = load_settings()
    for warning in store.warnings:
        say(f"warning: {warning}")
    return store.saved["colors"]


def run(args) -> int:
    """`termpool replay FILE --watch`: the exit status. Raises WatchError for bad options or
    a bad file (one line, status 2). Headless, plays the --keys script on a virtual screen
    and prints the last screen, like `termpool play --headless`."""
    if not args.headless:
        for flag, val in (("--size", args.size), ("--keys", args.keys)):
            if val is not None:
                raise WatchError(f"{flag}: only with --headless (a terminal has its own size "
                                 "and keys)")
        if args.file == "-":
            raise WatchError("FILE: in a terminal the keys come from stdin, so the replay "
                             "must be a file, not '-'")
    elif not args.keys:
        raise WatchError("--headless needs --keys FILE (a key script; '-' reads stdin)")
    elif args.keys == "-" and args.file == "-":
        raise WatchError("--keys: stdin already holds the replay (FILE is '-')")
    try:
        watch = Watch.from_file(args.file, colour_setting(args.colors))
    except ReplayError as e:
        raise WatchError(str(e)) from None
    if args.headless:
        return _headless(watch, args)
    if not (os.isatty(sys.stdin.fileno()) and os.isatty(sys.stdout.fileno())):
        raise WatchError("watching needs a terminal (stdin and stdout are not a tty); "
                         "without one add --headless --keys FILE")
    return term.run(watch, watch.depth, kitty=False, mouse=False)


def _headless(watch: Watch, args) -> int:
    try:
        cols, rows = screen_size(args.size or "100x32")
    except ValueError as e:
        raise WatchError(str(e)) from None
    try:
        events = parse_script(read_script(args.keys))
    except (FileError, ValueError) as e:
        raise WatchError(f"--keys: {e}") from None
    try:
        with term.stoppable():
            screen = play(watch, events, cols, rows)
    except KeyboardInterrupt:
        return 130
    except term.Stop as e:
        return 128 + e.signum
    sys.stdout.write(screen + "\n")
    return 0
