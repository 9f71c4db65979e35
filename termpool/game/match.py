"""A match: whose turn, ball in hand, options, frames and the record.

See the package docstring (`termpool.game`) for the API and the choices made. The balls
between shots are `balls.Balls`; a shot's record is made by `record.shot_record`; the saved
form is `saved`'s.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from termpool.physics.engine import POCKETED
from termpool.physics.params import Physics
from termpool.physics.results import DT  # the fixed engine step of every shot (recorded with it)
from termpool.physics.table import Table
from termpool.rules.codec import game_block
from termpool.rules.codes import Choice, Option
from termpool.rules.common import GROUPS, MODE_BALLS, Outcome, State
from termpool.rules.events import summarize
from termpool.rules.referee import judge
from termpool.rules.words import FOUL_LIMIT, RECORD, Voice
from termpool.scene import table_to_dict

from . import record, saved
from .balls import Balls
from .players import Player
from .settings import check_settings
from .turn import Shot, ShotRun


class Match:
    """Two players (one in practice), frames to win, the balls between shots and the record."""

    def __init__(self, mode: str = "8ball", *, table: str | Table = "9ft", frames: int = 1,
                 players: tuple[str | Player, str | Player] = ("Player 1", "Player 2"),
                 seed: int = 0, physics: Physics | None = None, three_foul: bool = False,
                 theme: str = "standard", dt: float = DT, eight_break: str = "respot") -> None:
        s = check_settings(mode, table, frames, players, seed, physics, three_foul, theme, dt,
                           eight_break)
        self.mode, self.table, self.physics, self.frames = s.mode, s.table, s.physics, s.frames
        self.seats = s.players  # the players themselves (`players.Player`)
        self.players = tuple(p.name for p in s.players)
        self.levels = tuple(p.level for p in s.players)
        self.seed, self.three_foul, self.theme, self.dt = s.seed, s.three_foul, s.theme, s.dt
        self.eight_break = s.eight_break
        self.rng = np.random.default_rng(seed)
        self.balls = Balls(self.table, ["cue", *MODE_BALLS[mode]])
        self.scores = [0, 0]
        self.frame = -1  # new_frame makes it 0
        self.winner: int | None = None
        self.frame_winner: int | None = None
        self.conceded: int | None = None  # the player who left, giving the other the match
        self.history: list[dict] = []
        self.choices: list[dict] = []
        self.last_outcome: Outcome | None = None
        self.state = State(mode=mode)  # the rack's, from new_frame
        self.ball_in_hand: str | None = None
        self.option: Option | None = None
        self.breaker = 0
        self._run: ShotRun | None = None
        self._undo: list[dict] = []
        self.new_frame()

    @classmethod
    def from_json(cls, data: Any) -> Match:
        """A match saved by `to_json`, ready to go on; ValueError (one line naming the key)
        for a malformed one."""
        return saved.load_match(cls, data)

    def resume(self, where: saved.Position, choices: list[dict], history: list[dict],
               last: Outcome | None) -> Match:
        """This match (just made from a saved match's settings) at the saved position, with
        its options answered, its shot records and the verdict on the last shot."""
        self.balls.pos[:], self.balls.on_table[:] = where.pos, where.on_table
        self.state, self.frame, self.breaker = where.state, where.frame, where.breaker
        self.scores, self.winner, self.frame_winner = where.scores, where.winner, where.frame_winner
        self.ball_in_hand, self.option = where.ball_in_hand, where.option
        self.rng.bit_generator.state = where.rng
        self.choices, self.history, self.last_outcome = choices, history, last
        return self

    def to_json(self) -> dict:
        """The match as JSON: its settings, the position now and every shot's record (a
        replay file for `termpool replay`)."""
        self._check_idle("to_json")
        return saved.match_json(self)

    # ------------------------------------------------------------------------- views
    ids = property(lambda self: self.balls.ids)
    radius = property(lambda self: self.balls.radius)
    mass = property(lambda self: self.balls.mass)
    pos = property(lambda self: self.balls.pos)
    on_table = property(lambda self: self.balls.on_table)

    @property
    def shooter(self) -> int:
        return self.state.shooter

    @property
    def frame_over(self) -> bool:
        return self.frame_winner is not None

    def index(self, ball: str) -> int:
        return self.balls.index(ball)

    def balls_on_table(self) -> list[str]:
        return self.balls.present()

    def warning(self) -> int | None:
        """The shooter, when they are owed the WPA warning before a shot that could be their
        last foul in a row (9-ball with `three_foul`: `words.foul_warning` says it); else
        None."""
        s = self.state
        if not s.three_foul or s.fouls[s.shooter] < FOUL_LIMIT - 1 or self.frame_over:
            return None
        return s.shooter

    def needs_call(self) -> bool:
        """True when the shooter must name a pocket: 8-ball, their group cleared, the 8 next."""
        s = self.state
        if s.mode != "8ball" or s.is_break or s.groups is None:
            return False
        own = GROUPS[s.groups[s.shooter]]
        return not any(self.on_table[self.index(b)] for b in own)

    # ------------------------------------------------------------------------- racks
    def _rack(self, breaker: int) -> None:
        self.balls.rack(self.mode, self.rng)
        self.state = State(mode=self.mode, shooter=breaker, is_break=True,
                           three_foul=self.three_foul,
                           eight_break=self.eight_break if self.mode == "8ball" else "respot")
        self.ball_in_hand = "anywhere" if self.mode == "practice" else "kitchen"
        self.option = None
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
        """Practice: a fresh 15-ball rack (the shots so far stay in the record). `take_back`
        puts the balls back as they were."""
        if self.mode != "practice":
            raise ValueError("rerack: only in practice (8-ball re-racks are the 'rerack' option)")
        self._check_idle("rerack")
        self._undo.append(self._snapshot("rerack"))
        self._rack(0)

    # --------------------------------------------------------------------- ball in hand
    def placement_error(self, x: float, y: float, v: Voice = RECORD) -> str | None:
        """Why the cue ball cannot be placed at (x, y) now, in words (pockets named in the
        voice `v`); None when it can."""
        if self.ball_in_hand is None:
            return "the cue ball is not in hand"
        return self.balls.placement_error(x, y, self.ball_in_hand, v)

    def place_cue(self, x: float, y: float) -> None:
        """Put the cue ball at (x, y) (ball in hand); ValueError(the reason) when illegal."""
        self._check_idle("place_cue")
        why = self.placement_error(x, y)
        if why:
            raise ValueError(f"cue ball: {why}")
        self.pos[self.index("cue")] = (float(x), float(y))

    def waiting_spot(self) -> tuple[float, float]:
        """Where the cue ball waits for a ball in hand (`Balls.waiting_spot`)."""
        return self.balls.waiting_spot()

    # ------------------------------------------------------------------------- options
    def choose(self, choice: str) -> None:
        """Answer the pending option: "rerack" or "accept" after an illegal 8-ball break (a
        re-rack is broken by the player choosing), "shoot" or "pass" after a 9-ball push-out
        (a pass hands the shot back to the player who pushed)."""
        self._check_idle("choose")
        if self.option is None:
            raise ValueError("option: there is nothing to choose now")
        allowed = Option(self.option).choices
        if choice not in allowed:
            raise ValueError(f"option: must be {' or '.join(repr(a.value) for a in allowed)} "
                             f"(pending: {self.option}), not {choice!r}")
        self.choices.append({"after_shot": len(self.history), "player": self.shooter,
                             "option": str(self.option), "choice": str(choice)})
        self._undo.clear()
        if choice == Choice.RERACK:
            self._rack(self.shooter)
        elif choice == Choice.PASS:
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
            raise ValueError(f"begin: {self.players[self.shooter]} must first choose "
                             f"({' or '.join(Option(self.option).choices)})")
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
        try:
            run = ShotRun(shot, state, self.scene_dict(state), self.ids, self.dt, self.settle)
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
        return {"table": table_to_dict(self.table), "physics": self.physics.to_dict(),
                "balls": self.balls.scene_balls(), "game": game_block(state)}

    def settle(self, run: ShotRun) -> Outcome:
        """Judge a shot run to rest, record it and move the match on (`ShotRun.finish` calls
        this once)."""
        if run is not self._run:
            raise ValueError("finish: this shot does not belong to the match's current turn")
        eng = run.engine
        summary = summarize(eng.log[0], run.ids, is_break=run.state.is_break)
        outcome, new_state = judge(run.state, summary)
        self._undo.append(self._snapshot("shot"))
        self.history.append(record.shot_record(run, outcome, len(self.history) + 1,
                                               self.frame + 1))
        if outcome.rerack:  # a fresh rack, broken by `next_shooter`: the new state is its
            self._rack(outcome.next_shooter)
        else:
            self.balls.settle(run.rows, eng.pos[0], eng.state[0] != POCKETED, outcome.respot)
            self.ball_in_hand = outcome.ball_in_hand_area if outcome.ball_in_hand else None
            self.option = outcome.option
        self.state = new_state
        self.last_outcome = outcome
        if outcome.winner is not None:
            self.frame_winner = outcome.winner
            self.scores[outcome.winner] += 1
            if self.scores[outcome.winner] >= self.frames:
                self.winner = outcome.winner
        self._run = None
        return outcome

    # ------------------------------------------------------------------------- take back
    def _snapshot(self, undoes: str) -> dict:
        """What `take_back` restores before a shot or a re-rack (`undoes`: "shot", "rerack")."""
        return {"undoes": undoes, "balls": self.balls.snapshot(), "state": self.state,
                "ball_in_hand": self.ball_in_hand, "option": self.option,
                "last_outcome": self.last_outcome, "history": len(self.history),
                "choices": len(self.choices)}

    def concede(self, player: int) -> None:
        """`player` leaves a match before its end (online: they quit it): the other wins it,
        the frames as they stand. Nothing changes once the match is over."""
        if player not in (0, 1):
            raise ValueError("concede: player must be 0 or 1")
        self._check_idle("concede")
        if self.winner is None:
            self.winner, self.conceded = 1 - player, player

    def take_back(self) -> str:
        """Practice: undo the last shot or re-rack (the layout, state and record before it).
        Returns what it undid: "shot" or "rerack"."""
        if self.mode != "practice":
            raise ValueError("take_back: only in practice")
        self._check_idle("take_back")
        if not self._undo:
            raise ValueError("take_back: no shot to take back")
        snap = self._undo.pop()
        self.balls.restore(snap["balls"])
        self.state, self.ball_in_hand = snap["state"], snap["ball_in_hand"]
        self.option, self.last_outcome = snap["option"], snap["last_outcome"]
        del self.history[snap["history"]:]
        del self.choices[snap["choices"]:]
        return snap["undoes"]
