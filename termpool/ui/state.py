"""The game's state as a value: what the app knows between two events.

`State` is one frozen dataclass: the session (options, keys, files), the match in play, the
shot being set up (`Stroke`), the words on show, and the phase's own part (`part`, one small
dataclass per phase, its `Phase` on the class), with the box open over it (`box`). The
phases' `update` functions (ui.phases) take a state and an event and give the next state;
the view (ui.view) draws one on a screen of any size. Two screens can show one state.

A state is a value except for its handles, each changed only through its own methods: the
match (`game.Match`), the shot rolling (`game.ShotRun`), the keys' clocks (`ui.controls`),
the aid's prediction job (`ui.predict.Job`), a watched replay (`ui.watch.Watch`) and the
session's files (`Files`).

Phases: MENU, AIM (a human to shoot), PLACE (ball in hand), RUN (balls moving), CPU (the
computer thinks, then turns its stick), OPTION (the incoming player answers a choice), OVER
(the match is won). Help, pause, the quit question and the Settings and Stats screens are
boxes over any phase.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any, ClassVar

import numpy as np

from termpool.ai import Plan
from termpool.game import Match, ShotRun
from termpool.physics.results import DT
from termpool.rules import words
from termpool.rules.codes import Choice, PlanNote
from termpool.rules.common import legal_targets
from termpool.ui.aim import Aim as Trace
from termpool.ui.aim import aim_trace
from termpool.ui.controls import AimControl, HoldRamp, KeyMap, PowerCharge
from termpool.ui.help import help_pages, keymap_rows
from termpool.ui.settings import DEFAULTS
from termpool.ui.shots import DEFAULT_POWER, Clock
from termpool.ui.table_view import Layout

Line = tuple[str, str]  # (text, tone) of the panel's words: "plain", "dim", "turn", ...
MENU = [  # the menu's entries: a game (mode, opponent), or a screen
    ("8-ball vs computer", ("8ball", "cpu")),
    ("8-ball, two players", ("8ball", "human")),
    ("9-ball vs computer", ("9ball", "cpu")),
    ("9-ball, two players", ("9ball", "human")),
    ("Practice", ("practice", "human")),
    ("Play someone online", "online"),  # only under a server (`termpool serve`)
    ("Settings", "settings"),
    ("Stats", "stats"),
    ("Help", "help"),
    ("Quit", "quit"),
]


@dataclass(frozen=True)
class Options:
    """How to play: the settings (ui.settings: their values and defaults) and the rest."""

    mode: str | None = None  # None: start at the menu
    opponent: str = "cpu"  # "cpu" or "human"
    seed: int | None = None  # racks and the computer's choices; None: a new seed each game
    three_foul: bool = False  # 9-ball: three fouls in a row lose the frame
    eight_break: str = "respot"  # 8-ball: the 8 pocketed on the break is re-spotted or re-racked
    level: str = DEFAULTS["level"]
    table: str = DEFAULTS["table"]
    frames: int = DEFAULTS["frames"]
    theme: str = DEFAULTS["theme"]
    colors: str = DEFAULTS["colors"]
    aid: str = DEFAULTS["aid"]  # the aim aid: "full", "ghost" (the ghost ball only) or "off"
    power: str = DEFAULTS["power"]  # "hold", "meter" or "digits"
    bell: bool = DEFAULTS["bell"]
    fast: str = DEFAULTS["fast"]  # shots start fast-forwarded: "off", "computer", "always"
    records: bool = DEFAULTS["records"]  # every match kept in the data directory's records/
    player1: str = DEFAULTS["player1"]  # names; empty: the usual ones
    player2: str = DEFAULTS["player2"]


class Phase(enum.Enum):
    MENU = "menu"
    AIM = "aim"
    PLACE = "place"
    RUN = "run"
    CPU = "cpu"
    OPTION = "option"
    OVER = "over"
    LOBBY = "lobby"  # who is online, under a server: challenge them, answer challenges
    REMOTE = "remote"  # the other player of an online match moves, on their own screen


@dataclass(frozen=True)
class Power:
    """A player's power as they left it: the level set with a digit (None: hold) and their
    last shot's, which the aid predicts at."""

    preset: float | None
    last: float


# ------------------------------------------------------------------------ the phases' parts
@dataclass(frozen=True)
class Menu:
    phase: ClassVar[Phase] = Phase.MENU


@dataclass(frozen=True)
class Aim:
    phase: ClassVar[Phase] = Phase.AIM


@dataclass(frozen=True)
class Place:
    """Ball in hand: where the cue ball would go (drawn there); `again`, the stroke (angle,
    side, top) of a shot taken back, which the stick takes again if the ball goes down
    where it was."""

    phase: ClassVar[Phase] = Phase.PLACE
    cursor: tuple[float, float]
    again: tuple[float, float, float] | None = None


