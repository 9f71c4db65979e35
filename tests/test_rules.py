"""Rules: shot summaries, 8-ball, 9-ball, practice, the scene `game` block and the
referee in `termpool sim`.

Most cases are synthetic event lists written as short scripts (see `shot`); a few are real
simulated shots set up so that they do what they say.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from termpool.physics.engine import Engine
from termpool.rules import codec, eight, nine, practice, words
from termpool.rules.codec import state_from_game
from termpool.rules.codes import Choice, Option, Why
from termpool.rules.common import SOLIDS, STRIPES, Outcome, State
from termpool.rules.events import ShotSummary, summarize
from termpool.rules.referee import judge, load_game_scene, referee
from termpool.scene import SceneError

ROOT = Path(__file__).resolve().parent.parent
IDS = ["cue", *(str(n) for n in range(1, 16))]


def events(*steps: str) -> list[dict]:
    """Engine-style events from a script, one step per event, 0.1 s apart:
    "cue-3" the cue ball hits the 3; "3|" the 3 hits a rail ("3|jaw", "3|tip" for the other
    cushion features); "3>foot_left" the 3 drops into the foot-left pocket."""
    out = []
    for k, step in enumerate(steps):
        t = 0.1 * (k + 1)
        if "-" in step:
            a, b = step.split("-")
            out.append({"t": t, "type": "ball_ball", "i": [IDS.index(a), IDS.index(b)]})
        elif "|" in step:
            b, feature = step.split("|")
            out.append({"t": t, "type": "cushion", "i": [IDS.index(b)],
                        "feature": feature or "rail"})
        elif ">" in step:
            b, pocket = step.split(">")
            out.append({"t": t, "type": "pocket", "i": [IDS.index(b)], "pocket": pocket})
        else:
            raise ValueError(step)
    return out


def shot(*steps: str, is_break: bool = False) -> ShotSummary:
    return summarize(events(*steps), IDS, is_break=is_break)


def cleared(group: str) -> tuple[str, ...]:
    return SOLIDS if group == "solids" else STRIPES


# ----------------------------------------------------------------------------- summaries


def test_summary_of_nothing() -> None:
    s = summarize([], IDS)
    assert s.first_contact is None and s.cushions_after_contact == 0 and s.rail_balls == ()
    assert s.pocketed == {} and not s.scratch and s.off_table == () and not s.is_break


def test_summary_fields() -> None:
    s = shot("cue|", "cue-3", "3-5", "5|jaw", "cue|", "5|tip", "3>foot_left", "cue>side_left",
             is_break=True)
    assert s.first_contact == "3"
    assert s.cushions_after_contact == 3  # the cue ball's rail before contact does not count
    assert s.rail_balls == ("5", "cue") and s.object_rail_balls == ["5"]
    assert list(s.pocketed.items()) == [("3", "foot_left"), ("cue", "side_left")]
    assert s.object_pocketed == ["3"] and s.scratch and s.is_break
    assert s.off_table == ()  # the engine never lets a ball leave the table


def test_first_contact_ignores_object_ball_collisions() -> None:
    # A ball set rolling by hand hits another before the cue ball touches anything.
    s = shot("4-5", "cue-2")
    assert s.first_contact == "2"


def test_summary_reads_sim_output_and_sorts_by_time() -> None:
    evs = events("cue-1", "1|", "1>foot_right")
    as_sim = [{"t": e["t"], "type": e["type"], "ids": [IDS[i] for i in e["i"]],
               **{k: e[k] for k in ("pocket", "feature") if k in e}} for e in evs]
    assert summarize(as_sim[::-1], IDS) == summarize(evs, IDS)


# ----------------------------------------------------------------------------- 8-ball


def state8(**kw) -> State:
    kw.setdefault("mode", "8ball")
    return State(**kw)


BREAK = state8(is_break=True)

# (name, summary, expected fields of the outcome)
BREAK_CASES = [
    ("pot", shot("cue-1", "1-2", "2>foot_left", is_break=True),
     dict(foul=None, next_shooter=0, continue_turn=True, groups=None, ball_in_hand=False)),
    ("four rails", shot("cue-1", "2|", "3|", "4|", "5|", is_break=True),
     dict(foul=None, next_shooter=1, continue_turn=False, option=None)),
    ("three rails", shot("cue-1", "2|", "3|", "4|", "cue|", is_break=True),
     dict(foul="illegal_break", next_shooter=1, ball_in_hand=False, option="rerack_or_accept")),
    ("same ball twice", shot("cue-1", "2|", "2|", "3|", "4|", is_break=True),
     dict(foul="illegal_break", option="rerack_or_accept")),
    ("missed the rack", shot("cue|", is_break=True),
     dict(foul="illegal_break", next_shooter=1)),
    ("scratch", shot("cue-1", "3>side_left", "cue>head_left", is_break=True),
     dict(foul="scratch", next_shooter=1, ball_in_hand=True, ball_in_hand_area="kitchen",
          groups=None, respot=())),
    ("8 on the break", shot("cue-1", "8>foot_left", is_break=True),
     dict(foul=None, next_shooter=0, continue_turn=True, respot=("8",), winner=None)),
    ("8 and scratch", shot("cue-1", "8>foot_left", "cue>side_right", is_break=True),
     dict(foul="scratch", next_shooter=1, ball_in_hand_area="kitchen", respot=("8",),
          winner=None)),
    ("illegal and scratch", shot("cue-1", "2|", "cue>head_right", is_break=True),
     dict(foul="scratch", fouls=("scratch", "illegal_break"), option="rerack_or_accept",
          ball_in_hand=True, ball_in_hand_area="kitchen")),
    ("cue off the table", ShotSummary(first_contact="1", pocketed={"4": "foot_left"},
                                      off_table=("cue",), is_break=True),
     dict(foul="off_table", ball_in_hand_area="kitchen", next_shooter=1)),
]


def check(out: Outcome, expect: dict) -> None:
    for key, val in expect.items():
        assert getattr(out, key) == val, (key, out)
    assert isinstance(out.reason, str) and out.reason
    assert out.ball_in_hand == (out.ball_in_hand_area is not None)


@pytest.mark.parametrize("name, summary, expect", BREAK_CASES, ids=[c[0] for c in BREAK_CASES])
def test_eight_break(name: str, summary: ShotSummary, expect: dict) -> None:
    out, new = eight.judge(BREAK, summary)
    check(out, expect)
    assert new.is_break is False and new.groups is None and new.shooter == out.next_shooter
    assert "8" not in new.pocketed  # re-spotted
    assert out.winner is None


def test_eight_break_balls_stay_down_and_reasons() -> None:
    out, new = eight.judge(BREAK, shot("cue-1", "3>side_left", "cue>head_left", is_break=True))
    assert new.pocketed == ("3",) and new.fouls == (1, 0)
    assert "behind the head string" in out.reason
    out, _ = eight.judge(BREAK, shot("cue-1", "2|", is_break=True))
    assert "illegal break" in out.reason and "re-racked" in out.reason
    out, _ = eight.judge(BREAK, shot("cue-1", "8>foot_left", is_break=True))
    assert "re-spotted" in out.reason


OPEN = state8()
SOLIDS0 = state8(groups={0: "solids", 1: "stripes"})
STRIPES1 = state8(shooter=1, groups={0: "solids", 1: "stripes"})
ON_EIGHT = state8(groups={0: "solids", 1: "stripes"}, pocketed=SOLIDS)
ON_EIGHT_CALLED = state8(groups={0: "solids", 1: "stripes"}, pocketed=SOLIDS,
                         called=("8", "foot_left"))
ONE_LEFT = state8(groups={0: "solids", 1: "stripes"}, pocketed=SOLIDS[:-1],
                  called=("8", "foot_left"))
SOLIDS_STRIPES = {0: "solids", 1: "stripes"}
STRIPES_SOLIDS = {0: "stripes", 1: "solids"}

SHOT_CASES = [
    # open table
    ("open: pot a solid", OPEN, shot("cue-3", "3>foot_left"),
     dict(foul=None, next_shooter=0, continue_turn=True, groups=SOLIDS_STRIPES)),
    ("open: pot a stripe", OPEN, shot("cue-12", "12>side_right"),
     dict(foul=None, next_shooter=0, groups=STRIPES_SOLIDS)),
    ("open: first pocketed decides", OPEN, shot("cue-2", "2-10", "10>foot_left", "2>head_left"),
     dict(foul=None, next_shooter=0, groups=STRIPES_SOLIDS)),
    ("open: combination across groups", OPEN, shot("cue-4", "4-13", "13>foot_right"),
     dict(foul=None, groups=STRIPES_SOLIDS)),
    ("open: the 8 first", OPEN, shot("cue-8", "8-3", "3>foot_left"),
     dict(foul="wrong_ball_first", next_shooter=1, ball_in_hand=True,
          ball_in_hand_area="anywhere", groups=None)),
    ("open: no hit", OPEN, shot("cue|", "cue|"),
     dict(foul="no_hit", next_shooter=1, ball_in_hand=True)),
    ("open: no rail", OPEN, shot("cue-5"), dict(foul="no_rail", next_shooter=1)),
    ("open: cue ball to a rail counts", OPEN, shot("cue-5", "cue|"),
     dict(foul=None, next_shooter=1, ball_in_hand=False, groups=None)),
    ("open: a jaw is a cushion", OPEN, shot("cue-5", "5|jaw"), dict(foul=None)),
    ("open: miss", OPEN, shot("cue-5", "5|"),
     dict(foul=None, next_shooter=1, continue_turn=False, groups=None)),
    ("open: pot then scratch", OPEN, shot("cue-3", "3>foot_left", "cue>foot_right"),
     dict(foul="scratch", next_shooter=1, ball_in_hand_area="anywhere", groups=None)),
    ("open: the 8 goes in", OPEN, shot("cue-3", "3-8", "8>side_left"),
     dict(winner=1, foul=None)),
    ("object ball off the table", OPEN,
     ShotSummary(first_contact="3", rail_balls=("3",), off_table=("3",)),
     dict(foul="off_table", next_shooter=1, ball_in_hand=True)),
    ("cue ball off the table", OPEN,
     ShotSummary(first_contact="3", rail_balls=("3",), off_table=("cue",)),
     dict(foul="off_table", next_shooter=1, ball_in_hand_area="anywhere")),
    # groups assigned
    ("solids: wrong group first", SOLIDS0, shot("cue-11", "11-3", "3>foot_left"),
     dict(foul="wrong_ball_first", next_shooter=1, ball_in_hand=True, groups=SOLIDS_STRIPES)),
    ("solids: own ball", SOLIDS0, shot("cue-3", "3>foot_left"),
     dict(foul=None, next_shooter=0, continue_turn=True)),
    ("solids: only an opponent's ball", SOLIDS0, shot("cue-3", "3-12", "12>foot_left", "3|"),
     dict(foul=None, next_shooter=1, continue_turn=False)),
    ("solids: own and opponent's", SOLIDS0, shot("cue-3", "3-12", "12>foot_left", "3>side_left"),
     dict(foul=None, next_shooter=0)),
    ("stripes: player 1 pots own", STRIPES1, shot("cue-11", "11>head_left"),
     dict(foul=None, next_shooter=1, continue_turn=True)),
    ("stripes: player 1 hits a solid", STRIPES1, shot("cue-2", "2|"),
     dict(foul="wrong_ball_first", next_shooter=0, ball_in_hand=True)),
    ("cleared: the 8 first is legal", ON_EIGHT, shot("cue-8", "8|"),
     dict(foul=None, next_shooter=1)),
    ("cleared: a stripe first", ON_EIGHT, shot("cue-9", "9|"),
     dict(foul="wrong_ball_first", next_shooter=1)),
    # the 8
    ("8 in the called pocket", ON_EIGHT_CALLED, shot("cue-8", "8>foot_left"),
     dict(winner=0, foul=None, continue_turn=False)),
    ("8 in the wrong pocket", ON_EIGHT_CALLED, shot("cue-8", "8>foot_right"),
     dict(winner=1, foul=None)),
    ("8 not called", ON_EIGHT, shot("cue-8", "8>foot_left"), dict(winner=1)),
    ("8 with a scratch", ON_EIGHT_CALLED, shot("cue-8", "8>foot_left", "cue>foot_left"),
     dict(winner=1, foul="scratch")),
    ("8 with the wrong ball first", ON_EIGHT_CALLED, shot("cue-10", "10-8", "8>foot_left"),
     dict(winner=1, foul="wrong_ball_first")),
    ("8 with the last solid", ONE_LEFT, shot("cue-7", "7>side_left", "7-8", "8>foot_left"),
     dict(winner=1, foul=None)),
    ("8 early", SOLIDS0, shot("cue-2", "2-8", "8>foot_left"), dict(winner=1)),
    ("8 off the table", ON_EIGHT_CALLED,
     ShotSummary(first_contact="8", rail_balls=("8",), off_table=("8",)), dict(winner=1)),
]


@pytest.mark.parametrize("name, state, summary, expect", SHOT_CASES,
                         ids=[c[0] for c in SHOT_CASES])
def test_eight_shots(name: str, state: State, summary: ShotSummary, expect: dict) -> None:
    out, new = eight.judge(state, summary)
    check(out, expect)
    assert out.groups == new.groups
    if out.winner is None:
        assert new.shooter == out.next_shooter
        assert out.continue_turn == (out.next_shooter == state.shooter)
        assert (out.foul is not None) == out.ball_in_hand  # every foul gives ball in hand
    else:
        assert out.winner in (0, 1)
        assert ("loses" if out.winner != state.shooter else "wins") in out.reason


def test_eight_state_bookkeeping() -> None:
    out, new = eight.judge(OPEN, shot("cue-3", "3>foot_left", "3-4", "4>side_left"))
    assert new.pocketed == ("3", "4") and new.groups == {0: "solids", 1: "stripes"}
    assert new.called is None and not new.is_break
    # A foul counts for the shooter and stays down; a legal shot resets the count.
    st = state8(fouls=(1, 2), shooter=1)
    _, new = eight.judge(st, shot("cue-3", "3|", "cue>foot_left"))
    assert new.fouls == (1, 3) and new.shooter == 0
    _, new = eight.judge(st, shot("cue-3", "3|"))
    assert new.fouls == (1, 0)
    # The state given is never changed.
    assert OPEN == state8()
    # Balls pocketed on a foul stay down but do not assign the groups.
    out, new = eight.judge(OPEN, shot("cue-8", "8-3", "3>foot_left"))
    assert new.pocketed == ("3",) and new.groups is None


def test_eight_reasons_in_words() -> None:
    out, _ = eight.judge(SOLIDS0, shot("cue-11", "11|"))
    assert "11" in out.reason and "solids" in out.reason and "ball in hand" in out.reason
    out, _ = eight.judge(ON_EIGHT_CALLED, shot("cue-8", "8>foot_right"))
    assert "foot_right" in out.reason and "foot_left" in out.reason
    out, _ = eight.judge(SOLIDS0, shot("cue-2", "2-8", "8>foot_left"))
    assert "early" in out.reason


def test_eight_rejects_other_modes() -> None:
    with pytest.raises(ValueError):
        eight.judge(State(mode="9ball"), shot("cue-1"))


# ----------------------------------------------------------------------------- 9-ball


def state9(**kw) -> State:
    kw.setdefault("mode", "9ball")
    return State(**kw)


NINE = state9()
NINE_BREAK = state9(is_break=True)
PUSH = state9(push_out="declared")

NINE_CASES = [
    ("lowest first, pot", NINE, shot("cue-1", "1-4", "4>side_left"),
     dict(foul=None, next_shooter=0, continue_turn=True)),
    ("lowest first, miss", NINE, shot("cue-1", "1|"), dict(foul=None, next_shooter=1)),
    ("not the lowest", NINE, shot("cue-2", "2>foot_left"),
     dict(foul="wrong_ball_first", next_shooter=1, ball_in_hand=True,
          ball_in_hand_area="anywhere")),
    ("lowest after the 1 is down", state9(pocketed=("1",)), shot("cue-2", "2|"),
     dict(foul=None, next_shooter=1)),
    ("no hit", NINE, shot("cue|"), dict(foul="no_hit", ball_in_hand=True)),
    ("no rail", NINE, shot("cue-1"), dict(foul="no_rail", ball_in_hand=True)),
    ("scratch", NINE, shot("cue-1", "1|", "cue>foot_left"),
     dict(foul="scratch", ball_in_hand_area="anywhere", next_shooter=1)),
    ("the 9 on a combination", NINE, shot("cue-1", "1-9", "9>foot_left"),
     dict(winner=0, foul=None)),
    ("the 9 on a foul", NINE, shot("cue-3", "3-9", "9>foot_left"),
     dict(winner=None, foul="wrong_ball_first", respot=("9",), next_shooter=1)),
    ("the 9 and a scratch", NINE, shot("cue-1", "1-9", "9>foot_left", "cue>side_left"),
     dict(winner=None, foul="scratch", respot=("9",))),
    ("the 9 off the table", NINE,
     ShotSummary(first_contact="1", rail_balls=("9",), off_table=("9",)),
     dict(winner=None, foul="off_table", respot=("9",))),
    # break
    ("break: pot", NINE_BREAK, shot("cue-1", "1-5", "5>foot_left", is_break=True),
     dict(foul=None, next_shooter=0, continue_turn=True)),
    ("break: four rails", NINE_BREAK, shot("cue-1", "2|", "3|", "4|", "5|", is_break=True),
     dict(foul=None, next_shooter=1)),
    ("break: three rails", NINE_BREAK, shot("cue-1", "2|", "3|", "4|", is_break=True),
     dict(foul="illegal_break", next_shooter=1, ball_in_hand_area="anywhere")),
    ("break: 2 first", NINE_BREAK, shot("cue-2", "2>foot_left", is_break=True),
     dict(foul="wrong_ball_first", ball_in_hand=True)),
    ("break: the 9 wins", NINE_BREAK, shot("cue-1", "1-9", "9>side_right", is_break=True),
     dict(winner=0, foul=None)),
    ("break: scratch", NINE_BREAK, shot("cue-1", "3>foot_left", "cue>head_left", is_break=True),
     dict(foul="scratch", ball_in_hand_area="anywhere")),
    # push-out
    ("push-out: any ball, no rail", PUSH, shot("cue-6"),
     dict(foul=None, next_shooter=1, option="shoot_or_pass", ball_in_hand=False)),
    ("push-out: no ball at all", PUSH, shot(), dict(foul=None, option="shoot_or_pass")),
    ("push-out: the 9 is re-spotted", PUSH, shot("cue-1", "1-9", "9>foot_left"),
     dict(winner=None, foul=None, respot=("9",), option="shoot_or_pass")),
    ("push-out: a scratch is a foul", PUSH, shot("cue-6", "cue>foot_left"),
     dict(foul="scratch", ball_in_hand=True, option=None)),
]


@pytest.mark.parametrize("name, state, summary, expect", NINE_CASES,
                         ids=[c[0] for c in NINE_CASES])
def test_nine(name: str, state: State, summary: ShotSummary, expect: dict) -> None:
    out, new = nine.judge(state, summary)
    check(out, expect)
    assert out.groups is None and new.push_out in ("none", "available")
    if out.winner is None:
        assert new.shooter == out.next_shooter
    assert not (set(out.respot) & set(new.pocketed))


def test_nine_push_out_availability() -> None:
    _, new = nine.judge(NINE_BREAK, shot("cue-1", "2|", "3|", "4|", "5|", is_break=True))
    assert new.push_out == "available" and new.shooter == 1
    _, new = nine.judge(NINE_BREAK, shot("cue-1", "1-3", "3>foot_left", "cue>side_left",
                                         is_break=True))
    assert new.push_out == "available"  # scratch on a break that met its requirements
    _, new = nine.judge(NINE_BREAK, shot("cue-1", "2|", is_break=True))
    assert new.push_out == "none"  # illegal break
    _, new = nine.judge(state9(push_out="available"), shot("cue-1", "1|"))
    assert new.push_out == "none"
    with pytest.raises(ValueError):
        nine.judge(state9(is_break=True, push_out="declared"), shot("cue-1", is_break=True))


def test_nine_balls_on_a_foul_stay_down() -> None:
    _, new = nine.judge(NINE, shot("cue-2", "2-9", "2>foot_left", "9>side_left"))
    assert new.pocketed == ("2",)


@pytest.mark.parametrize("rule, before, winner", [
    (True, (2, 0), 1), (True, (1, 2), None), (False, (2, 0), None), (True, (0, 5), None),
])
def test_nine_three_fouls(rule: bool, before: tuple, winner: int | None) -> None:
    st = state9(three_foul=rule, fouls=before)
    out, new = nine.judge(st, shot("cue-3", "3|"))
    assert out.foul == "wrong_ball_first" and out.winner == winner
    assert new.fouls == (before[0] + 1, before[1])
    if winner is not None:
        assert "third consecutive foul" in out.reason and not out.ball_in_hand
    # A legal shot resets the count.
    _, new = nine.judge(st, shot("cue-1", "1|"))
    assert new.fouls == (0, before[1])


# ----------------------------------------------------------------------------- practice


@pytest.mark.parametrize("summary, in_hand", [
    (shot("cue-3", "3>foot_left"), False),
    (shot("cue-3", "3|", "cue>foot_left"), True),
    (shot(), False),
    (shot("cue-8", "8>foot_left"), False),
    (ShotSummary(off_table=("cue",)), True),
])
def test_practice(summary: ShotSummary, in_hand: bool) -> None:
    st = State(mode="practice", pocketed=("1",))
    out, new = practice.judge(st, summary)
    assert out.foul is None and out.winner is None and out.next_shooter == 0
    assert out.continue_turn and out.ball_in_hand == in_hand
    assert out.ball_in_hand_area == ("anywhere" if in_hand else None)
    assert new.pocketed == ("1", *summary.object_pocketed)


# ----------------------------------------------------------------------------- common


def test_state_validation() -> None:
    for bad in (dict(mode="snooker"), dict(shooter=2), dict(push_out="maybe"),
                dict(groups={0: "solids", 1: "solids"}), dict(groups={0: "solids"})):
        with pytest.raises(ValueError):
            State(**bad)


def test_outcome_json() -> None:
    out, _ = eight.judge(OPEN, shot("cue-3", "3>foot_left"))
    j = out.to_json()
    assert {"foul", "next_shooter", "ball_in_hand", "groups", "winner", "reason"} <= set(j)
    assert j["groups"] == {"0": "solids", "1": "stripes"}
    assert json.loads(json.dumps(j)) == j


def test_referee_dispatch_and_state_from_game() -> None:
    ids = ["cue", "8", "9", "10"]
    st = state_from_game({"mode": "8ball", "shooter": 1, "groups": {"0": "solids",
                          "1": "stripes"}, "called": {"ball": "8", "pocket": "side_left"},
                          "fouls": {"0": 1, "1": 0}}, ids)
    assert st.pocketed == (*SOLIDS, *(str(n) for n in range(11, 16)))
    assert st.groups == {0: "solids", 1: "stripes"} and st.called == ("8", "side_left")
    assert st.fouls == (1, 0) and st.shooter == 1
    out = referee({"mode": "9ball", "push_out": True}, ["cue", "1", "9"],
                  [{"t": 0.1, "type": "ball_ball", "i": [0, 2]}])
    assert out["option"] == "shoot_or_pass" and out["foul"] is None
    out, _ = judge(state9(), shot("cue-2", "2|"))
    assert out.foul == "wrong_ball_first"


# ----------------------------------------------------------------------------- themes


# ----------------------------------------------------------------------------- game block

L, W = 2.54, 1.27


def straight_pot(top: float = 0.0, **game) -> dict:
    """The cue ball and the 1 on the diagonal to the foot-left corner; a straight shot."""
    return {
        "balls": [{"id": "cue", "x": L - 0.9, "y": W - 0.9}, {"id": "1", "x": L - 0.4,
                                                             "y": W - 0.4},
                  {"id": "8", "x": 0.5, "y": 0.3}, {"id": "12", "x": 0.5, "y": 0.9}],
        "shot": {"speed": 1.5, "angle": 45, "top": top},
        "game": {"mode": "8ball", **game},
    }


def run_scene(d: dict):
    s = load_game_scene(d)
    eng = Engine(s.table, s.physics, s.pos, s.vel, s.w, s.radius, s.mass)
    eng.run(1 / 60)
    return s, eng.events[0]


def test_real_straight_pot_assigns_solids() -> None:
    s, evs = run_scene(straight_pot())
    summary = summarize(evs, s.ids)
    assert summary.first_contact == "1" and summary.pocketed == {"1": "foot_left"}
    state = state_from_game(s.game, s.ids)
    assert state.groups is None and "1" not in state.pocketed and "2" in state.pocketed
    out, new = eight.judge(state, summary)
    assert out.foul is None and out.continue_turn and out.next_shooter == 0
    assert out.groups == {0: "solids", 1: "stripes"} and new.pocketed[-1] == "1"


def test_real_follow_in_is_a_scratch() -> None:
    s, evs = run_scene(straight_pot(top=0.4, shooter=1))
    summary = summarize(evs, s.ids)
    assert list(summary.pocketed) == ["1", "cue"] and summary.scratch
    out, _ = judge(state_from_game(s.game, s.ids), summary)
    assert out.foul == "scratch" and out.next_shooter == 0 and out.ball_in_hand
    assert out.groups is None


def test_game_block_normalized() -> None:
    s = load_game_scene(straight_pot(groups={"1": "solids"}, shooter=1, fouls={"1": 2}))
    assert s.game == {"mode": "8ball", "shooter": 1, "break": False,
                      "groups": {"0": "stripes", "1": "solids"}, "fouls": {"0": 0, "1": 2}}
    assert load_game_scene(straight_pot()).game["fouls"] == {"0": 0, "1": 0}
    assert load_game_scene({"balls": "9ball", "game": {"mode": "9ball", "break": True}}).game == {
        "mode": "9ball", "shooter": 0, "break": True, "fouls": {"0": 0, "1": 0},
        "push_out": False, "three_foul": False}
    assert load_game_scene(straight_pot()).game is not None
    assert load_game_scene({"balls": "8ball"}).game is None
    # The block survives scene_to_dict.
    from termpool.scene import scene_to_dict

    d = scene_to_dict(load_game_scene(straight_pot(called={"ball": "8", "pocket": "head_left"})))
    assert d["game"]["called"] == {"ball": "8", "pocket": "head_left"}
    assert load_game_scene(d).game == d["game"]


def with_balls(balls, **game) -> dict:
    d = straight_pot(**game)
    d["balls"] = balls
    return d


BAD_GAMES = [
    (straight_pot(colour="red"), "game: unknown key 'colour'"),
    ({"balls": "8ball", "game": {}}, "game: missing key 'mode'"),
    ({"balls": "8ball", "game": "8ball"}, "game: must be an object"),
    (straight_pot(mode="snooker"), "game.mode: must be '8ball', '9ball' or 'practice'"),
    (straight_pot(shooter=2), "game.shooter: must be 0 or 1, not 2"),
    (straight_pot(shooter=True), "game.shooter: must be 0 or 1, not true"),
    (straight_pot(**{"break": "yes"}), "game.break: must be true or false"),
    (straight_pot(groups={"0": "reds"}), "game.groups.0: must be 'solids' or 'stripes'"),
    (straight_pot(groups={"2": "solids"}), "game.groups: unknown key '2'"),
    (straight_pot(groups={}), "game.groups: must give the group of player 0 or 1"),
    (straight_pot(groups={"0": "solids", "1": "solids"}), "cannot both have the solids"),
    (straight_pot(groups={"0": "solids"}, **{"break": True}), "the table is open on a break"),
    (straight_pot(called={"ball": "8"}), "game.called: missing key 'pocket'"),
    (straight_pot(called={"ball": "3", "pocket": "foot_left"}),
     "game.called.ball: no object ball with id '3' on the table"),
    (straight_pot(called={"ball": "8", "pocket": "corner"}),
     "game.called.pocket: unknown pocket 'corner'"),
    (straight_pot(fouls={"0": -1}), "game.fouls.0: must be a whole number >= 0, not -1"),
    (straight_pot(fouls={"0": 1.5}), "game.fouls.0: must be a whole number"),
    (straight_pot(push_out=True), "game.push_out: only for mode '9ball'"),
    ({"balls": "9ball", "game": {"mode": "9ball", "break": True, "push_out": True}},
     "game.push_out: a break shot cannot be a push-out"),
    ({"balls": "8ball", "game": {"mode": "9ball"}},
     "balls[10] (id '10'): not a ball of game mode '9ball' (use 'cue' and '1'..'9')"),
    (with_balls([{"id": "cue", "x": 0.5, "y": 0.5}, {"id": "x", "x": 1.0, "y": 0.5}]),
     "balls[1] (id 'x'): not a ball of game mode '8ball'"),
    (with_balls([{"id": "cue", "x": 0.5, "y": 0.5}, {"id": "1", "x": 1.0, "y": 0.5}]),
     "game: mode '8ball' needs the 8 on the table"),
    ({"balls": [{"id": "8", "x": 0.5, "y": 0.5}], "game": {"mode": "8ball"}},
     "game: the scene needs the cue ball"),
    ({**straight_pot(), "shot": {"ball": "1", "speed": 1}},
     "shot.ball: must be the cue ball 'cue'"),
    ({**straight_pot(called={"ball": "8", "pocket": "foot_left"}),
      "table": {"pockets": "none"}}, "game.called.pocket: the table has no pockets"),
]


@pytest.mark.parametrize("scene, message", BAD_GAMES, ids=[m for _, m in BAD_GAMES])
def test_bad_game_blocks(scene: dict, message: str) -> None:
    with pytest.raises(SceneError) as e:
        load_game_scene(scene)
    text = str(e.value)
    assert message in text and "\n" not in text


# ----------------------------------------------------------------------------- CLI

REFEREE_EXAMPLES = {
    "referee_pot.json": dict(foul=None, winner=None, next_shooter=0, ball_in_hand=False,
                             groups={"0": "solids", "1": "stripes"}),
    "referee_scratch.json": dict(foul="scratch", winner=None, next_shooter=1, ball_in_hand=True,
                                 groups=None),
    "referee_eight.json": dict(foul=None, winner=1),
    "referee_nine.json": dict(foul=None, winner=1),
}


def sim(path: str) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    p = subprocess.run([sys.executable, "-m", "termpool", "sim", path], cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0 and p.stderr == "", p.stderr
    return json.loads(p.stdout)


@pytest.mark.parametrize("name, expect", REFEREE_EXAMPLES.items(), ids=list(REFEREE_EXAMPLES))
def test_cli_referee_examples(name: str, expect: dict) -> None:
    out = sim(f"examples/{name}")
    outcome = out["outcome"]
    assert {"foul", "next_shooter", "ball_in_hand", "groups", "winner", "reason"} <= set(outcome)
    for key, val in expect.items():
        assert outcome[key] == val, (key, outcome)
    assert isinstance(outcome["reason"], str) and outcome["reason"]


def test_cli_no_outcome_without_game() -> None:
    assert "outcome" not in sim("examples/cut.json")


def test_referee_examples_listed() -> None:
    names = {p.name for p in (ROOT / "examples").glob("referee_*.json")}
    assert names == set(REFEREE_EXAMPLES)
    docs = (ROOT / "docs" / "scenes.md").read_text()
    assert all(n in docs for n in names)


# ----------------------------------------------------------------------------- invariants

from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

POCKETS = ["head_left", "head_right", "side_left", "side_right", "foot_left", "foot_right"]


@st.composite
def any_shot(draw, balls: list[str]) -> tuple[list[dict], bool]:
    steps = []
    for _ in range(draw(st.integers(0, 8))):
        kind = draw(st.sampled_from(["hit", "rail", "pot"]))
        a = draw(st.sampled_from(["cue", *balls]))
        if kind == "hit":
            b = draw(st.sampled_from([x for x in ["cue", *balls] if x != a]))
            steps.append(f"{a}-{b}")
        elif kind == "rail":
            steps.append(f"{a}|{draw(st.sampled_from(['rail', 'jaw', 'tip']))}")
        else:
            steps.append(f"{a}>{draw(st.sampled_from(POCKETS))}")
    return events(*steps), draw(st.booleans())


@st.composite
def any_state(draw) -> State:
    mode = draw(st.sampled_from(["8ball", "9ball", "practice"]))
    balls = [b for b in IDS[1:] if mode != "9ball" or int(b) <= 9]
    keep = draw(st.sets(st.sampled_from(balls), min_size=1))
    keep.add("8" if mode == "8ball" else "9" if mode == "9ball" else balls[0])
    is_break = draw(st.booleans())
    groups = None
    if mode == "8ball" and not is_break and draw(st.booleans()):
        groups = draw(st.sampled_from([SOLIDS_STRIPES, STRIPES_SOLIDS]))
    push = "declared" if mode == "9ball" and not is_break and draw(st.booleans()) else "none"
    called = None
    if draw(st.booleans()):
        called = (draw(st.sampled_from(sorted(keep))), draw(st.sampled_from(POCKETS)))
    rerack = mode == "8ball" and draw(st.booleans())
    return State(mode=mode, shooter=draw(st.integers(0, 1)), groups=groups,
                 fouls=(draw(st.integers(0, 3)), draw(st.integers(0, 3))),
                 pocketed=tuple(b for b in balls if b not in keep), is_break=is_break,
                 push_out=push, called=called, three_foul=draw(st.booleans()),
                 eight_break="rerack" if rerack else "respot")


@settings(max_examples=400, deadline=None)
@given(data=st.data())
def test_outcome_invariants(data) -> None:
    state = data.draw(any_state())
    on = state.on_table()
    evs, _ = data.draw(any_shot(on))
    summary = summarize(evs, IDS, is_break=state.is_break)
    before = repr(state)
    out, new = judge(state, summary)
    assert repr(state) == before  # pure
    assert out.next_shooter in (0, 1) and out.winner in (None, 0, 1)
    assert out.ball_in_hand == (out.ball_in_hand_area in ("anywhere", "kitchen"))
    assert out.foul is None or out.foul == out.fouls[0]
    assert out.reason and "\n" not in out.reason
    if out.rerack:  # the 8 on the break with the re-rack variant: the same player breaks
        assert state.eight_break == "rerack" and state.is_break and out.winner is None
        assert new == State(mode="8ball", shooter=state.shooter, is_break=True,
                            three_foul=state.three_foul, eight_break="rerack")
        assert out.next_shooter == state.shooter and out.respot == ()
        assert out.ball_in_hand_area == "kitchen" and out.option is None
        return
    assert out.groups == new.groups and not new.is_break and new.called is None
    if out.winner is None:
        assert new.shooter == out.next_shooter
        assert out.continue_turn == (out.next_shooter == state.shooter)
        if state.mode != "practice":
            assert not (out.foul and out.continue_turn)
            assert out.foul is None or out.next_shooter != state.shooter
    else:
        assert not out.continue_turn and state.mode != "practice"
    # Every ball pocketed is down afterwards, unless re-spotted; nothing else is.
    down = set(state.pocketed) | set(summary.object_pocketed)
    assert set(new.pocketed) == down - set(out.respot)
    assert len(set(new.pocketed)) == len(new.pocketed)
    json.dumps(out.to_json())


# ------------------------------------------------------------------------------- the words

THIRD_PERSON = re.compile(r"\byou (has|is|continues|loses|wins|takes|chooses|breaks)\b",
                          re.IGNORECASE)


@settings(max_examples=300, deadline=None)
@given(data=st.data())
def test_every_verdict_reads_right_in_every_voice(data) -> None:
    state = data.draw(any_state())
    evs, _ = data.draw(any_shot(state.on_table()))
    summary = summarize(evs, IDS, is_break=state.is_break)
    out, _ = judge(state, summary)
    record = words.reason(out.said)
    assert record == out.reason and "you" not in record.lower().split()
    assert "player 0" in record or "player 1" in record or state.mode == "practice"
    for who in (("You", "Bob"), ("Ann", "You")):
        said = words.reason(out.said, words.voice(who, "classic"))
        assert "player 0" not in said and "player 1" not in said
        assert not THIRD_PERSON.search(said), said
        assert "_" not in said  # pockets in words
        assert "solids" not in said and "stripes" not in said  # the classic theme's groups
        if state.mode != "9ball":  # (9-ball is shown in the standard theme)
            assert not re.search(r"\bthe (1[0-5]|[1-79])\b", said), said  # no numbers seen
    # The people's words are the record's with the names, pockets and groups changed, and a
    # ball pocketed alone said with its pocket ("the 3 in the top-right corner pocket").
    ann = words.reason(out.said, words.voice(("Ann", "Bob")))
    plain = record.replace("player 0", "Ann").replace("player 1", "Bob")
    expected = re.sub(r"(head|foot|side)_(left|right)", lambda m: ON_SCREEN[m.group(0)], plain)
    for x in out.said:
        assert len(x.pockets) == len(x.balls) or not x.pockets
        if x.why in POTTED and len(x.balls) == 1 and x.pockets[0] is not None:
            b, p = x.balls[0], x.pockets[0]
            assert p == summary.pocketed[b]  # where the shot's events put it
            said = f"the {b} in the {ON_SCREEN[p]} pocket"
            expected = expected.replace(f"the {b} pocketed", said, 1)
        elif x.why is Why.PRACTICE_POTTED and len(x.balls) > 1:
            # (the record lists practice's balls with commas alone; people hear "and")
            names = [f"the {b}" for b in x.balls]
            expected = expected.replace(", ".join(names), ", ".join(names[:-1]) + " and "
                                        + names[-1], 1)
    assert ann == expected


POTTED = {Why.LEGAL_BREAK_POTTED, Why.TAKES_GROUP, Why.POTTED_CONTINUES, Why.POTTED_NOT_OWN,
          Why.PRACTICE_POTTED}  # the clauses of balls pocketed, which give their pockets

PAST = re.compile(r"\b(went|reached|was|were|hit|left the table)\b")


@settings(max_examples=300, deadline=None)
@given(data=st.data())
def test_the_aid_warns_ahead_of_the_shot(data) -> None:
    """The aim aid's warning speaks of a shot not yet played ("the cue ball goes into ..."),
    of every foul and loss the referee finds, and only of those."""
    state = data.draw(any_state())
    evs, _ = data.draw(any_shot(state.on_table()))
    out, _ = judge(state, summarize(evs, IDS, is_break=state.is_break))
    for who in (("You", "Bob"), ("Ann", "Bob")):
        warning = words.aid_warning(out, words.voice(who), state.shooter)
        lost = out.winner is not None and out.winner != state.shooter
        spoiled = any(x.why in (Why.SCRATCH_IN_HAND, Why.CUE_LEFT_IN_HAND) for x in out.said)
        assert (warning is not None) == (lost or out.foul is not None or spoiled)
        if warning is None:
            continue
        assert warning.startswith("As aimed, a foul: " if out.foul and not lost
                                  else "As aimed: ")
        assert not PAST.search(warning), warning
        assert warning.count(":") <= 2 + lost, warning



# The pockets where the screen shows them (the head on the left, its left pockets at the top).
ON_SCREEN = {"head_left": "top-left corner", "head_right": "bottom-left corner",
             "foot_left": "top-right corner", "foot_right": "bottom-right corner",
             "side_left": "top side", "side_right": "bottom side"}


def test_every_pocket_is_named_as_people_say_it() -> None:
    from termpool.physics.table import POCKET_NAMES

    v = words.voice(("Ann", "Bob"))
    assert {p: v.pocket(p) for p in POCKET_NAMES} == ON_SCREEN
    assert words.calling(v, "8", "side_right") == "calling the 8 in the bottom side pocket"
    assert words.RECORD.pocket("side_right") == "side_right"  # records keep the table's names


def test_every_reason_code_has_its_words() -> None:
    assert set(words.CLAUSES) == set(Why)
    assert [words.group_label(g, "classic") for g in ("solids", "stripes")] == \
        ["reds", "yellows"]


def test_option_words_and_keys() -> None:
    assert words.option_lines("rerack_or_accept") == [
        "The break was illegal.", "", "r: re-rack and break yourself",
        "a: accept the table and shoot"]
    assert words.option_lines(Option.SHOOT_OR_PASS)[2:] == ["s: shoot from here",
                                                            "p: pass the shot back"]
    assert words.chose("You", Choice.ACCEPT) == "You chose to accept the table"
    assert len({words.CHOICE_KEYS[c] for c in Choice}) == len(Choice)


# ------------------------------------------------------------------------------- the codec


@settings(max_examples=300, deadline=None)
@given(data=st.data())
def test_the_state_s_two_json_forms_read_back(data) -> None:
    state = data.draw(any_state())
    assert codec.state_from_json(json.loads(json.dumps(codec.state_to_json(state)))) == state
    # The game block: the balls not in the scene are the pocketed ones (in the set's order);
    # only a declared push-out is the referee's business, and three fouls only 9-ball's.
    ids = ["cue", *state.on_table()]
    block = codec.read_game(json.loads(json.dumps(codec.game_block(state))), ids, POCKETS,
                            "cue")
    assert block == codec.game_block(state)  # already normal
    back = codec.state_from_game(block, ids)
    assert back == replace(state, pocketed=tuple(sorted(state.pocketed, key=int)),
                           push_out="declared" if state.push_out == "declared" else "none",
                           three_foul=state.three_foul and state.mode == "9ball")


def test_old_saves_and_blocks_read_as_the_re_spot() -> None:
    s = State(mode="8ball", eight_break="rerack")
    assert "eight_break" in codec.state_to_json(s) and "eight_break" in codec.game_block(s)
    old = {k: v for k, v in codec.state_to_json(s).items() if k != "eight_break"}
    assert codec.state_from_json(old).eight_break == "respot"
    assert "eight_break" not in codec.state_to_json(State()) | codec.game_block(State())
    with pytest.raises(SceneError, match="^game.eight_break: only for mode '8ball'"):
        codec.read_game({"mode": "9ball", "eight_break": "rerack"}, ["cue", "9"], POCKETS)
    with pytest.raises(SceneError, match="^game.eight_break: must be one of respot, rerack"):
        codec.read_game({"mode": "8ball", "eight_break": "x"}, ["cue", "8"], POCKETS)


def test_signed_readings_never_say_minus_zero() -> None:
    assert [words.signed(x) for x in (-0.0, 0.0, -0.04, 0.04, -0.05, 0.3, -1.0)] == \
        ["0.0", "0.0", "0.0", "0.0", "-0.1", "+0.3", "-1.0"]
    assert words.tip_words(-0.01, 0.5) == "tip: side 0.0, top +0.5"
