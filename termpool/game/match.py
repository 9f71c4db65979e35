"""A match: the table between shots, whose turn, ball in hand, options, frames and the record.

See the package docstring (`termpool.game`) for the API and the choices made.
"""

from __future__ import annotations

import copy
from dataclasses import replace
from typing import Any

import numpy as np

from termpool.ai import LEVELS
from termpool.physics.engine import POCKETED
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics
from termpool.physics.results import DT  # the fixed engine step of every shot (recorded with it)
from termpool.physics.table import PRESETS, Table
from termpool.rules.common import GROUPS, MODE_BALLS, MODES, Outcome, State
from termpool.rules.events import summarize
from termpool.rules.referee import judge
from termpool.rules.themes import THEMES
from termpool.rules.words import FOUL_LIMIT, count_word, ordinal
from termpool.scene import table_to_dict

from . import layout, record
from .turn import Shot, ShotRun, game_block, state_to_json

EIGHT_BREAKS = ("respot", "rerack")  # what the 8 pocketed on a legal break means
OPTIONS = {"rerack_or_accept": ("rerack", "accept"), "shoot_or_pass": ("shoot", "pass")}
FORMAT = "termpool-replay"
VERSION = 1


class Match:
    """Two players (one in practice), frames to win, the layout between shots and the record."""

    def __init__(self, mode: str = "8ball", *, table: str | Table = "9ft", frames: int = 1,
                 players: tuple[str, str] = ("Player 1", "Player 2"), seed: int = 0,
                 physics: Physics | None = None, three_foul: bool = False,
                 theme: str = "standard", dt: float = DT, eight_break: str = "respot",
                 levels: tuple[str | None, str | None] = (None, None)) -> None:
        if mode not in MODES:
            raise ValueError(f"mode: must be one of {', '.join(MODES)}, not {mode!r}")
        if isinstance(table, str):
            if table not in PRESETS:
                raise ValueError(f"table: unknown preset {table!r} (use {', '.join(PRESETS)})")
            table = Table.preset(table)
        if not isinstance(table, Table) or table.pockets != "standard":
            raise ValueError("table: must be a preset name or a Table with pockets")
        if type(frames) is not int or frames < 1:
            raise ValueError(f"frames: must be a whole number >= 1, not {frames!r}")
        if (not isinstance(players, (tuple, list)) or len(players) != 2
                or not all(isinstance(p, str) and p.strip() for p in players)):
            raise ValueError("players: must be two non-empty names")
        if type(seed) is not int:
            raise ValueError(f"seed: must be a whole number, not {seed!r}")
        if (not isinstance(levels, (tuple, list)) or len(levels) != 2
                or not all(lv is None or lv in LEVELS for lv in levels)):
            raise ValueError(f"levels: must be two of None (a person), {', '.join(LEVELS)}")
        physics = Physics() if physics is None else physics
        for k in record.NEVER_STOP:
            if not getattr(physics, k) > 0:
                raise ValueError(f"physics.{k}: must be positive in a match (else the balls "
                                 "never stop)")
        if three_foul and mode != "9ball":
            raise ValueError("three_foul: only for mode '9ball'")
        if eight_break not in EIGHT_BREAKS:
            raise ValueError(f"eight_break: must be one of {', '.join(EIGHT_BREAKS)}, "
                             f"not {eight_break!r}")
        if theme not in THEMES:
            raise ValueError(f"theme: must be one of {', '.join(THEMES)}, not {theme!r}")
        if not (isinstance(dt, float) and record.DT_RANGE[0] <= dt <= record.DT_RANGE[1]):
            raise ValueError(f"dt: must be from {record.DT_RANGE[0]:g} to "
                             f"{record.DT_RANGE[1]:g} seconds (what a replay accepts)")
        self.mode, self.table, self.physics = mode, table, physics
        self.frames, self.players, self.seed = frames, tuple(players), seed
        self.three_foul, self.theme, self.dt = bool(three_foul), theme, dt
        self.eight_break = eight_break
        self.levels = tuple(levels)
        self.rng = np.random.default_rng(seed)
        self.ids: list[str] = ["cue", *MODE_BALLS[mode]]
        n = len(self.ids)
        self.radius = np.full(n, BALL_RADIUS)
        self.mass = np.full(n, BALL_MASS)
        self.pos = np.zeros((n, 2))
        self.on_table = np.zeros(n, dtype=bool)
        self.scores = [0, 0]
        self.frame = -1  # new_frame makes it 0
        self.winner: int | None = None
        self.frame_winner: int | None = None
        self.history: list[dict] = []
        self.choices: list[dict] = []
        self.last_outcome: Outcome | None = None
        self._run: ShotRun | None = None
        self._undo: list[dict] = []
        self.new_frame()

    # ------------------------------------------------------------------------- views
    @property
    def shooter(self) -> int:
        return self.state.shooter

    @property
    def frame_over(self) -> bool:
        return self.frame_winner is not None

    def index(self, ball: str) -> int:
        return self.ids.index(ball)

    def balls_on_table(self) -> list[str]:
        return [b for b, on in zip(self.ids, self.on_table, strict=True) if on]

    def warning(self) -> str | None:
        """The WPA warning owed to the shooter before a shot that could be their third
        consecutive foul (9-ball with `three_foul`), else None."""
        s = self.state
        if not s.three_foul or s.fouls[s.shooter] < FOUL_LIMIT - 1 or self.frame_over:
            return None
        return (f"{self.players[s.shooter]} is on {count_word(FOUL_LIMIT - 1)} fouls: a "
                f"{ordinal(FOUL_LIMIT)} foul in a row loses the frame")

    def needs_call(self) -> bool:
        """True when the shooter must name a pocket: 8-ball, their group cleared, the 8 next."""
        s = self.state
        if s.mode != "8ball" or s.is_break or s.groups is None:
            return False
        own = GROUPS[s.groups[s.shooter]]
        return not any(self.on_table[self.index(b)] for b in own)

    # ------------------------------------------------------------------------- racks
    def _rack(self, breaker: int) -> None:
        spots = layout.rack_balls(self.mode, self.table, self.rng, BALL_RADIUS)
        for bid, (x, y) in spots.items():
            self.pos[self.index(bid)] = (x, y)
        self.on_table[:] = True
        self.state = State(mode=self.mode, shooter=breaker, is_break=True,
                           three_foul=self.three_foul)
        self.ball_in_hand: str | None = "anywhere" if self.mode == "practice" else "kitchen"
        self.option: str | None = None
        self.breaker = breaker

    def new_frame(self) -> None:
        """Rack the next frame. Breaks alternate: player 0 breaks frames 1, 3, ...; player 1
        frames 2, 4, ... (in practice player 0 always breaks)."""
        if self.winner is not None:
            raise ValueError("new_frame: the match is over")
        if self.frame >= 0 and not self.frame_over and self.mode != "practice":
            raise ValueError("new_frame: the frame is still being played")
        self.frame += 1
        self.frame_winner = None
        self._undo.clear()
        self._rack(0 if self.mode == "practice" else self.frame % 2)

    def rerack(self) -> None:
        """Practice: a fresh 15-ball rack (the shots so far stay in the record)."""
        if self.mode != "practice":
            raise ValueError("rerack: only in practice (8-ball re-racks are the 'rerack' option)")
        self._check_idle("rerack")
        self._undo.clear()
        self._rack(0)

    # --------------------------------------------------------------------- ball in hand
    def _others(self, skip: str = "cue") -> dict[str, tuple[float, float, float]]:
        return {b: (float(self.pos[i, 0]), float(self.pos[i, 1]), float(self.radius[i]))
                for i, b in enumerate(self.ids) if self.on_table[i] and b != skip}

    def placement_error(self, x: float, y: float) -> str | None:
        """Why the cue ball cannot be placed at (x, y) now, in words; None when it can."""
        if self.ball_in_hand is None:
            return "the cue ball is not in hand"
        c = self.index("cue")
        return layout.placement_error(self.table, x, y, float(self.radius[c]),
                                      self.ball_in_hand, self._others())

    def place_cue(self, x: float, y: float) -> None:
        """Put the cue ball at (x, y) (ball in hand); ValueError(the reason) when illegal."""
        self._check_idle("place_cue")
        why = self.placement_error(x, y)
        if why:
            raise ValueError(f"cue ball: {why}")
        c = self.index("cue")
        self.pos[c] = (float(x), float(y))

    # ------------------------------------------------------------------------- options
    def choose(self, option: str) -> None:
        """Answer the pending option: "rerack" or "accept" after an illegal 8-ball break (a
        re-rack is broken by the player choosing), "shoot" or "pass" after a 9-ball push-out
        (a pass hands the shot back to the player who pushed)."""
        self._check_idle("choose")
        if self.option is None:
            raise ValueError("option: there is nothing to choose now")
        allowed = OPTIONS[self.option]
        if option not in allowed:
            raise ValueError(f"option: must be {' or '.join(repr(a) for a in allowed)} "
                             f"(pending: {self.option}), not {option!r}")
        self.choices.append({"after_shot": len(self.history), "player": self.shooter,
                             "option": self.option, "choice": option})
        self._undo.clear()
        if option == "rerack":
            self._rack(self.shooter)
        elif option == "pass":
            self.state = replace(self.state, shooter=1 - self.shooter)
        self.option = None

    # --------------------------------------------------------------------------- shots
    def _check_idle(self, what: str) -> None:
        if self._run is not None:
            raise ValueError(f"{what}: a shot is still running (finish it first)")

    def _check_call(self, shot: Shot) -> tuple[str, str] | None:
        if shot.called is None:
            if self.needs_call():
                raise ValueError("called: name the pocket for the 8, e.g. ('8', 'foot_left')")
            return None
        if (not isinstance(shot.called, (tuple, list)) or len(shot.called) != 2):
            raise ValueError("called: must be (ball, pocket)")
        ball, pocket = str(shot.called[0]), str(shot.called[1])
        if ball not in self.ids or ball == "cue" or not self.on_table[self.index(ball)]:
            raise ValueError(f"called: no object ball {ball!r} on the table")
        if pocket not in self.table.hole_names:
            raise ValueError(f"called: unknown pocket {pocket!r} "
                             f"(use {', '.join(self.table.hole_names)})")
        if self.needs_call() and ball != "8":
            raise ValueError("called: the 8 is next: call the 8 and its pocket")
        return (ball, pocket)

    def begin(self, shot: Shot) -> ShotRun:
        """Start a shot from the current layout; ValueError (one line) when it cannot be
        played now or the shot is invalid."""
        self._check_idle("begin")
        if self.winner is not None:
            raise ValueError("begin: the match is over")
        if self.frame_over:
            raise ValueError("begin: the frame is over (call new_frame)")
        if self.option is not None:
            raise ValueError(f"begin: player {self.shooter} must first choose "
                             f"({' or '.join(OPTIONS[self.option])})")
        if not isinstance(shot, Shot):
            raise ValueError("shot: must be a Shot")
        called = self._check_call(shot)
        if shot.push_out and not (self.mode == "9ball" and self.state.push_out == "available"):
            raise ValueError("push_out: only on the shot after a legal 9-ball break")
        if self.ball_in_hand is not None:
            c = self.index("cue")
            why = self.placement_error(self.pos[c, 0], self.pos[c, 1])
            if why:
                raise ValueError(f"cue ball: {why}")
        state = replace(self.state, called=called,
                        push_out="declared" if shot.push_out else self.state.push_out)
        scene = self.scene_dict(state)
        try:
            run = ShotRun(self, shot, state, scene)
        except ValueError as e:  # the strike's own checks (speed, miscue, ...)
            raise ValueError(str(e)) from None
        self._run = run
        return run

    @property
    def running(self) -> ShotRun | None:
        """The shot begun and not yet finished, if any."""
        return self._run

    def abandon(self, run: ShotRun) -> None:
        """Forget a shot begun but never finished (the program ends mid-shot and cannot play
        it out): the match stays as it was before it, ready to save."""
        if run is self._run:
            self._run = None

    def scene_dict(self, state: State | None = None) -> dict:
        """The table now as a scene (`load_scene` form, balls at rest), with the game block
        of `state` (default: the match's state)."""
        state = self.state if state is None else state
        balls = [{"id": b, "x": float(self.pos[i, 0]), "y": float(self.pos[i, 1]),
                  "radius": float(self.radius[i]), "mass": float(self.mass[i])}
                 for i, b in enumerate(self.ids) if self.on_table[i]]
        return {"table": table_to_dict(self.table), "physics": self.physics.to_dict(),
                "balls": balls, "game": game_block(state)}

    def _snapshot(self) -> dict:
        return {"pos": self.pos.copy(), "on_table": self.on_table.copy(), "state": self.state,
                "ball_in_hand": self.ball_in_hand, "option": self.option,
                "last_outcome": self.last_outcome, "history": len(self.history),
                "choices": len(self.choices)}

    def _apply(self, run: ShotRun) -> Outcome:
        """Judge a finished shot, move the match on and record it (called by ShotRun)."""
        if run is not self._run:
            raise ValueError("finish: this shot does not belong to the match's current turn")
        eng = run.engine
        summary = summarize(eng.events[0], run.ids, is_break=run.state.is_break)
        outcome, new_state = judge(run.state, summary)
        snap = self._snapshot()
        rec = {"n": len(self.history) + 1, "frame": self.frame + 1, "player": run.state.shooter,
               "scene": run.scene_dict, "shot": run.shot.to_json(), "dt": run.dt,
               **record.results(run.scene, eng, run.dt),
               "outcome": outcome.to_json()}
        # The layout at rest; pocketed balls leave the table.
        self.pos[run.rows] = eng.pos[0]
        self.on_table[run.rows] = eng.state[0] != POCKETED
        for b in outcome.respot:
            self._respot(b)
        c = self.index("cue")
        if not self.on_table[c]:
            self.pos[c] = self.waiting_spot()
            self.on_table[c] = True
        self.state = new_state
        self.last_outcome = outcome
        self.ball_in_hand = outcome.ball_in_hand_area if outcome.ball_in_hand else None
        self.option = outcome.option
        if outcome.winner is not None:
            self.frame_winner = outcome.winner
            self.scores[outcome.winner] += 1
            if self.scores[outcome.winner] >= self.frames:
                self.winner = outcome.winner
        self.history.append(rec)
        self._undo.append(snap)
        if (self.eight_break == "rerack" and run.state.mode == "8ball" and run.state.is_break
                and "8" in outcome.respot and outcome.winner is None):
            # The variant where the 8 on the break means a fresh rack, broken by the same
            # player (the record keeps the referee's verdict; replays judge it the same way).
            breaker = run.state.shooter
            self._rack(breaker)
            outcome = replace(outcome, respot=(), ball_in_hand=True,
                              ball_in_hand_area="kitchen", next_shooter=breaker,
                              reason=f"{outcome.reason}; the 8 on the break: re-racked, "
                                     f"player {breaker} breaks again")
            self.last_outcome = outcome
        self._run = None
        return outcome

    def waiting_spot(self) -> tuple[float, float]:
        """Where the cue ball waits for a ball in hand: the head spot, or the nearest free point
        behind it on the long string (then in front of it)."""
        c = self.index("cue")
        return layout.cue_return_point(self.table, float(self.radius[c]), *self._others_arrays())

    def _others_arrays(self, skip: str = "cue") -> tuple[np.ndarray, np.ndarray]:
        keep = self.on_table.copy()
        keep[self.index(skip)] = False
        return self.pos[keep], self.radius[keep]

    def _respot(self, ball: str) -> None:
        i = self.index(ball)
        self.on_table[i] = False
        keep = self.on_table.copy()
        self.pos[i] = layout.respot_point(self.table, float(self.radius[i]), self.pos[keep],
                                          self.radius[keep])
        self.on_table[i] = True

    def take_back(self) -> None:
        """Practice: undo the last shot (the layout, state and record before it)."""
        if self.mode != "practice":
            raise ValueError("take_back: only in practice")
        self._check_idle("take_back")
        if not self._undo:
            raise ValueError("take_back: no shot to take back")
        snap = self._undo.pop()
        self.pos[:], self.on_table[:] = snap["pos"], snap["on_table"]  # same arrays: views stay
        self.state, self.ball_in_hand = snap["state"], snap["ball_in_hand"]
        self.option, self.last_outcome = snap["option"], snap["last_outcome"]
        del self.history[snap["history"]:]
        del self.choices[snap["choices"]:]

    # ---------------------------------------------------------------------- saving
    def to_json(self) -> dict:
        """The match as JSON: its settings, the current position and every shot's record
        (a replay file for `termpool replay`)."""
        if self._run is not None:
            raise ValueError("to_json: a shot is still running (finish it first)")
        return copy.deepcopy({
            "format": FORMAT,
            "version": VERSION,
            "match": {"mode": self.mode, "table": table_to_dict(self.table),
                      "physics": self.physics.to_dict(), "frames": self.frames,
                      "players": list(self.players), "seed": self.seed,
                      "three_foul": self.three_foul, "theme": self.theme, "dt": self.dt,
                      "eight_break": self.eight_break, "levels": list(self.levels)},
            "current": {
                "frame": self.frame, "breaker": self.breaker, "scores": list(self.scores),
                "winner": self.winner, "frame_winner": self.frame_winner,
                "ball_in_hand": self.ball_in_hand, "option": self.option,
                "state": state_to_json(self.state),
                "balls": [{"id": b, "x": float(self.pos[i, 0]), "y": float(self.pos[i, 1]),
                           "on_table": bool(self.on_table[i])}
                          for i, b in enumerate(self.ids)],
                "last_outcome": None if self.last_outcome is None else self.last_outcome.to_json(),
                "rng": self.rng.bit_generator.state,
            },
            "choices": self.choices,
            "shots": self.history,
        })

    @classmethod
    def from_json(cls, data: Any) -> Match:
        """A match saved by `to_json`, ready to go on; ValueError (one line naming the key)
        for a malformed one."""
        from .saved import load_match

        return load_match(cls, data)