@dataclass(frozen=True)
class Run:
    """A shot rolling: its frames, computed at the strike, shown by the clock."""

    phase: ClassVar[Phase] = Phase.RUN
    shot: ShotRun
    frames: list  # (pos, state) of the shot's balls after each frame (ui.shots.simulate)
    struck_at: float  # the clock at the strike
    fast: bool  # fast-forwarded (F, or the settings)
    shown: int = 0  # frames shown so far
    clock: Clock = Clock()


@dataclass(frozen=True)
class Thinking:
    """The computer's turn, before its decision: `since` the first tick that showed it
    thinking (its plan is made a frame later, so that the words are on screen while it
    blocks); `skip` a key asked it not to wait."""

    phase: ClassVar[Phase] = Phase.CPU
    since: float | None = None
    skip: bool = False


@dataclass(frozen=True)
class Answering:
    """The computer has decided how to answer the option; it says so at the next tick."""

    phase: ClassVar[Phase] = Phase.CPU
    choice: Choice


@dataclass(frozen=True)
class Aiming:
    """The computer turns its stick from `start` onto its plan's line, then shows it there
    before it shoots (timed from `since`, the first tick of the turn)."""

    phase: ClassVar[Phase] = Phase.CPU
    plan: Plan
    start: float
    since: float | None = None
    skip: bool = False


@dataclass(frozen=True)
class Option:
    phase: ClassVar[Phase] = Phase.OPTION


@dataclass(frozen=True)
class Over:
    phase: ClassVar[Phase] = Phase.OVER


@dataclass(frozen=True)
class Lobby:
    """The players online (ui.link): the one chosen (by their id: the list changes under
    it), the game a challenge is to, and the player challenged while their answer is
    awaited, with the game."""

    phase: ClassVar[Phase] = Phase.LOBBY
    chosen: int | None = None
    game: int = 0  # LOBBY_GAMES
    waiting: str | None = None


LOBBY_GAMES = ("8ball", "9ball")


@dataclass(frozen=True)
class Waiting:
    """An online match: the other player's turn, until their move arrives (ui.link);
    `placed`: their ball in hand is down (the match keeps it in hand until the shot)."""

    phase: ClassVar[Phase] = Phase.REMOTE
    placed: bool = False
    cursor: tuple[float, float] | None = None  # their ball in hand, as they move it
    stick: bool = False  # their stick is on show (its angle and tip in `stroke`)
    power: float | None = None  # the power their aid has (0..1), as it last came
    paused: bool = False  # they have paused their game (P)


Part = (Menu | Aim | Place | Run | Thinking | Answering | Aiming | Option | Over | Lobby
        | Waiting)


# --------------------------------------------------------------------------------- boxes
@dataclass(frozen=True)
class Help:
    page: int = 0  # as asked; the view shows the last page its screen has, if fewer


@dataclass(frozen=True)
class Pause:
    pass


@dataclass(frozen=True)
class Quit:
    pass


@dataclass(frozen=True)
class Settings:
    """The Settings screen (ui.screens): the setting chosen, a name being typed, and the
    values when it opened (the changes are saved when it closes)."""

    before: Mapping[str, Any]
    back: Pause | None = None  # the box it goes back to
    index: int = 0
    editing: str | None = None
    refused: str | None = None  # why a key typed into the name was not taken
    whole: bool = False  # the name being typed is still the old one whole: a key replaces it
    touched: frozenset[str] = frozenset()  # the settings set here (saved as shown, even one
    # set back to a value a flag gave this run)


@dataclass(frozen=True)
class Stats:
    """The Stats screen (ui.screens): its lines, read when it opened, from line `top` and
    column `left` (where the screen is narrower than they are)."""

    text: tuple[str, ...]
    back: Pause | None = None
    top: int = 0
    left: int = 0


Box = Help | Pause | Quit | Settings | Stats


# ------------------------------------------------------------------------- the rest of it
@dataclass(frozen=True)
class Stroke:
    """The shot being set up, by the keys or by the computer's stick."""

    angle: float = 0.0  # degrees, counter-clockwise from the table's length
    side: float = 0.0  # the cue tip's offsets, in ball radii
    top: float = 0.0
    called_k: int = 0  # the pocket called for the 8, when the player picked it ...
    call_picked: bool = False  # ... with C (else the aim's pocket is called)
    push_out: bool = False


@dataclass(frozen=True)
class Controls:
    """The keys' own clocks (ui.controls: handles) and the key that placed the ball in hand
    while it is still held: (key, time, repeating), none of it may start a shot."""

    charge: PowerCharge
    aim: AimControl
    place: HoldRamp
    swallow: tuple[str, float, bool] | None = None


