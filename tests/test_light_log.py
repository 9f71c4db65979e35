"""The light event log (`Engine(record="light")`): the full log's events without the balls'
states, on the geometry games are made of, and the same verdicts from the referee."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from termpool.physics.engine import Engine
from termpool.physics.log import LIGHT
from termpool.physics.params import BALL_RADIUS as R
from termpool.rules.common import State
from termpool.rules.events import summarize
from termpool.rules.referee import judge, load_game_scene, verdict
from termpool.scene import load_scene

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _kept(ev) -> tuple:
    """The fields of an event the light log keeps."""
    return (ev.kind, ev.t, ev.table, ev.balls, ev.cushion, ev.feature, ev.pocket)


def _both(sc, pos=None, vel=None, w=None) -> tuple[Engine, Engine]:
    """The scene (or a batch of its balls) run to rest at the game's step, full and light."""
    out = []
    for record in (True, LIGHT):
        eng = Engine(sc.table, sc.physics, sc.pos if pos is None else pos,
                     sc.vel if vel is None else vel, sc.w if w is None else w, sc.radius,
                     sc.mass, record=record)
        eng.run(1 / 60)
        out.append(eng)
    return out[0], out[1]


def _row(ids: list[str], x0: float, y: float, gap: float = 0.0) -> list[dict]:
    """Balls `ids` in a row along y, each frozen to the next (centres 2R apart, plus gap)."""
    return [{"id": b, "x": x0 + k * (2 * R + gap), "y": y} for k, b in enumerate(ids)]


SCENES = {
    # A full 8-ball rack on the foot spot and a 9-ball diamond, broken straight at the apex.
    "8-ball break": {"table": "9ft", "balls": "8ball", "shot": {"speed": 8.0, "angle": 0}},
    "9-ball break": {"table": "9ft", "balls": "9ball", "shot": {"speed": 7.0, "angle": 0}},
    # A straight stun into a row of frozen balls (a cradle), and a frozen pair at the foot
    # rail's middle driven into it along the table's centre line.
    "frozen row": {"table": "9ft", "balls": [{"id": "cue", "x": 0.6, "y": 0.635},
                                             *_row(["1", "2", "3", "4"], 1.4, 0.635)],
                   "shot": {"speed": 3.0, "angle": 0}},
    "frozen at the rail": {"table": "9ft", "balls": [{"id": "cue", "x": 1.8, "y": 0.635},
                                                     *_row(["1", "2"], 2.54 - 3 * R, 0.635)],
                           "shot": {"speed": 2.0, "angle": 0}},
}


@pytest.mark.parametrize("name", sorted(SCENES))
def test_the_light_log_is_the_full_log_without_states(name):
    sc = load_scene(SCENES[name])
    full, light = _both(sc)
    assert [_kept(ev) for ev in light.log[0]] == [_kept(ev) for ev in full.log[0]]
    assert all(ev.states == () for ev in light.log[0])
    assert all(len(ev.states) == len(ev.balls) for ev in full.log[0])
    kinds = {ev.kind.value for ev in full.log[0]}
    assert "ball_ball" in kinds and "cushion" in kinds
    # The log changes nothing the balls do.
    assert np.array_equal(light.pos, full.pos) and np.array_equal(light.state, full.state)
    assert (light.passes, light.steps) == (full.passes, full.steps)
    # The referee's verdict on the shot as a break and as an ordinary shot of an open table.
    for state in (State(mode="8ball", is_break=True), State(mode="8ball"),
                  State(mode="9ball", is_break=True)):
        got = [judge(state, summarize(eng.log[0], sc.ids, is_break=state.is_break))
               for eng in (full, light)]
        assert got[0] == got[1]


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.json")), ids=lambda p: p.name)
def test_the_referee_gives_the_same_verdict_from_either_log(path):
    # The examples include a straight stun pot, a scratch and both games' breaks.
    sc = load_game_scene(path)
    full, light = _both(sc)
    assert [_kept(ev) for ev in light.log[0]] == [_kept(ev) for ev in full.log[0]]
    if sc.game is not None:
        assert verdict(sc.game, sc.ids, light.log[0]) == verdict(sc.game, sc.ids, full.log[0])


def test_a_batch_of_breaks_logs_the_same_events_either_way():
    from bench.speed import batch_breaks, break_scene

    sc = break_scene()
    full, light = _both(sc, *batch_breaks(sc, 16))
    for b in range(16):
        assert [_kept(ev) for ev in light.log[b]] == [_kept(ev) for ev in full.log[b]]
        assert all(ev.states == () for ev in light.log[b])
        assert summarize(light.log[b], sc.ids, is_break=True) == \
            summarize(full.log[b], sc.ids, is_break=True)
    assert sum(len(log) for log in light.log) > 16 * 50


def test_a_light_log_written_out_has_no_states():
    sc = load_scene(SCENES["frozen row"])
    full, light = _both(sc)
    for a, b in zip(full.events[0], light.events[0], strict=True):
        assert b["balls"] == [] and {**a, "balls": []} == b


def test_the_computers_candidates_keep_the_light_log():
    from termpool.ai.balls import read_inputs
    from termpool.ai.candidates import break_cands, simulate
    from termpool.ai.levels import LEVELS

    sc = load_scene({"table": "9ft", "balls": "8ball"})
    state = State(mode="8ball", is_break=True)
    t = read_inputs(sc.table, sc.physics, sc.ids, sc.pos, sc.radius, sc.mass,
                    [True] * len(sc.ids), state, "easy", 0)
    eng = simulate(t, break_cands(t, ["1"], LEVELS["easy"]), sc.table, sc.physics)
    assert eng.log[0] and all(ev.states == () for log in eng.log for ev in log)


@pytest.mark.parametrize("bad", ["full", "", None, 2, "LIGHT"])
def test_a_bad_record_mode_is_named(bad):
    sc = load_scene(SCENES["frozen row"])
    with pytest.raises(ValueError, match="^record: "):
        Engine(sc.table, sc.physics, sc.pos, record=bad)
