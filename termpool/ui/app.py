"""The game as a state machine: keys and clock ticks in, screen cells out.

`App` never touches a terminal, so the same code runs on a real terminal (``ui.term``), on a
virtual screen from a key script (``ui.headless``) and in tests. It holds a match
(``termpool.game.Match``), the aim (angle, tip offset, called pocket), the power charge and the
shot in motion, which advances by wall-clock time through a fixed-step accumulator.

Phases: "menu", "aim" (a human to shoot), "place" (ball in hand), "run" (balls moving), "cpu"
(the computer thinks, then turns its stick), "option" (the incoming player answers a choice),
"over" (the match is won). Help, pause, the quit question and the Settings and Stats screens
(``ui.screens``) are boxes over any phase.
"""

from __future__ import annotations

import math
import secrets
from dataclasses import dataclass

import numpy as np

from termpool.game.layout import head_string
from termpool.physics.cue import clamp_tip
from termpool.physics.results import DT
from termpool.physics.state import POCKETED
from termpool.physics.table import POCKET_NAMES
from termpool.rules import words
from termpool.rules.codes import Option
from termpool.ui.output import resolve_depth
from termpool.ui.settings import DEFAULTS, player_names
from termpool.ui.table_view import TableView, layout
from termpool.ui.term import signals_held

MAX_STEPS_PER_TICK = 12  # a stalled terminal drops time instead of freezing on catch-up
MAX_SHOT_FRAMES = 180 * 60  # frames computed ahead; a longer shot finishes at once
MIN_SPEED, MAX_SPEED = 0.25, 9.0  # m/s at no and full power
DEFAULT_POWER = 0.5  # the aid's power (and the digits') before a match's first shot
FAST = 4.0  # fast-forward factor
PLACE_TAP, PLACE_FINE = 0.01, 0.002  # m a tap moves the ball in hand (shift: fine)
SPIN_STEP = 0.1  # tip offset per key, in units of R
CPU_AIM_S = 0.6  # the computer turns its stick onto its aim over this long ...
CPU_SHOW_S = 1.2  # ... then holds it there, its aid and plan on show, this long before it
# shoots (a key shoots at once)
CPU_THINK_FRAME_S = 0.05  # show "thinking" for at least this long before blocking on the plan
AID_STEP = 8  # event times of the aid's prediction run per frame (about 3 ms on the project's
# machine, benchmarks/aid.py): a long prediction fills in over a few frames
AID_WORDS = {"full": "aim aid: every path (G: ghost ball only)",
             "ghost": "aim aid: the ghost ball only (G: off)", "off": "aim aid off (G: on)"}

MENU = [
    ("8-ball vs computer", ("8ball", "cpu")),
    ("8-ball, two players", ("8ball", "human")),
    ("9-ball vs computer", ("9ball", "cpu")),
    ("9-ball, two players", ("9ball", "human")),
    ("Practice", ("practice", "human")),
    ("Settings", "settings"),
    ("Stats", "stats"),
    ("Help", "help"),
    ("Quit", "quit"),
]


@dataclass
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
    player1: str = DEFAULTS["player1"]  # names; empty: the usual ones
    player2: str = DEFAULTS["player2"]


def power_to_speed(level: float) -> float:
    """Cue-ball speed for a power level in [0, 1]: finer control of the soft shots most
    positions need (half power is about 3.3 m/s, full power a 9 m/s break)."""
    level = min(1.0, max(0.0, level))
    return MIN_SPEED + (MAX_SPEED - MIN_SPEED) * level ** 1.5


