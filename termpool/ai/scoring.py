"""Scoring simulated tables: the referee's verdict on each, the chance the shot does in play
what it did in the batch, and what it leaves the next player."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from termpool.physics.engine import POCKETED
from termpool.physics.events import EventKind
from termpool.physics.table import Table
from termpool.rules.codes import Aim, PlanNote
from termpool.rules.common import State, legal_targets
from termpool.rules.events import summarize
from termpool.rules.referee import judge

from . import geometry as geo
from .balls import OnTable
from .candidates import Cands

WIN, LOSS, CONTINUE, PASS, FOUL = 1000.0, -1000.0, 300.0, 0.0, -250.0
MISS_LEAVE = 0.7  # what a missed pot usually leaves the opponent, as a leave value (0..1)
LEAVE_SIGMA = 0.5  # degrees: the aim error a table left behind is valued with, for the
# shooter's next shot and for the opponent alike (a club player's, whatever the level: an
# error as small as a pro's would call every open shot certain, and tell no leave from another)
FLUKE = 0.3  # chance a legal pot the sim found by a kiss or a combination happens in play




def _call(state: State, targets: list[str], t: OnTable, cands: Cands, b: int, summary,
          pockets: geo.Pockets) -> tuple[str, str] | None:
    """The call for candidate b: only for the 8 when it is the legal target. The pocket the
    simulation drops it in, else the pocket aimed at, else the one nearest the 8."""
    if state.mode != "8ball" or targets != ["8"] or not pockets.names:
        return None
    if "8" in summary.pocketed:
        return ("8", summary.pocketed["8"])
    if cands.pocket[b] >= 0:
        return ("8", pockets.names[cands.pocket[b]])
    p8 = t.pos[t.ids.index("8")]
    k = int(np.argmin(np.linalg.norm(pockets.aim - p8, axis=1)))
    return ("8", pockets.names[k])


def score_tables(state, targets, t, cands, eng, table, pockets, lv,
                 sampled: bool = False) -> tuple[np.ndarray, list, list, list]:
    """Score every simulated table; returns (scores, calls, notes: (note, sees) pairs, see
    `Plan`, flukes). With `sampled`, the tables are samples of aim error and every pot aimed
    at counts in full. `flukes` holds, for a shot that keeps the table by a pot it did not
    aim at (a kiss, a bank: scored at FLUKE), the (ball, pocket) that dropped, else None."""
    B, n = eng.B, eng.N
    alive = eng.state != POCKETED
    final = eng.pos
    scores = np.zeros(B)
    calls: list = []
    notes: list = []
    sees: list = []
    flukes: list = []
    leave_for: list[tuple[int, float, State]] = []  # (table, pot chance or -1, next state)
    practice = state.mode == "practice"
    # A pot that misses in play: the opponent gets the table (in practice, nobody does).
    miss = 0.0 if practice else -lv.leave * MISS_LEAVE
    foul = FOUL - (0.0 if practice else lv.leave)  # ball in hand: the best table to leave
    for b in range(B):
        summary = summarize(eng.log[b], t.ids, is_break=state.is_break)
        called = _call(state, targets, t, cands, b, summary, pockets)
        out, nxt = judge(replace(state, called=called), summary)
        calls.append(called)
        tgt = t.ids[cands.target[b]] if cands.target[b] >= 0 else None
        aimed = pockets.names[cands.pocket[b]] if cands.pocket[b] >= 0 else None
        potted = summary.object_pocketed
        # How likely the shot is to do in play what it did here: a pot aimed at a pocket
        # by its chance, the break as it is, anything else (a kiss, a combination) a fluke.
        sunk = t.ids[cands.via[b]] if cands.via[b] >= 0 else tgt  # the ball aimed at a pocket
        intended = sunk is not None and aimed is not None and summary.pocketed.get(sunk) == aimed
        p = 1.0 if cands.kind[b] == "break" else (1.0 if sampled else cands.chance[b]) \
            if intended else FLUKE
        kept = out.winner == state.shooter or (out.continue_turn and bool(potted))
        fluke = kept and bool(potted) and not intended and cands.kind[b] != "break"
        ball = next((x for x in potted if x in targets), potted[0]) if fluke else None
        flukes.append((ball, summary.pocketed[ball]) if fluke else None)
        if out.winner is not None:
            scores[b] = p * WIN + (1 - p) * miss if out.winner == state.shooter else LOSS
            notes.append(PlanNote(Aim.VERDICT, said=tuple(out.said)))
            sees.append("win" if out.winner == state.shooter else "loss")
        elif out.foul is not None or (practice and out.ball_in_hand):
            scores[b] = foul
            notes.append(PlanNote(Aim.VERDICT, said=tuple(out.said), foul=out.foul is not None))
            sees.append("foul")
        elif out.continue_turn and potted:
            scores[b] = p * CONTINUE + (1 - p) * miss
            leave_for.append((b, p, nxt))
            if intended and cands.kind[b] == "combo":
                notes.append(PlanNote(Aim.COMBO, ball=tgt, sunk=sunk, pocket=aimed))
            elif intended:
                notes.append(PlanNote(Aim.POT, ball=tgt, pocket=aimed))
            else:
                notes.append(PlanNote(Aim.FLUKE, balls=tuple(potted),
                                      by_break=cands.kind[b] == "break"))
            sees.append("pot")
        else:
            scores[b] = PASS
            if not practice:  # in practice the same player shoots again: nothing to deny
                leave_for.append((b, -1.0, nxt))
            aim = {"break": Aim.BREAK, "safety": Aim.SAFETY, "kick": Aim.KICK}.get(
                cands.kind[b], Aim.TRY)
            notes.append(PlanNote(aim, ball=tgt, sunk=sunk, pocket=aimed) if aim is Aim.TRY
                         else PlanNote(aim, ball=tgt))
            sees.append("pass")
    if leave_for:
        rows = [b for b, _, _ in leave_for]
        tmask = np.zeros((len(rows), n), bool)
        for r, (b, _, nxt) in enumerate(leave_for):
            present = [t.ids[k] for k in range(n) if alive[b, k]]
            nxt_t = legal_targets(nxt, present) if "cue" in present else []
            tmask[r] = [bid in nxt_t for bid in t.ids]
        cue_alive = alive[rows, t.cue]
        chance, _ = geo.pot_chances(final[rows, t.cue], final[rows], alive[rows], tmask,
                                    t.radius, t.cue, pockets, table, LEAVE_SIGMA)
        value = geo.leave_value(chance)
        now = _opponent_now(state, t, pockets, table)
        for r, (b, p, _) in enumerate(leave_for):
            if not cue_alive[r]:
                continue
            # After a pot (p >= 0): the shooter's next shot, as likely as the pot itself.
            # After the turn passes (p < 0): the opponent's. A safety that leaves the opponent
            # no less than the table has now hides nothing: it counts as leaving them the
            # best table there is (a pot with any chance then goes first).
            if p >= 0:
                scores[b] += p * lv.position * value[r]
            elif cands.kind[b] == "safety" and value[r] >= now:
                scores[b] -= lv.leave
            else:
                scores[b] -= lv.leave * value[r]
    # The scratches a pot's exact stroke escaped in the sim: more likely the more cushions
    # its cue ball, struck for position, met. Scratching as the 8 drops loses in 8-ball.
    # (A safety's cue ball is struck softly, and needs its cushion.)
    rails = cue_cushions(eng.log, t.cue)
    lose = LOSS if state.mode == "8ball" else foul
    for b in range(B):
        if sees[b] in ("win", "pot") and rails[b]:
            risk = 1.0 - (1.0 - lv.scratch) ** rails[b]
            scores[b] = (1.0 - risk) * scores[b] + risk * (lose if sees[b] == "win" else foul)
    return scores, calls, list(zip(notes, sees, strict=True)), flukes


def cue_cushions(logs: list[list], cue: int) -> list[int]:
    """How many cushions the cue ball met on each table."""
    return [sum(ev.kind is EventKind.CUSHION and ev.balls[0] == cue for ev in log)
            for log in logs]


def _opponent_now(state: State, t: OnTable, pockets: geo.Pockets, table: Table) -> float:
    """The leave value of the table as it lies, for the opponent (their legal balls, the cue
    ball where it is)."""
    opp = replace(state, shooter=state.opponent)
    tmask = np.array([[b in legal_targets(opp, t.ids) for b in t.ids]])
    chance, _ = geo.pot_chances(t.pos[t.cue][None], t.pos[None], np.ones((1, len(t.ids)), bool),
                                tmask, t.radius, t.cue, pockets, table, LEAVE_SIGMA)
    return float(geo.leave_value(chance)[0])