@dataclass(frozen=True)
class Files:
    """The session's files: the settings (ui.settings.Store), the history of play
    (game.history.Recorder) and the matches' records (ui.records.Records); None for those
    not kept."""

    prefs: Any = None
    history: Any = None
    records: Any = None


@dataclass(frozen=True)
class AidJob:
    """The aim aid's prediction (ui.predict) of the shot aimed, as far as it has run: the
    predictor of the table as it lies (`table`: what it is for) and the job of one shot
    (`key`: the table and the shot)."""

    table: tuple | None = None
    predictor: Any = None
    key: tuple | None = None
    job: Any = None


@dataclass(frozen=True)
class Seen:
    """What a screen showed last: its size and the layout of the table it drew (for the
    mouse, and the help's and Stats' pages, which depend on the screen's size)."""

    cols: int
    rows: int
    layout: Layout | None = None
    table: Any = None


@dataclass(frozen=True)
class State:
    # the session
    opts: Options
    keymap: KeyMap
    controls: Controls
    env: Mapping[str, str] | None = None
    files: Files = Files()
    depth: str = "truecolor"
    input_mode: str = "release"
    pending: Mapping[str, Any] = field(default_factory=dict)  # settings for the next game
    notes: tuple[str, ...] = ()  # for the terminal after the game
    done: bool = False
    bells: int = 0  # bells to ring (the driver rings them and sets this back to 0)
    now: float = 0.0  # the clock at the last event
    # what is on show
    part: Part = Menu()
    box: Box | None = None
    watch: Any = None  # a ui.watch.Watch of the match just played (W at the end)
    menu_index: int = 0
    # the match
    match: Match | None = None
    played: tuple[Match, ...] = ()  # earlier matches of this session, with their shots
    cpu: tuple[bool, bool] = (False, False)  # which players the computer plays
    link: Any = None  # the line to the server's lobby (ui.link.Link), under `termpool serve`
    remote: tuple[int, ...] = ()  # an online match: the players whose moves come over the
    # link (the other player; both, watching)
    stroke: Stroke = Stroke()
    last_power: float = DEFAULT_POWER  # the shooter's last shot's power: the aid's until
    # another
    powers: tuple[Power | None, Power | None] = (None, None)  # each player's, kept for
    # their next turn (None: the default power, before their first shot)
    aid: AidJob = AidJob()
    # the words on show
    settings_row: int = 0  # the Settings screen's row when it last closed (it opens there)
    message: tuple[Line, ...] = ()  # the last verdicts and notes, in the panel
    cpu_plan: PlanNote | None = None  # the computer's plan ("the 3 in the top-right corner
    # pocket" in words; None: none)
    shot_note: tuple[Line, ...] = ()  # its line, kept for the shot it is playing

    @property
    def phase(self) -> Phase:
        return self.part.phase

    @property
    def cpu_note(self) -> tuple[Line, ...]:
        """The computer's plan as the panel's line (none without one)."""
        if self.cpu_plan is None:
            return ()
        return ((words.computer_plan(self.cpu_plan, voice(self)), "turn"),)


# ------------------------------------------------------------------------- reading a state
def cue_index(s: State) -> int:
    return s.match.ids.index("cue")


def lies_playable(s: State) -> tuple[float, float] | None:
    """Where the cue ball lies, when it is on the table where it could be put down (Esc
    then leaves it there); else None (after a scratch it must be placed)."""
    m = s.match
    c = cue_index(s)
    if not m.on_table[c]:
        return None
    x, y = (float(v) for v in m.pos[c])
    return None if m.placement_error(x, y) else (x, y)


def shooter_is_cpu(s: State) -> bool:
    return s.cpu[s.match.shooter]


def concedes(s: State) -> bool:
    """Whether leaving now gives the match to the other player: an online match not over,
    whose other player is there (one whose connection dropped is not given it)."""
    m = s.match
    return (len(s.remote) == 1 and m is not None and m.winner is None
            and s.link is not None and s.link.away is None)


def shooter_is_remote(s: State) -> bool:
    return s.match.shooter in s.remote


def lobby_choice(s: State) -> tuple[list[dict], int]:
    """The other players online (ui.link) and the place of the one chosen among them (the
    first when the one chosen has gone; 0 when there is nobody)."""
    others = s.link.others()
    ids = [p.get("id") for p in others]
    return others, ids.index(s.part.chosen) if s.part.chosen in ids else 0


def menu_entries(s: State) -> list:
    """The menu as this session has it: playing someone online only under a server."""
    return [e for e in MENU if e[1] != "online" or s.link is not None]