class App:
    def __init__(self, opts: Options | None = None, keymap=None, input_mode: str = "release",
                 env=None) -> None:
        from termpool.ui.controls import AimControl, HoldRamp, KeyMap

        self.opts = opts or Options()
        self.keymap = keymap if keymap is not None else KeyMap()
        self.env = env
        self.depth = resolve_depth(self.opts.colors, env)
        self.aimctl = AimControl(self.keymap)
        self.last_power = DEFAULT_POWER  # the last shot's power: the aid's until another
        self.shot_power_set = False  # ... once this match has a shot of the keys'
        self.set_input_mode(input_mode)
        self.done = False
        self.dirty = True
        self.bells = 0  # bells to ring (the driver writes BEL and resets this)
        self.overlay: str | None = None  # "help", "pause", "quit"
        self.help_page, self.help_count = 0, 1  # the help box's page on show, of how many
        self.watching = None  # a ui.watch.Watch of the match just played (W at the end)
        self.menu_index = 0
        self._swallow = None  # (key, time, repeating): the key that placed the ball, held
        # Ball in hand: 1 cm a tap; held, from 0.25 to 1 m/s over a second from the press.
        self.place_ramp = HoldRamp(PLACE_TAP, 0.25, 1.0, 1.0, from_press=True)
        self.match = None
        self.played: list = []  # earlier matches of this session, with their shots
        self.run = None
        self.now = 0.0
        self._last = None  # clock at the last tick while a shot runs
        self._acc = 0.0
        self.fast = False
        self.message: list[tuple[str, str]] = []
        self.notes: list[str] = []  # for the terminal after the game (see `record`)
        self._geom = None  # (cols, rows, layout, view)
        self._aim_cache = None
        self._predictor = None  # (layout key, ui.predict.Predictor) for the table now
        self._aid = None  # (key, Job, Prediction or None): the aid's prediction, as far as run
        self._cpu_note: list = []  # the computer's plan, in words, for the panel
        self._shot_note: list = []  # ... kept for the shot it is playing
        self._your_verdict = None  # the verdict on the last shot of a player against the
        # computer: kept in view through the computer's turn
        self.screen = None  # the Settings or Stats screen (ui.screens), when open
        self.pending: dict = {}  # settings changed during a match, for the next one
        self.prefs = None  # the settings file (ui.settings.Store), to save changes to
        self.history = None  # the history of play (game.history.Recorder), to add matches to
        self.records = None  # --record (ui.records.Records): every match of the session
        if self.opts.mode is None:
            self.phase = "menu"
        else:
            self.new_match(self.opts.mode, self.opts.opponent)

    # ----------------------------------------------------------------------------- set-up
    def set_input_mode(self, mode: str) -> None:
        """How the terminal tells a held key: "release" (kitty protocol), "repeat" (infer
        holds) or "classic" (it cannot: press, press). The power setting picks the meter or
        digits over holds."""
        from termpool.ui.controls import PowerCharge

        self.input_mode = mode
        shoot = self.keymap.keys_for("shoot")
        self.charge = PowerCharge("classic" if self.opts.power == "meter" else mode,
                                  key_label=shoot[0] if shoot else "space")
        if self.opts.power == "digits":
            self.charge.preset(self.last_power)
        self.dirty = True

    def new_match(self, mode: str, opponent: str) -> None:
        from termpool.game import Match
        from termpool.ui.screens import apply_pending

        self.log_match()
        if self.match is not None and self.match.history:
            self.played.append(self.match)  # kept for --record
        apply_pending(self)
        # Power starts afresh: a soft safety's 20% of the last game is no break for this one.
        self.last_power, self.shot_power_set = DEFAULT_POWER, False
        self.charge.preset(self.last_power if self.opts.power == "digits" else None)
        self.opts.mode, self.opts.opponent = mode, opponent
        names = player_names(self.opts.player1, self.opts.player2, mode, opponent)
        self.cpu = (False, opponent == "cpu" and mode != "practice")
        # Without a seed every game deals a new rack; the seed is in the record either way.
        seed = self.opts.seed if self.opts.seed is not None else secrets.randbits(63)
        from termpool.ai import Computer

        players = tuple(Computer(self.opts.level, n) if c else n
                        for n, c in zip(names, self.cpu, strict=True))
        self.match = Match(mode, table=self.opts.table, frames=self.opts.frames,
                           players=players, seed=seed, theme=self.opts.theme,
                           three_foul=self.opts.three_foul and mode == "9ball",
                           eight_break=self.opts.eight_break)
        self._geom = None
        self.run = None
        self.message = []
        self._your_verdict = None
        self.angle = 0.0
        self.side = self.top = 0.0
        self.called_k = 0
        self.call_picked = False  # the player chose the called pocket with C
        self.push_out = False
        self._turn_start()

    # ------------------------------------------------------------------------ the match
    @property
    def table(self):
        return self.match.table

    def cue_index(self) -> int:
        return self.match.ids.index("cue")

    def _targets(self) -> list[int]:
        """Indices of the balls the shooter may legally hit first (for the initial aim); any
        ball on an 8-ball break, or when the rules name none."""
        from termpool.rules.common import legal_targets

        m = self.match
        on = [b for b, here in zip(m.ids, m.on_table, strict=True) if here]
        objects = [b for b in on if b != "cue"]
        st = m.state
        legal = objects if st.is_break and st.mode == "8ball" else legal_targets(st, on)
        return [m.ids.index(b) for b in legal or objects]

    def _aim_at_nearest(self) -> None:
        """Aim at the nearest ball the shooter may hit first whose path from the cue ball is
        clear (the straight line meets that ball before any other); the nearest one if none
        is clear."""
        from termpool.ui.aim import aim_trace

        m = self.match
        c = self.cue_index()
        t = self._targets()
        if not t or not m.on_table[c]:
            return
        d = m.pos[t] - m.pos[c]
        order = np.argsort(np.hypot(d[:, 0], d[:, 1]), kind="stable")
        angles = [math.degrees(math.atan2(d[k, 1], d[k, 0])) % 360.0 for k in order]
        for k, angle in zip(order, angles, strict=True):
            a = aim_trace(m.table, m.pos, m.radius, m.on_table, c, angle)
            if a.hit == "ball" and a.ball == t[k]:
                self.angle = angle
                return
        self.angle = angles[0]

    def voice(self) -> words.Voice:
        """How words name this match's players, pockets and groups (rules.words)."""
        return words.voice(self.match.players, self.opts.theme)

    def shooter_is_cpu(self) -> bool:
        return self.cpu[self.match.shooter]

    def _turn_start(self) -> None:
        """Set up the next phase once the table is at rest."""
        m = self.match
        self.run = None
        self.charge.cancel()
        self.side = self.top = 0.0
        self.push_out = False
        self.call_picked = False
        self._aim_cache = None
        self._cpu_skip = False
        if m.frame_over and m.winner is None:
            self._your_verdict = None  # the frame's end is the news now
            won = m.frame_winner
            m.new_frame()
            self.message.append((words.frame_won(self.voice(), won, m.scores, m.shooter),
                                 "good"))
        if m.winner is not None:
            self.phase = "over"
            self.log_match()
        elif m.option is not None:
            self.phase = "cpu" if self.shooter_is_cpu() else "option"
            self._cpu_plan = None
        elif self.shooter_is_cpu():
            self.phase = "cpu"
            self._cpu_plan = None
            self._cpu_t0 = None
        elif m.ball_in_hand:
            self.phase = "place"
            c = self.cue_index()
            x, y = m.pos[c] if m.on_table[c] else m.table.head_spot
            if m.placement_error(x, y):
                x, y = m.table.head_spot
            self.cursor = [float(x), float(y)]
        else:
            self.phase = "aim"
            if m.state.is_break:
                self.angle = 0.0
            else:
                self._aim_at_nearest()
        self.dirty = True

    def _shoot(self, speed: float, angle: float, side: float, top: float, called=None,
               push_out: bool = False, keep_message: bool = False) -> None:
        from termpool.game import Shot

        side, top = clamp_tip(side, top)  # the strike's own limit, for the computer's too
        shot = Shot(speed=speed, angle=angle, side=side, top=top, called=called,
                    push_out=push_out)
        try:
            self.run = self.match.begin(shot)
        except ValueError as e:  # a shot the match refuses: say why, and let the shooter
            # aim again (the computer's shots are checked the same way; should one be refused,
            # the shot is left to the keys rather than to a loop of refusals)
            self.message = [(f"that shot cannot be played: {e}", "foul")]
            self.phase = "aim"
            self.dirty = True
            return
        self.struck_at = self.now  # the clock at the strike
        self.frames = self._simulate(self.run)
        self.shown = 0  # frames of the shot shown so far
        fast = self.opts.fast  # fast-forward is for one shot, unless the settings say
        self.fast = fast == "always" or (fast == "computer" and self.shooter_is_cpu())
        self.phase = "run"
        self._last = None
        self._acc = 0.0
        # The computer's plan stays in view while its shot runs, and then beside the verdict.
        self._shot_note = self._cpu_note if keep_message else []
        yours = [self._your_verdict] if keep_message and self._your_verdict else []
        self.message = yours + list(self._shot_note)
        self.dirty = True

    def _shoot_human(self, level: float) -> None:
        self.last_power, self.shot_power_set = level, True
        called = None
        if self.match.needs_call():
            called = self._called()
        self._shoot(power_to_speed(level), self.angle, self.side, self.top, called,
                    self.push_out)

    def _called(self) -> tuple[str, str]:
        """The call for this shot (the 8, which is the only ball ever called): the pocket the
        aim sends it to, unless the player picked one with C."""
        k = self.called_k if self.call_picked else self._aimed_pocket()
        return "8", POCKET_NAMES[k % len(POCKET_NAMES)]

    def _aimed_pocket(self) -> int:
        """Index of the pocket the aid sees the first ball go into; else the one it heads
        for (0 with no ball hit)."""
        pred = self.prediction()
        names = list(self.table.hole_names)
        if pred is not None and pred.object is not None and len(pred.object.points) > 1:
            if pred.object.end == "pocket" and pred.object.pocket in names:
                return names.index(pred.object.pocket)
            p, q = pred.object.points[0], pred.object.points[1]
        else:
            aim = self.aim()
            if aim is None or aim.ball is None or aim.object_dir is None:
                return 0
            p = self.match.pos[aim.ball]
            q = p + np.asarray(aim.object_dir)
        d = self.table.hole_c.reshape(-1, 2) - p
        u = (q - p) / max(float(np.hypot(*(q - p))), 1e-12)
        score = (d @ u) / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-9)
        return int(np.argmax(score))

    def _finish_shot(self) -> None:
        m = self.match
        before = int(m.on_table.sum())
        by_cpu = self.shooter_is_cpu()
        with signals_held():  # judged and recorded whole, whatever interrupts
            out = self.run.finish()
        verdict = words.verdict(out, self.voice())
        self.message = [*self._shot_note, verdict]
        if not by_cpu and any(self.cpu):
            self._your_verdict = verdict
        if self.opts.bell and (out.foul or int(m.on_table.sum()) < before):
            self.bells += 1  # a pocketed ball or a foul
        self._turn_start()

    # -------------------------------------------------------------------------- the clock
    def wake_in(self, t: float) -> float | None:
        """Seconds until the app needs a tick (None: only on a key)."""
        if self.watching is not None:
            return self.watching.wake_in(t)
        if self.overlay is not None:
            return None
        if self.phase in ("run", "cpu") or (self._aid is not None and not self._aid[1].done):
            return 0.0
        if self.charge.active:  # the meter moves; an inferred release is due at its time
            due = self.charge.release_due()
            return 0.0 if due is None else max(0.0, due - t)
        return None

    def tick(self, t: float) -> None:
        self.now = t
        if self.watching is not None:
            self.watching.tick(t)
            self.dirty = self.dirty or self.watching.dirty
            return
        if self._aid is not None and not self._aid[1].done:  # the aid fills in
            self._aid[1].run(AID_STEP)
            self._aid = (*self._aid[:2], None)
            self.dirty = True
        if self.overlay is not None:
            self._last = None  # paused or asking: the shot waits
            return
        if self.phase == "run":
            self._advance(t)
        elif self.phase == "cpu":
            self._cpu(t)
        elif self.phase == "aim" and self.charge.active:
            level = self.charge.poll(t)
            self.dirty = True
            if level is not None:
                self._shoot_human(level)

    @staticmethod
    def _simulate(run) -> list:
        """Every frame of the shot, computed when it is struck. A step can cost far more than a
        frame (the break's impact: ~100 contacts in 1/60 s), and a hitch there would show; the
        same cost paid at the strike does not. The steps are the ones `run.step` takes live, so
        the match and its replay are unchanged."""
        frames = []
        while not run.done and len(frames) < MAX_SHOT_FRAMES:
            run.step(DT)
            e = run.engine
            frames.append((e.pos[0].copy(), e.state[0].copy()))
        return frames

    @property
    def shot_clock(self) -> float:
        """Simulated seconds of the running shot shown so far."""
        return self.shown * DT if self.run is not None else 0.0

    def _advance(self, t: float) -> None:
        if self._last is None:
            self._last = t
            return
        self._acc += (t - self._last) * (FAST if self.fast else 1.0)
        self._last = t
        n = min(int(self._acc / DT), MAX_STEPS_PER_TICK)
        self._acc = 0.0 if n == MAX_STEPS_PER_TICK else self._acc - n * DT
        if n:
            self.shown = min(self.shown + n, len(self.frames))
            self.dirty = True
        if self.shown >= len(self.frames):
            self._finish_shot()

    def _cpu(self, t: float) -> None:
        m = self.match
        if self._cpu_plan is None:
            if getattr(self, "_cpu_t0", None) is None:
                self._cpu_t0 = t  # draw "thinking" first, then block on the plan
                self.dirty = True
                return
            if t - self._cpu_t0 < CPU_THINK_FRAME_S:
                return
            self._cpu_plan = self._plan()
            self._cpu_from = self.angle
            self._cpu_t0 = None  # timed from the first frame that shows it: `t` is from
            self.dirty = True  # before the plan, which takes a second of its own
            return
        plan = self._cpu_plan
        if plan == "done":
            return
        if isinstance(plan, str):  # an answer to an option, said in words
            who = m.players[m.shooter]
            m.choose(plan)
            self._cpu_plan = "done"
            self.message = [(words.chose(who, plan), "turn")]
            self._turn_start()
            return
        if self._cpu_t0 is None:
            self._cpu_t0 = t
        elapsed = t - self._cpu_t0
        f = 1.0 if self._cpu_skip else min(1.0, elapsed / CPU_AIM_S)
        turn = (plan.angle - self._cpu_from + 180.0) % 360.0 - 180.0
        self.angle = plan.angle if f >= 1.0 else (self._cpu_from + f * turn) % 360.0
        self.side, self.top = plan.side * f, plan.top * f
        self.dirty = True
        if self._cpu_skip or elapsed >= CPU_AIM_S + CPU_SHOW_S:
            self._cpu_plan = "done"
            self._shoot(plan.speed, plan.angle, plan.side, plan.top, plan.called,
                        keep_message=True)

    def _plan(self):
        """The computer's decision: an option's answer, a placement, then a shot."""
        m = self.match
        player = m.seats[m.shooter]
        if m.option is not None:
            return player.answer(m)
        if m.ball_in_hand:
            m.place_cue(*player.place(m))
        plan = player.shot(m)
        foresees = plan.sees in ("win", "loss", "foul")
        note = [(f"Computer: {plan.note}", "turn")] if plan.note and not foresees \
            else []  # a plan ("3 in the foot left pocket"), not the result it simulated
        # The verdict on the player's own last shot stays in view through the computer's
        # turn, however many shots it takes; else the last verdict (without the plan of the
        # shot it was about).
        last = [x for x in self.message if x not in self._shot_note][:2]
        kept = last if self._your_verdict is None else [self._your_verdict] + [
            x for x in last if x[0].startswith(f"{m.players[m.shooter]} chose to ")]
        self.message = kept + note
        self._cpu_note = note
        return plan

    # ------------------------------------------------------------------------------ keys
    def key(self, key, t: float) -> None:
        self.now = t
        if self.watching is not None:
            self.watching.key(key, t)
            if self.watching.done:  # back to the end of the match
                self.watching = None
            self.dirty = True
            return
        action = self.keymap.action(key)
        if key.kind == "release" and action != "shoot":
            self.aimctl.step(key, t)  # a release ends an aim hold: the next press is a tap
            self.place_ramp.release(key.name)  # ... and a ball-in-hand hold
            if self._swallow is not None and key.name == self._swallow[0]:
                self._swallow = None
            return
        if self.overlay is not None:
            self._overlay_key(key, action)
            return
        if self.phase in ("option", "over") and key.kind == "press" and self._answer(key):
            self.dirty = True
            return  # their letters (P: pass, N: new game) come before the global keys
        if action == "help" and key.kind == "press":
            self.overlay, self.help_page = "help", 0
        elif action == "quit" and key.kind == "press":
            self.overlay = "quit" if self.phase != "menu" else None
            self.done = self.phase == "menu"
        elif action == "pause" and key.kind == "press" and self.phase != "menu":
            self.overlay = "pause"
        elif action == "bell" and key.kind == "press":
            self.opts.bell = not self.opts.bell
            self.message = [("sound on" if self.opts.bell else "sound off", "dim")]
        else:
            getattr(self, "_key_" + self.phase)(key, action, t)
        self.dirty = True

    def mouse(self, ev, t: float) -> None:
        """A left press or drag on the table aims at that point (or, with ball in hand,
        moves the cue ball there); the arrows then refine."""
        self.now = t
        if (self.overlay is not None or self.match is None or self._geom is None
                or self.watching is not None
                or self.phase not in ("aim", "place") or ev.button != 0
                or ev.kind not in ("press", "drag")):
            return
        lay = self._geom[2]
        if lay is None:
            return
        ox, oy, ow, oh = lay.outer
        if not (ox <= ev.col < ox + ow and oy <= 2 * ev.row + 1 < oy + oh):
            return  # the panel, or beside the table
        x = (ev.col + 0.5 - lay.px) / lay.sx  # the cell's centre, in table metres
        y = lay.width - (2 * ev.row + 1 - lay.py) / lay.sy
        if self.phase == "place":
            self.cursor = self._clamp_cursor(x, y)
        else:
            cx, cy = self.match.pos[self.cue_index()]
            if math.hypot(x - cx, y - cy) < 1e-9:
                return
            self.angle = math.degrees(math.atan2(y - cy, x - cx)) % 360.0
            self._aim_cache = None
            self.call_picked = False  # a new aim: the 8's call follows it again
        self.dirty = True

    def open_screen(self, what: str, back: str | None = None) -> None:
        """Open the Settings or the Stats screen; it goes back to `back` when it closes."""
        from termpool.ui.screens import SettingsScreen, StatsScreen

        self.screen = (SettingsScreen if what == "settings" else StatsScreen)(self, back)
        self.overlay = "screen"

    def to_menu(self) -> None:
        """Leave the match for the menu (it is saved and added to the history first)."""
        if self.run is not None:
            self.record()  # a shot still rolling is played out, as on the way out
        self.log_match()
        if self.match is not None and self.match.history:
            self.played.append(self.match)
        self.overlay = None
        self.run = None
        self.phase = "menu"
        self.match = None
        self.dirty = True

    def log_match(self) -> None:
        """The match in play has ended or is being left: save it (--record) and add it to the
        history of play (once; not one without shots). A file that cannot be written is one
        line for the terminal when the game ends."""
        if self.records is not None:
            self.records.keep(self.match)
        if self.history is not None and self.match is not None:
            warning = self.history.add(self.match, self.cpu, self.opts.level)
            if warning:
                self.notes.append(warning)

    def _overlay_key(self, key, action) -> None:
        if self.screen is not None:
            self.screen.key(self, key, action)
            if self.screen.closed:
                self.overlay, self.screen = self.screen.back, None
            self.dirty = True
            return
        if key.kind != "press":
            return
        if self.overlay == "pause" and key.name == "s" and not (key.ctrl or key.alt):
            self.open_screen("settings", "pause")
        elif self.overlay == "quit":
            if key.name in ("y", "q") or action == "quit":
                self.done = True
            elif key.name == "m" and not (key.ctrl or key.alt):
                self.to_menu()
            elif key.name == "n" or action in ("cancel", "confirm"):
                self.overlay = None
        elif self.overlay == "help":
            from termpool.ui.help import page_key

            self.help_page, close = page_key(key.name, self.help_page, self.help_count)
            if close:
                self.overlay = None
                self._menu_help = False
        else:
            self.overlay = None  # any key ends the pause
        self.dirty = True

    _menu_help = False

    def _key_menu(self, key, action, t) -> None:
        if key.kind == "release":
            return
        n = len(MENU)
        if key.name in ("up", "k") or action == "spin_up":
            self.menu_index = (self.menu_index - 1) % n
        elif key.name in ("down", "j") or action == "spin_down":
            self.menu_index = (self.menu_index + 1) % n
        elif key.name.isdigit() and 1 <= int(key.name) <= n:
            self.menu_index = int(key.name) - 1
            self._menu_pick()
        elif action in ("confirm", "shoot"):
            self._menu_pick()

    def menu_label(self, k: int) -> str:
        """Menu entry k as shown."""
        return MENU[k][0]

    def _menu_pick(self) -> None:
        what = MENU[self.menu_index][1]
        if what == "quit":
            self.done = True
        elif what == "help":
            self.overlay, self.help_page = "help", 0
            self._menu_help = True
        elif what in ("settings", "stats"):
            self.open_screen(what)
        else:
            self.new_match(*what)

    def _key_aim(self, key, action, t) -> None:
        if self._swallow is not None and key.name == self._swallow[0]:
            name, last, repeating = self._swallow
            # Auto-repeat starts up to 0.75 s after the press, then comes every 20-100 ms.
            if key.kind == "repeat" or (key.kind == "press"
                                        and t - last <= (0.15 if repeating else 0.75)):
                self._swallow = (name, t, True)
                return
            self._swallow = None
            if key.kind == "release":
                return
        if action == "shoot":
            level = self.charge.key(key, t)
            if level is not None:
                self._shoot_human(level)
            return
        if key.kind == "release":
            return
        if action in ("aim_ccw", "aim_cw", "aim_fine_ccw", "aim_fine_cw"):
            self.angle = (self.angle + self.aimctl.step(key, t)) % 360.0
            self._aim_cache = None
            self.call_picked = False  # a new aim: the 8's call follows it again
        elif action in ("spin_up", "spin_down", "spin_left", "spin_right"):
            dx = {"spin_left": -1, "spin_right": 1}.get(action, 0)
            dy = {"spin_down": -1, "spin_up": 1}.get(action, 0)
            # Rounded so that ten steps make 1.0, then kept on the ball: past the miscue
            # limit the tip slides along it.
            self.side, self.top = clamp_tip(round(self.side + dx * SPIN_STEP, 6),
                                            round(self.top + dy * SPIN_STEP, 6))
        elif action == "spin_reset":
            self.side = self.top = 0.0
        elif action == "cancel":
            if self.charge.active:
                self.charge.cancel()
            elif self.charge.preset_level is not None and self.opts.power != "digits":
                self.charge.preset(None)
                self.message = [(f"power: hold {self.charge.key_label} again", "dim")]
        elif action is None and _power_digit(key) is not None:
            self.charge.preset(_power_digit(key))
        elif action == "aim_aid":
            from termpool.ui.predict import LEVELS

            self.opts.aid = LEVELS[(LEVELS.index(self.opts.aid) - 1) % len(LEVELS)]
            self.message = [(AID_WORDS[self.opts.aid], "dim")]
        elif action == "call_pocket":
            if self.match.needs_call():
                start = self.called_k if self.call_picked else self._aimed_pocket()
                self.called_k = (start + 1) % len(POCKET_NAMES)
                self.call_picked = True
            elif self.match.state.mode == "8ball":
                self.message = [("no call needed: only the 8 is called, once your group is "
                                 "down", "dim")]
            else:
                self.message = [("no calls in this game", "dim")]
        elif action == "push_out":
            if self.match.state.push_out == "available":
                self.push_out = not self.push_out
            else:
                self.message = [("a push-out is only for the shot after a 9-ball break", "dim")]
        elif action == "place" and self.match.ball_in_hand:
            self.phase = "place"
        elif action == "fast_forward":
            self.fast = not self.fast
        elif action in ("undo", "rerack") and self.match.state.mode != "practice":
            self.message = [("take back and re-rack are for practice", "dim")]
        elif action == "undo" and self.match.state.mode == "practice":
            try:
                self.match.take_back()
                self.message = [("took the last shot back", "dim")]
            except ValueError:
                self.message = [("nothing to take back", "dim")]
            self._turn_start()
        elif action == "rerack" and self.match.state.mode == "practice":
            self.match.rerack()
            self.message = [("re-racked", "dim")]
            self._turn_start()

    def _key_place(self, key, action, t) -> None:
        if key.name in ("left", "right", "up", "down") and key.kind != "release":
            step = self._place_step(key, t)
            dx = {"left": -1, "right": 1}.get(key.name, 0)
            dy = {"up": 1, "down": -1}.get(key.name, 0)
            self.cursor = self._clamp_cursor(self.cursor[0] + dx * step,
                                             self.cursor[1] + dy * step)
        elif action in ("confirm", "place", "shoot") and key.kind == "press":
            why = self.match.placement_error(*self.cursor, self.voice())
            if why:
                self.message = [(f"Can't place the cue ball there: {why}", "foul")]
            else:
                self.match.place_cue(*self.cursor)
                self.message = []
                self.phase = "aim"
                # Held, the key that put the ball down keeps coming (repeats; on terminals
                # without releases, as presses): none of it may start a shot.
                self._swallow = (key.name, t, False) if action == "shoot" else None
                self._aim_at_nearest()
                self._aim_cache = None

    def _place_step(self, key, t: float) -> float:
        """Metres to move the ball in hand for this arrow event (Shift: 2 mm, held or not)."""
        if key.shift:
            return PLACE_FINE
        return self.place_ramp.step(key.name, key.kind, t)

    def _clamp_cursor(self, x: float, y: float) -> list[float]:
        """Keep the ball in hand on the cloth (and behind the head string when it must be)."""
        r = float(self.match.radius[self.cue_index()])
        L, W = self.table.length, self.table.width
        right = head_string(self.table) if self.match.ball_in_hand == "kitchen" else L - r
        return [min(right, max(r, x)), min(W - r, max(r, y))]

    def _key_run(self, key, action, t) -> None:
        if action == "shoot":
            self.charge.observe(key, t)  # a key still held after the strike: its repeats
        elif action == "fast_forward" and key.kind == "press":
            self.fast = not self.fast

    def _key_cpu(self, key, action, t) -> None:
        if key.kind == "press":  # any key: no more waiting for the computer's shot
            self._cpu_skip = True
        self._key_run(key, action, t)

    def _answer(self, key) -> bool:
        """A letter answering the option box or the game-over box; False if it is not one."""
        if self.phase == "option":
            keys = {words.CHOICE_KEYS[c]: c for c in Option(self.match.option).choices}
            pick = keys.get(key.name)
            if pick is None:
                return False
            who = self.match.players[self.match.shooter]
            self.match.choose(pick)
            self.message = [(words.chose(who, pick), "dim")]
            self._turn_start()
            return True
        if key.name == "n":
            self.new_match(self.opts.mode, self.opts.opponent)
        elif key.name == "m":
            self.to_menu()
        elif key.name == "w":  # watch the match just played, then come back here
            from termpool.ui.watch import Watch

            self.watching = Watch(self.match.to_json(), self.depth)
        elif key.name == "q" or self.keymap.action(key) == "quit":
            self.done = True  # the box says "q: quit": no second question on top of it
        else:
            return False
        return True

    def _key_option(self, key, action, t) -> None:
        pass  # only the answers (see _answer) and the global keys

    def _key_over(self, key, action, t) -> None:
        pass

    # ------------------------------------------------------------------------ the screen
    def aim(self):
        """The aim trace for the current angle (cached until the angle or the layout changes)."""
        from termpool.ui.aim import aim_trace

        m = self.match
        c = self.cue_index()
        if not m.on_table[c]:
            return None
        key = (self.angle, len(m.history), m.pos[c, 0], m.pos[c, 1])
        if self._aim_cache is None or self._aim_cache[0] != key:
            a = aim_trace(m.table, m.pos, m.radius, m.on_table, c, self.angle)
            self._aim_cache = (key, a)
        return self._aim_cache[1]

    def aid_level(self) -> str:
        """What the aid shows now: the player's choice; on the computer's turn at least the
        ghost ball, so that its aim can be followed."""
        if self.phase == "cpu" and self.opts.aid == "off":
            return "ghost"
        return self.opts.aid

    def aid_shot(self):
        """The shot the aid predicts: the shooter's aim and spin at the power they would
        shoot with now (set, charging, or their last), or the computer's plan as its stick
        turns; None when no shot is being aimed."""
        from termpool.game import Shot

        if self.phase == "aim":
            ch = self.charge
            level = ch.preset_level if ch.preset_level is not None else (
                round(ch.level(self.now), 2) if ch.active else self.last_power)
            return Shot(power_to_speed(level), self.angle, self.side, self.top)
        plan = getattr(self, "_cpu_plan", None)
        if self.phase == "cpu" and plan is not None and not isinstance(plan, str):
            return Shot(plan.speed, self.angle, self.side, self.top)
        return None

    def prediction(self):
        """The engine's prediction of `aid_shot()` (ui.predict), as far as it has run: the
        first share of it at once, the rest a share a frame (see `tick`); None with the aid
        off or nothing aimed. Computed again only when the aim, power, spin or table change."""
        from termpool.ui.predict import Predictor

        m = self.match
        shot = self.aid_shot() if m is not None and self.aid_level() != "off" else None
        if shot is None or not m.on_table[self.cue_index()]:
            return None
        where = (len(m.history), m.frame, m.pos.tobytes(), m.on_table.tobytes())
        if self._predictor is None or self._predictor[0] != where:
            self._predictor = (where, Predictor(m))
            self._aid = None
        key = (where, shot)
        if self._aid is None or self._aid[0] != key:
            job = self._predictor[1].start(shot)
            if job is None:
                return None
            job.run(AID_STEP)
            self._aid = (key, job, None)
        if self._aid[2] is None:
            self._aid = (*self._aid[:2], self._aid[1].result())
        return self._aid[2]

    def _geometry(self, cols: int, rows: int):
        if self._geom is None or self._geom[:2] != (cols, rows):
            lay = layout(cols, rows, self.table)
            view = TableView(self.table, lay, self.opts.theme) if lay is not None else None
            self._geom = (cols, rows, lay, view)
        return self._geom[2], self._geom[3]

    def cells(self, cols: int, rows: int):
        """The whole screen as (chars, fg, bg) cells (see ui.app_screen)."""
        from termpool.ui.app_screen import cells

        if self.watching is not None:
            self.dirty = False
            return self.watching.cells(cols, rows)
        return cells(self, cols, rows)

    def _positions(self):
        m = self.match
        state = np.where(m.on_table, 0, POCKETED).astype(np.int8)
        if self.run is not None and self.shown > 0:  # the shot's frame now on show
            p, st = self.frames[self.shown - 1]
            rows = self.run.rows  # the engine holds only the balls that were on the table
            pos = m.pos.copy()
            pos[rows] = p
            state[rows] = st
            return pos, state
        if self.phase == "place":  # the ball in hand is drawn where the cursor is
            pos = m.pos.copy()
            c = self.cue_index()
            pos[c] = self.cursor
            state[c] = 0
            return pos, state
        return m.pos, state

    def record(self):
        """The match to save (--record): this one if it has shots, else the last that had.
        A shot still rolling (the game was left mid-shot) is played out first: simulated again
        from its start, since an interrupt may have stopped its engine between two updates
        (the same steps give the same shot). Should even that fail, the match is kept as it
        stood before the shot, and `notes` says so."""
        m = self.match
        if m is not None and m.running is not None:
            shot = m.running.shot
            m.abandon(m.running)
            try:
                m.begin(shot).finish()
            except Exception as e:  # whatever went wrong, the shots before it are kept
                if m.running is not None:
                    m.abandon(m.running)
                self.notes.append(f"the last shot could not be played out ({e}); the record "
                                  "ends with the shot before it")
            self.run = None
        if m is not None and m.history:
            return m
        return self.played[-1] if self.played else m


def _power_digit(key) -> float | None:
    """The power a digit key sets (1-9: 10-90%, 0: 100%), or None for any other key."""
    if key.kind != "press" or key.ctrl or key.alt or len(key.name) != 1 \
            or key.name not in "0123456789":
        return None
    return (int(key.name) or 10) / 10
