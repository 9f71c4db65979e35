"""Matches: racks, re-spots, ball-in-hand placement, the turn flow with real simulated shots,
options, frames, practice's re-rack and take-back, saving and loading.

Most turn-flow cases are small layouts set on a match's table (`setup`) and one real shot:
the cue ball on the diagonal of the foot-right corner, so a shot at -45 degrees goes straight
at the pocket (potting the ball in front of it, or scratching when nothing is in the way).
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from termpool.game import Match, Shot, replay
from termpool.game import layout as lay
from termpool.physics.params import BALL_RADIUS as R
from termpool.physics.params import Physics
from termpool.physics.table import Table
from termpool.rules import words
from termpool.rules.common import MODE_BALLS, SOLIDS, STRIPES
from termpool.scene import load_scene

RECORDS = Path(__file__).parent / "records"


class Seat(NamedTuple):
    """A player as the match takes one: a name and a level (None: a person)."""

    name: str
    level: str | None


def seats(levels) -> tuple[Seat, Seat]:
    return tuple(Seat(f"Player {k + 1}", lv) for k, lv in enumerate(levels))

T = Table.preset("9ft")
L, W = T.length, T.width
FOOT = T.foot_spot
HEAD = T.head_spot
# A ball on the foot-right corner's diagonal, and the cue ball behind it on the same line.
NEAR_POCKET = (L - 0.25, 0.25)
BEHIND = (L - 0.45, 0.45)
POT = Shot(1.5, -45.0, top=-0.3)  # stun-draw: the object ball drops, the cue ball stays up
SCRATCH = {"cue": (L - 0.3, 0.3)}  # nothing between the cue ball and the pocket
PARK = {"8": (0.5, 0.3), "1": (0.4, 1.0), "9": (0.5, 1.0)}  # out of the way


def setup(m: Match, where: dict[str, tuple[float, float]], **state) -> None:
    """Only the balls in `where` on the table, at those places; the state says the others
    are down; no break, no ball in hand unless given."""
    m.on_table[:] = False
    for b, p in where.items():
        m.pos[m.index(b)] = p
        m.on_table[m.index(b)] = True
    down = tuple(b for b in MODE_BALLS[m.mode] if b not in where)
    m.state = replace(m.state, **{"pocketed": down, "is_break": False, **state})
    m.ball_in_hand = None


def at(m: Match, ball: str) -> tuple[float, float]:
    return tuple(float(v) for v in m.pos[m.index(ball)])


# ---------------------------------------------------------------------------------- racks


def slot_ids(m: Match, kind: str) -> list[list[str]]:
    """The rack read back by position: ids by row, ordered like `layout.rack_slots`."""
    rows = lay.rack_slots(kind, m.table)
    where = {at(m, b): b for b in m.ids}
    return [[where[p] for p in row] for row in rows]


@pytest.mark.parametrize("seed", range(40))
def test_eight_ball_rack_pattern(seed: int) -> None:
    m = Match("8ball", seed=seed)
    rows = slot_ids(m, "8ball")
    assert [len(r) for r in rows] == [1, 2, 3, 4, 5]
    assert rows[2][1] == "8"  # centre of the third row
    corners = {rows[4][0], rows[4][4]}
    assert len(corners & set(SOLIDS)) == 1 and len(corners & set(STRIPES)) == 1
    assert sorted(b for r in rows for b in r) == sorted(MODE_BALLS["8ball"])
    assert at(m, "cue") == HEAD and m.ball_in_hand == "kitchen" and m.state.is_break
    assert at(m, rows[0][0]) == FOOT


@pytest.mark.parametrize("seed", range(40))
def test_nine_ball_rack_pattern(seed: int) -> None:
    m = Match("9ball", seed=seed)
    rows = slot_ids(m, "9ball")
    assert [len(r) for r in rows] == [1, 2, 3, 2, 1]
    assert rows[0][0] == "1" and at(m, "1") == FOOT
    assert rows[2][1] == "9"
    assert sorted(b for r in rows for b in r) == sorted(MODE_BALLS["9ball"])


def test_racks_are_random_but_seeded() -> None:
    def pattern(mode: str, seed: int) -> list:
        return [b for r in slot_ids(Match(mode, seed=seed), mode) for b in r]

    for mode in ("8ball", "9ball"):
        assert pattern(mode, 5) == pattern(mode, 5)
        assert len({tuple(pattern(mode, s)) for s in range(12)}) > 6
    # Over many racks every ball but the fixed ones visits several slots, and both back
    # corners hold a solid sometimes.
    corners = [slot_ids(Match("8ball", seed=s), "8ball")[4][0] for s in range(30)]
    assert {c in SOLIDS for c in corners} == {True, False}


def test_practice_has_a_full_rack() -> None:
    m = Match("practice")
    assert m.on_table.all() and len(m.ids) == 16
    assert slot_ids(m, "8ball")[2][1] == "8"
    assert m.ball_in_hand == "anywhere"


# ------------------------------------------------------------------------------- re-spots


def test_respot_on_free_foot_spot() -> None:
    assert lay.respot_point(T, R, np.zeros((0, 2)), np.zeros(0)) == FOOT


@pytest.mark.parametrize(
    "others, want_x",
    [
        ([FOOT], FOOT[0] + 2 * R),  # on the spot: just behind it, touching
        ([FOOT, (FOOT[0] + 2 * R, FOOT[1])], FOOT[0] + 4 * R),  # two in a row
        ([(FOOT[0] + R, FOOT[1] + R)], FOOT[0] + R + math.sqrt(3) * R),  # off the string
        ([(FOOT[0] + 3 * R, FOOT[1])], FOOT[0]),  # close behind, but the spot itself is free
        ([(FOOT[0], FOOT[1] + 2 * R)], FOOT[0]),  # beside the spot, touching: free
    ],
)
def test_respot_behind_an_occupied_spot(others, want_x) -> None:
    x, y = lay.respot_point(T, R, np.array(others), np.full(len(others), R))
    assert y == W / 2 and x == pytest.approx(want_x, abs=1e-12)


def test_respot_in_front_when_the_string_behind_is_full() -> None:
    xs = np.arange(FOOT[0], L, 2 * R)  # a line of balls from the spot to the foot rail
    others = np.stack([xs, np.full(len(xs), W / 2)], axis=1)
    x, _ = lay.respot_point(T, R, others, np.full(len(xs), R))
    assert x == pytest.approx(FOOT[0] - 2 * R)


def test_cue_returns_to_the_head_spot_or_behind_it() -> None:
    assert lay.cue_return_point(T, R, np.zeros((0, 2)), np.zeros(0)) == HEAD
    x, _ = lay.cue_return_point(T, R, np.array([HEAD]), np.array([R]))
    assert x == pytest.approx(HEAD[0] - 2 * R)


# -------------------------------------------------------------------------- ball in hand


@pytest.mark.parametrize(
    "area, x, y, words",
    [
        ("anywhere", -0.1, 0.5, "off the table"),
        ("anywhere", 1.0, W - R / 2, "off the table"),
        ("anywhere", math.nan, 0.5, "finite"),
        ("anywhere", "a", 0.5, "two numbers"),
        ("kitchen", L / 4 + 0.01, 0.5, "not in the kitchen"),
        ("anywhere", 1.2 + R, 0.6, "overlaps the 5"),
        ("anywhere", R + 0.01, R + 0.01, "in the mouth of the head_right pocket"),
        ("anywhere", L - R - 0.01, W - R - 0.01, "in the mouth of the foot_left pocket"),
    ],
)
def test_placement_refusals(area, x, y, words) -> None:
    m = Match("8ball")
    setup(m, {"cue": HEAD, "5": (1.2, 0.6), **PARK})
    m.ball_in_hand = area
    why = m.placement_error(x, y)
    assert why is not None and words in why
    with pytest.raises(ValueError, match=words):
        m.place_cue(x, y)
    assert at(m, "cue") == HEAD  # unchanged


def test_a_placement_refused_names_the_ball_as_the_screen_does() -> None:
    from termpool.rules import words

    m = Match("8ball")
    setup(m, {"cue": HEAD, "5": (1.2, 0.6), **PARK})
    m.ball_in_hand = "anywhere"
    assert m.placement_error(1.2 + R, 0.6, words.voice(("You", "Bob"), "classic")) == \
        "overlaps a red"  # the classic theme's balls show no numbers
    assert m.placement_error(1.2 + R, 0.6, words.voice(("You", "Bob"))) == "overlaps the 5"


@pytest.mark.parametrize(
    "area, x, y",
    [
        ("kitchen", L / 4, 0.3),  # on the head string
        ("kitchen", 0.2, 0.2),
        ("anywhere", 2.0, 1.0),
        ("anywhere", 1.2 + 2 * R, 0.6),  # touching the 5
        ("anywhere", 1.0, R),  # against the side rail
    ],
)
def test_placement_allowed(area, x, y) -> None:
    m = Match("8ball")
    setup(m, {"cue": HEAD, "5": (1.2, 0.6), **PARK})
    m.ball_in_hand = area
    assert m.placement_error(x, y) is None
    m.place_cue(x, y)
    assert at(m, "cue") == (x, y)


def test_no_placement_without_ball_in_hand() -> None:
    m = Match("8ball")
    setup(m, {"cue": HEAD, **PARK})
    assert m.placement_error(0.3, 0.3) == "the cue ball is not in hand"
    with pytest.raises(ValueError, match="not in hand"):
        m.place_cue(0.3, 0.3)


def test_break_from_the_kitchen_only() -> None:
    m = Match("8ball")
    assert "kitchen" in m.placement_error(1.0, 0.6)
    m.place_cue(0.4, 0.3)
    assert at(m, "cue") == (0.4, 0.3)


# ------------------------------------------------------------------------------ turn flow


def test_pot_keeps_the_turn_and_assigns_groups() -> None:
    m = Match("8ball")
    setup(m, {"cue": BEHIND, "3": NEAR_POCKET, "12": (1.0, 0.9), **PARK})
    out = m.begin(POT).finish()
    assert out.foul is None and out.next_shooter == 0 and out.continue_turn
    assert m.state.groups == {0: "solids", 1: "stripes"}
    assert not m.on_table[m.index("3")] and m.on_table[m.index("cue")]
    assert m.ball_in_hand is None and m.last_outcome is out
    assert len(m.history) == 1 and m.history[0]["outcome"]["reason"] == out.reason


def test_scratch_gives_ball_in_hand_to_the_opponent() -> None:
    m = Match("8ball")
    setup(m, {**SCRATCH, "3": (1.0, 0.6), **PARK})
    out = m.begin(Shot(1.0, -45.0)).finish()
    assert out.foul == "scratch" and m.shooter == 1
    assert m.ball_in_hand == "anywhere"
    assert at(m, "cue") == HEAD and m.on_table[m.index("cue")]
    m.place_cue(2.0, 1.0)  # anywhere, not only the kitchen
    assert at(m, "cue") == (2.0, 1.0)


def test_scratch_on_the_break_gives_the_kitchen() -> None:
    m = Match("8ball")
    setup(m, {**SCRATCH, "3": (1.0, 0.6), **PARK}, is_break=True)
    out = m.begin(Shot(1.0, -45.0)).finish()
    assert out.foul == "scratch" and m.shooter == 1 and m.ball_in_hand == "kitchen"
    assert "kitchen" in m.placement_error(2.0, 1.0)


def test_foul_without_scratch_leaves_the_cue_ball_where_it_stopped() -> None:
    m = Match("8ball")
    setup(m, {"cue": (1.0, 0.6), "3": (1.2, 0.6), **PARK})
    out = m.begin(Shot(0.3, 0.0)).finish()  # a soft tap: nothing reaches a cushion
    assert out.foul == "no_rail" and m.shooter == 1 and m.ball_in_hand == "anywhere"
    final = {b["id"]: b for b in m.history[0]["final"]}
    assert at(m, "cue") == (final["cue"]["x"], final["cue"]["y"]) != (1.0, 0.6)


def test_eight_on_the_break_is_respotted_behind_an_occupied_spot() -> None:
    m = Match("8ball")
    setup(m, {"cue": BEHIND, "8": NEAR_POCKET, "4": FOOT, "1": (0.4, 1.0)}, is_break=True)
    out = m.begin(POT).finish()
    assert out.respot == ("8",) and out.next_shooter == 0
    assert m.on_table[m.index("8")]
    x, y = at(m, "8")
    assert y == W / 2 and x == pytest.approx(FOOT[0] + 2 * R)


def test_nine_pocketed_on_a_foul_is_respotted() -> None:
    m = Match("9ball")
    # The 1 is the lowest ball: hitting the 9 first is a foul, so the 9 comes back.
    setup(m, {"cue": BEHIND, "9": NEAR_POCKET, "1": (0.4, 1.0), "2": FOOT})
    out = m.begin(POT).finish()
    assert out.foul == "wrong_ball_first" and out.respot == ("9",) and out.winner is None
    assert m.on_table[m.index("9")] and at(m, "9")[0] == pytest.approx(FOOT[0] + 2 * R)
    assert m.shooter == 1 and m.ball_in_hand == "anywhere"


def test_the_eight_must_be_called() -> None:
    m = Match("8ball", frames=1)
    setup(m, {"cue": BEHIND, "8": NEAR_POCKET, "12": (1.0, 0.9)}, groups={0: "solids",
                                                                          1: "stripes"})
    assert m.needs_call()
    with pytest.raises(ValueError, match="called"):
        m.begin(Shot(1.5, -45.0))
    with pytest.raises(ValueError, match="called: unknown pocket"):
        m.begin(Shot(1.5, -45.0, called=("8", "corner")))
    with pytest.raises(ValueError, match="the 8 is next"):
        m.begin(Shot(1.5, -45.0, called=("12", "foot_right")))
    out = m.begin(replace(POT, called=("8", "foot_right"))).finish()
    assert out.winner == 0 and m.frame_over and m.winner == 0 and m.scores == [1, 0]
    with pytest.raises(ValueError, match="match is over"):
        m.begin(POT)


def test_the_eight_in_another_pocket_loses() -> None:
    m = Match("8ball", frames=2)
    setup(m, {"cue": BEHIND, "8": NEAR_POCKET, "12": (1.0, 0.9)}, groups={0: "solids",
                                                                          1: "stripes"})
    out = m.begin(replace(POT, called=("8", "foot_left"))).finish()
    assert out.winner == 1 and m.scores == [0, 1] and m.frame_over and m.winner is None


def test_no_call_needed_while_the_group_is_on_the_table() -> None:
    m = Match("8ball")
    setup(m, {"cue": BEHIND, "3": NEAR_POCKET, "12": (1.0, 0.9), **PARK},
          groups={0: "solids", 1: "stripes"})
    assert not m.needs_call()
    assert not Match("9ball").needs_call() and not Match("practice").needs_call()


def test_frames_are_counted_and_breaks_alternate() -> None:
    m = Match("9ball", frames=2)
    for frame, breaker, scores in [(0, 0, [1, 0]), (1, 1, [1, 1]), (2, 0, [2, 1])]:
        assert m.frame == frame and m.breaker == breaker and m.shooter == breaker
        assert m.on_table.all() and m.ball_in_hand == "kitchen" and m.state.is_break
        # The frame's last ball: the 9 alone, potted by the breaker.
        setup(m, {"cue": BEHIND, "9": NEAR_POCKET})
        out = m.begin(POT).finish()
        assert out.winner == breaker and m.scores == scores and m.frame_over
        if m.winner is None:
            with pytest.raises(ValueError, match="frame is over"):
                m.begin(POT)
            m.new_frame()
    assert m.winner == 0
    with pytest.raises(ValueError, match="match is over"):
        m.new_frame()
    assert [r["frame"] for r in m.history] == [1, 2, 3]


def test_new_frame_refused_while_a_frame_is_played() -> None:
    with pytest.raises(ValueError, match="still being played"):
        Match("8ball").new_frame()


def test_three_fouls_lose_the_frame() -> None:
    m = Match("9ball", three_foul=True)
    setup(m, {**SCRATCH, "1": (1.0, 0.6), "9": (0.5, 1.0)}, fouls=(2, 0))
    out = m.begin(Shot(1.0, -45.0)).finish()
    assert out.winner == 1 and m.scores == [0, 1] and m.frame_over
    # Without the rule the same foul is only a foul.
    m = Match("9ball")
    setup(m, {**SCRATCH, "1": (1.0, 0.6), "9": (0.5, 1.0)}, fouls=(2, 0))
    out = m.begin(Shot(1.0, -45.0)).finish()
    assert out.winner is None and m.state.fouls == (3, 0) and m.ball_in_hand == "anywhere"


# -------------------------------------------------------------------------------- options


def soft_break(m: Match) -> None:
    """A tap on the apex: an illegal break (nothing down, few balls to a cushion)."""
    out = m.begin(Shot(0.6, 0.0)).finish()
    assert out.foul == "illegal_break", out.reason


def test_illegal_break_accept() -> None:
    m = Match("8ball", seed=2)
    soft_break(m)
    assert m.option == "rerack_or_accept" and m.shooter == 1 and m.ball_in_hand is None
    with pytest.raises(ValueError, match=r"^begin: Player 2 must first choose \(rerack or "):
        m.begin(POT)
    with pytest.raises(ValueError, match="'rerack' or 'accept'"):
        m.choose("pass")
    before = m.pos.copy()
    m.choose("accept")
    assert m.option is None and m.shooter == 1 and not m.state.is_break
    assert np.array_equal(m.pos, before)
    assert m.choices == [{"after_shot": 1, "player": 1, "option": "rerack_or_accept",
                          "choice": "accept"}]
    with pytest.raises(ValueError, match="nothing to choose"):
        m.choose("accept")


def test_illegal_break_rerack_is_broken_by_the_chooser() -> None:
    m = Match("8ball", seed=2)
    soft_break(m)
    moved = m.pos.copy()
    m.choose("rerack")
    assert m.option is None and m.shooter == 1 and m.breaker == 1 and m.state.is_break
    assert m.on_table.all() and m.ball_in_hand == "kitchen" and at(m, "cue") == HEAD
    assert not np.array_equal(m.pos, moved)
    assert slot_ids(m, "8ball")[2][1] == "8"


def legal_nine_break() -> Match:
    m = Match("9ball", seed=1)
    out = m.begin(Shot(8.0, 0.0)).finish()
    assert out.foul is None and out.winner is None and m.shooter == 1, out.reason
    assert m.state.push_out == "available"
    return m


def test_push_out_then_pass() -> None:
    m = legal_nine_break()
    c = m.pos[m.index("cue")]
    out = m.begin(Shot(0.2, 90.0 if c[1] < W / 2 else -90.0, push_out=True)).finish()
    assert out.foul is None and m.option == "shoot_or_pass" and m.shooter == 0
    m.choose("pass")
    assert m.shooter == 1 and m.option is None
    assert m.choices[-1]["choice"] == "pass"


def test_push_out_then_shoot() -> None:
    m = legal_nine_break()
    c = m.pos[m.index("cue")]
    m.begin(Shot(0.2, 90.0 if c[1] < W / 2 else -90.0, push_out=True)).finish()
    m.choose("shoot")
    assert m.shooter == 0 and m.option is None


def test_push_out_only_after_the_break() -> None:
    m = Match("9ball")
    with pytest.raises(ValueError, match="push_out"):
        m.begin(Shot(8.0, 0.0, push_out=True))
    m = Match("8ball")
    with pytest.raises(ValueError, match="push_out"):
        m.begin(Shot(8.0, 0.0, push_out=True))


# -------------------------------------------------------------------------- shots running


def test_bad_shots_are_refused_in_words() -> None:
    m = Match("8ball")
    with pytest.raises(ValueError, match="shot.speed"):
        m.begin(Shot(-1.0, 0.0))
    with pytest.raises(ValueError, match="miscue"):
        m.begin(Shot(2.0, 0.0, side=0.5, top=0.5))
    m.begin(Shot(1.0, 0.0))
    with pytest.raises(ValueError, match="still running"):
        m.begin(Shot(1.0, 0.0))


def test_step_advances_whole_engine_steps() -> None:
    m = Match("8ball")
    run = m.begin(Shot(5.0, 0.0))
    run.step(0.4 * m.dt)
    assert run.engine.steps == 0
    run.step(0.7 * m.dt)
    assert run.engine.steps == 1
    run.step(3 * m.dt)
    assert run.engine.steps == 4


def test_frame_rate_does_not_change_the_shot() -> None:
    def play(frame_dts: list[float]) -> dict:
        m = Match("8ball", seed=4)
        run = m.begin(Shot(7.0, 1.0, side=0.1))
        k = 0
        while not run.done:
            run.step(frame_dts[k % len(frame_dts)])
            k += 1
        run.finish()
        return m.to_json()

    assert play([1 / 60]) == play([0.004, 0.031, 1 / 144])


def test_finish_is_idempotent_and_matches_are_reproducible() -> None:
    def play() -> dict:
        m = Match("8ball", seed=11)
        run = m.begin(Shot(7.5, 0.5))
        assert run.finish() is run.finish()
        m.choose("accept") if m.option else None
        c = m.pos[m.index("cue")]
        m.begin(Shot(2.0, 180.0 if c[0] > L / 2 else 0.0)).finish()
        return m.to_json()

    a, b = play(), play()
    assert a == b and len(a["shots"]) == 2


# -------------------------------------------------------------------------------- practice


def test_practice_scratch_keeps_the_shooter() -> None:
    m = Match("practice")
    setup(m, {**SCRATCH, "3": (1.0, 0.6), "8": (0.5, 0.3)})
    out = m.begin(Shot(1.0, -45.0)).finish()
    assert out.foul is None and m.shooter == 0 and m.ball_in_hand == "anywhere"


def test_practice_take_back_restores_the_table() -> None:
    m = Match("practice", seed=3)
    live = m.pos  # a UI may hold the array: it must see the restored table
    m.begin(Shot(8.0, 0.0)).finish()
    pos1, on1, state1 = m.pos.copy(), m.on_table.copy(), m.state
    m.begin(Shot(3.0, 30.0)).finish()
    assert len(m.history) == 2 and not np.array_equal(m.pos, pos1)
    m.take_back()
    assert np.array_equal(m.pos, pos1) and np.array_equal(m.on_table, on1) and live is m.pos
    assert m.state == state1 and len(m.history) == 1
    m.take_back()
    assert m.history == [] and m.state.is_break and at(m, "cue") == HEAD
    with pytest.raises(ValueError, match="no shot"):
        m.take_back()


def test_practice_rerack_and_its_take_back() -> None:
    """A re-rack racks every ball and keeps the record; taking it back puts the balls, the
    state and the ball in hand back as they were, and the shot before it can still be taken
    back after that."""
    m = Match("practice", seed=3)
    m.begin(Shot(8.0, 0.0)).finish()
    pos1, on1, state1, hand1 = m.pos.copy(), m.on_table.copy(), m.state, m.ball_in_hand
    m.rerack()
    assert m.on_table.all() and at(m, "cue") == HEAD and len(m.history) == 1
    assert not np.array_equal(m.pos, pos1)  # the break's layout is gone
    assert m.state.is_break
    assert m.take_back() == "rerack"
    assert np.array_equal(m.pos, pos1) and np.array_equal(m.on_table, on1)
    assert (m.state, m.ball_in_hand, len(m.history)) == (state1, hand1, 1)
    assert m.take_back() == "shot" and m.history == []
    with pytest.raises(ValueError, match="no shot"):
        m.take_back()


def test_take_back_and_rerack_only_in_practice() -> None:
    m = Match("8ball")
    with pytest.raises(ValueError, match="only in practice"):
        m.take_back()
    with pytest.raises(ValueError, match="only in practice"):
        m.rerack()


# ------------------------------------------------------------------------- settings, saving


@pytest.mark.parametrize(
    "kw, words",
    [
        ({"mode": "snooker"}, "mode"),
        ({"table": "12ft"}, "table"),
        ({"frames": 0}, "frames"),
        ({"frames": 1.5}, "frames"),
        ({"players": ("A",)}, "players"),
        ({"players": ("A", " ")}, "players"),
        ({"seed": "x"}, "seed"),
        ({"physics": Physics(mu_roll=0.0)}, "physics.mu_roll"),
        ({"three_foul": True}, "three_foul"),
        ({"theme": "neon"}, "theme"),
        ({"table": Table(pockets="none")}, "table"),
        ({"dt": 1e-300}, "dt: must be from 0.0001 to 1 seconds"),  # no replay would take it
        ({"dt": 2.0}, "dt: must be from 0.0001 to 1 seconds"),
        ({"players": ("A", Seat("B", "expert"))}, "^levels: must be two of None"),
        ({"players": (Seat("A", 3), "B")}, "^levels: must be two of None"),
    ],
)
def test_bad_settings(kw, words) -> None:
    kw = {"mode": "8ball", **kw}
    with pytest.raises(ValueError, match=words):
        Match(kw.pop("mode"), **kw)


@pytest.mark.parametrize("levels", [None, [None, "easy"], ["normal", None], ["hard", "hard"],
                                    ["pro", "easy"]])
def test_records_load_and_replay_with_every_level_and_from_before_levels(levels) -> None:
    # None: a record from before the match kept the computer's level (no "levels" key).
    m = Match("9ball", seed=3, players=seats(levels or [None, None]))
    m.begin(Shot(7.5, 0.5)).finish()
    data = json.loads(json.dumps(m.to_json()))
    if levels is None:
        del data["match"]["levels"]
    again = Match.from_json(data)
    assert list(again.levels) == (levels or [None, None])
    assert all(r["ok"] for r in replay(data))


def test_save_and_load_goes_on_identically() -> None:
    m = Match("8ball", seed=9, frames=3, players=("Ann", "Bob"))
    m.begin(Shot(7.5, 0.5)).finish()
    saved = json.loads(json.dumps(m.to_json()))
    m2 = Match.from_json(saved)
    assert m2.to_json() == saved
    assert np.array_equal(m2.pos, m.pos) and np.array_equal(m2.on_table, m.on_table)
    assert m2.state == m.state and m2.players == ("Ann", "Bob")
    # Both go on the same way, racks included (the generator's state is saved).
    for x in (m, m2):
        if x.option:
            x.choose("rerack")
        setup(x, {"cue": BEHIND, "8": NEAR_POCKET}, groups={0: "solids", 1: "stripes"})
        x.begin(replace(POT, called=("8", "foot_right"))).finish()
        if x.frame_over:
            x.new_frame()
    assert m.to_json() == m2.to_json()


@pytest.mark.parametrize(
    "change, words",
    [
        (lambda d: d.pop("match"), "missing key 'match'"),
        (lambda d: d.update(format="other"), "format"),
        (lambda d: d["match"].update(frames="3"), "match.frames"),
        (lambda d: d["match"].update(mode="snooker"), "mode"),
        (lambda d: d["current"]["balls"].pop(), "current.balls"),
        (lambda d: d["current"]["balls"][2].update(x="a"), r"current.balls\[2\].x"),
        (lambda d: d["current"]["state"].pop("fouls"), "current.state: missing key 'fouls'"),
        (lambda d: d["current"].update(ball_in_hand="home"), "current.ball_in_hand"),
        (lambda d: d["current"].update(option="flip"), "current.option"),
        (lambda d: d["current"].update(scores=[1]), "current.scores"),
        (lambda d: d["current"].update(winner=2), "current.winner"),
        (lambda d: d["current"].update(rng={"x": 1}), "current.rng"),
        (lambda d: d.update(shots={}), "shots"),
        (lambda d: d["match"].update(levels="hard"), "^match.levels: must be a list of two"),
        (lambda d: d["match"].update(levels=["hard", "expert"]), "^levels: must be two of"),
        # The physics of a saved match has the same limits as a scene's.
        (lambda d: d["match"]["physics"].update(mu_slide=5e-324),
         "physics.mu_slide: must be at least"),
        (lambda d: d["match"]["physics"].update(g=1e6), "physics.g: must be at most 100"),
    ],
)
def test_bad_saved_match(change, words) -> None:
    d = json.loads(json.dumps(Match("8ball").to_json()))
    change(d)
    with pytest.raises(ValueError, match=words):
        Match.from_json(d)


def test_warning_before_a_third_foul() -> None:
    m = Match("9ball", three_foul=True, players=("Ann", "Bob"))
    assert m.warning() is None
    setup(m, {**SCRATCH, "1": (1.0, 0.6), "9": (0.5, 1.0)}, fouls=(1, 2))
    assert m.warning() is None  # Ann shoots, on one foul
    m.state = replace(m.state, shooter=1)
    assert m.warning() == 1
    assert "Bob is on two fouls" in words.foul_warning(words.voice(m.players), m.warning())
    assert words.foul_warning(words.voice(("Ann", "You")), 1).startswith("You are on two fouls")
    m = Match("9ball", players=("Ann", "Bob"))  # no rule, no warning
    m.state = replace(m.state, fouls=(2, 2))
    assert m.warning() is None


# ------------------------------------------------------------------------------ properties

coord_x = st.floats(-0.05, L + 0.05, allow_nan=False)
coord_y = st.floats(-0.05, W + 0.05, allow_nan=False)


@given(x=coord_x, y=coord_y, area=st.sampled_from(["anywhere", "kitchen"]))
def test_an_accepted_placement_makes_a_valid_scene(x: float, y: float, area: str) -> None:
    m = Match("8ball", seed=1)
    m.ball_in_hand = area
    if m.placement_error(x, y) is None:
        m.place_cue(x, y)
        scene = load_scene(m.scene_dict())  # raises on an overlap or a ball off the table
        assert area == "anywhere" or x <= L / 4
        for name, p, n in lay.mouth_lines(T):
            assert float(np.dot(scene.pos[0] - p, n)) >= R - 1e-9, name


def test_the_placement_rule_at_its_edges() -> None:
    # Exactly on the head string is in the kitchen; touching a ball or a cushion nose is fine;
    # the margin the AI keeps refuses those.
    others, radii = np.array([[0.5, 0.6]]), np.array([R])
    spots = [[lay.head_string(T), 0.6],  # on the head string
             [0.5 - 2 * R, 0.6],  # touching the ball (straight along x)
             [0.3, R],  # touching the cushion nose
             [lay.head_string(T) + 1e-12, 0.3]]  # just past the head string
    assert lay.head_string(T) == L / 4 == HEAD[0]
    assert lay.spots_ok(T, spots, R, "kitchen", others, radii).tolist() == \
        [True, True, True, False]
    assert lay.spots_ok(T, spots, R, "anywhere", others, radii).tolist() == [True] * 4
    assert not lay.spots_ok(T, spots[1:3], R, "anywhere", others, radii, 1e-3).any()
    for (x, y), ok in zip(spots, [True, True, True, False], strict=True):
        err = lay.placement_error(T, x, y, R, "kitchen", {"1": (0.5, 0.6, R)})
        assert (err is None) == ok, err


@given(x=coord_x, y=coord_y, area=st.sampled_from(["anywhere", "kitchen"]),
       margin=st.sampled_from([0.0, 1e-3]))
def test_one_placement_rule_for_one_spot_and_for_many(x: float, y: float, area: str,
                                                      margin: float) -> None:
    # The game's check of a spot (with its reason) and the AI's of many spots are one rule;
    # the AI's margin only ever refuses more.
    m = Match("8ball", seed=1)
    m.ball_in_hand = area
    on = m.on_table.copy()
    on[m.index("cue")] = False
    ok = lay.spots_ok(T, [[x, y]], R, area, m.pos[on], m.radius[on], margin)[0]
    legal = m.placement_error(x, y) is None
    assert ok == legal if margin == 0 else (not ok or legal)


@given(st.lists(st.tuples(st.floats(FOOT[0] - 0.3, L - R), st.floats(W / 2 - 0.1, W / 2 + 0.1)),
                max_size=8))
def test_a_respot_never_overlaps(others: list) -> None:
    pts = np.array(others, float).reshape(-1, 2)
    x, y = lay.respot_point(T, R, pts, np.full(len(pts), R))
    assert y == W / 2 and R <= x <= L - R
    if len(pts):
        assert (np.hypot(pts[:, 0] - x, pts[:, 1] - y) >= 2 * R - 1e-9).all()
    # Nothing free lies between the spot and the chosen point (it is the nearest behind).
    if x > FOOT[0]:
        for z in np.linspace(FOOT[0], x, 50)[:-1]:
            assert len(pts) and (np.hypot(pts[:, 0] - z, pts[:, 1] - y) < 2 * R - 1e-9).any()


def test_eight_on_the_break_re_racks_for_the_same_breaker_in_that_variant() -> None:
    m = Match("8ball", eight_break="rerack")
    setup(m, {"cue": BEHIND, "8": NEAR_POCKET, "4": FOOT, "1": (0.4, 1.0)}, is_break=True)
    out = m.begin(POT).finish()
    assert m.history[0]["outcome"] == out.to_json()  # the verdict played is recorded
    assert out.rerack and out.respot == () and out.next_shooter == 0
    assert out.reason.endswith("the 8 on the break: re-racked, player 0 breaks again")
    assert m.on_table.all() and m.state.is_break and m.shooter == 0
    assert m.ball_in_hand == "kitchen"
    assert at(m, "8") != NEAR_POCKET
    back = Match.from_json(json.loads(json.dumps(m.to_json())))
    assert back.eight_break == "rerack"
    assert replay(m.to_json())[0]["ok"]
    with pytest.raises(ValueError, match="eight_break"):
        Match("8ball", eight_break="maybe")


def test_a_record_from_before_the_re_rack_rule_loads_and_replays() -> None:
    # Played when the match re-racked after the referee: its record holds the re-spot
    # verdict, and its game blocks name no variant (which reads as the re-spot).
    data = json.loads((RECORDS / "eight_break_rerack_before_the_rule.json").read_text())
    assert data["shots"][0]["outcome"]["respot"] == ["8"]
    assert "eight_break" not in data["shots"][0]["scene"]["game"]
    assert all(r["ok"] for r in replay(data))
    m = Match.from_json(data)
    assert m.eight_break == "rerack" and m.state.is_break and m.state.eight_break == "rerack"
    assert m.last_outcome.respot == ("8",) and not m.last_outcome.rerack


def test_a_player_who_concedes_gives_the_other_the_match_and_an_end_stays_as_it_was() -> None:
    m = Match("9ball", frames=3, seed=1)
    run = m.begin(Shot(6.0, 0.0))
    with pytest.raises(ValueError, match="a shot is still running"):
        m.concede(0)  # a shot first ends
    run.finish()
    scores = list(m.scores)
    m.concede(1)
    assert (m.winner, m.conceded, m.scores) == (0, 1, scores)  # the frames as they stood
    m.concede(0)  # over: nothing changes
    assert (m.winner, m.conceded) == (0, 1)
    with pytest.raises(ValueError, match="player must be 0 or 1"):
        Match("8ball").concede(2)