def voice(s: State) -> words.Voice:
    """How words name this match's players, pockets and groups (rules.words)."""
    return words.voice(s.match.players, shown_theme(s))


def shown_theme(s: State) -> str:
    """The theme this match's balls are drawn and named in (`words.shown_theme`)."""
    if s.match is None:
        return s.opts.theme
    return words.shown_theme(s.opts.theme, s.match.ids)


def shot_clock(s: State) -> float:
    """Simulated seconds of the running shot shown so far (0 with no shot running)."""
    return s.part.shown * DT if isinstance(s.part, Run) else 0.0


def say(s: State, text: str, tone: str = "note") -> State:
    """The state with one line of words in the panel (a note: the answer to a key)."""
    return replace(s, message=((text, tone),))


def trace(s: State) -> Trace | None:
    """The straight line of the aim from the cue ball (None when it is off the table)."""
    m = s.match
    c = cue_index(s)
    if not m.on_table[c]:
        return None
    return aim_trace(m.table, m.pos, m.radius, m.on_table, c, s.stroke.angle)


def targets(s: State) -> list[int]:
    """The balls (indices) the shooter may hit first: every object ball on an 8-ball break,
    and every one when the rules name none; none when the cue ball is off the table."""
    m = s.match
    if not m.on_table[cue_index(s)]:
        return []
    on = [b for b, here in zip(m.ids, m.on_table, strict=True) if here]
    objects = [b for b in on if b != "cue"]
    st = m.state
    legal = objects if st.is_break and st.mode == "8ball" else legal_targets(st, on)
    return [m.ids.index(b) for b in legal or objects]


SAME_AIM = 1e-6  # degrees: an aim this close to a ball's centre is at it already


def next_ball_angle(s: State, clockwise: bool) -> float:
    """The aim at the centre of the next ball the shooter may hit with a clear path (the
    straight line meets it first; any of them when none is clear), turning from the aim as
    it is (clockwise: as the aim's clockwise key turns it); the aim as it is when there is
    none (a ball straight along the aim is not the next: the key moves on)."""
    m = s.match
    c = cue_index(s)
    t = targets(s)
    d = m.pos[t] - m.pos[c]
    angles = [math.degrees(math.atan2(dy, dx)) % 360.0 for dx, dy in d.tolist()]
    clear = [a for a, k in zip(angles, t, strict=True)
             if _first_hit(s, c, a) == k]
    now = s.stroke.angle
    best = None
    for angle in clear or angles:
        turn = ((now - angle) if clockwise else (angle - now)) % 360.0
        if turn > SAME_AIM and (best is None or turn < best[0]):
            best = (turn, angle)
    return now if best is None else best[1]


def in_the_way(s: State) -> int | None:
    """The ball the aim's straight line meets first where it is not one the shooter may hit
    (None: a ball they may hit, or a cushion)."""
    b = _first_hit(s, cue_index(s), s.stroke.angle)
    return b if b is not None and b not in targets(s) else None


def _first_hit(s: State, c: int, angle: float) -> int | None:
    """The ball the cue ball's straight line at `angle` meets first (None: a cushion)."""
    m = s.match
    a = aim_trace(m.table, m.pos, m.radius, m.on_table, c, angle)
    return a.ball if a.hit == "ball" else None


def nearest_angle(s: State) -> float:
    """The aim at the nearest ball the shooter may hit first whose path from the cue ball is
    clear (the straight line meets that ball before any other); the nearest one if none is
    clear; the aim as it is when there is no ball to aim at."""
    m = s.match
    c = cue_index(s)
    t = targets(s)
    if not t:
        return s.stroke.angle
    d = m.pos[t] - m.pos[c]
    order = np.argsort(np.hypot(d[:, 0], d[:, 1]), kind="stable")
    angles = [math.degrees(math.atan2(d[k, 1], d[k, 0])) % 360.0 for k in order]
    for k, angle in zip(order, angles, strict=True):
        if _first_hit(s, c, angle) == t[k]:
            return angle
    return angles[0]


def help_of(s: State, cols: int, rows: int) -> list[tuple[str, list[str]]]:
    """The help box's pages (ui.help): the keys, then the rules of the game in play as it is
    set (at the menu, of every game)."""
    mode = s.match.mode if s.match is not None and s.phase is not Phase.MENU else None
    how: dict[str, Any] = {"theme": s.opts.theme}
    if mode == "9ball":
        how["three_foul"] = s.match.three_foul
    elif mode == "8ball":
        how["eight_break"] = s.match.eight_break
    return help_pages(keymap_rows(s.keymap), mode, cols, rows, **how)
