"""Every response model of the engine, by the event it answers: the array form (over K events at
once) and the plain-float form (one event, lists in and lists out) side by side. The engine
runs whichever is faster for the events at hand, so the two must agree bit for bit;
`tests/test_models.py` holds every model listed here to that on generated inputs. A model
added to a family (a cushion in `cushion.MODELS`, a ball-ball model in `ball_ball.MODELS`) is
listed here by itself.

The families and their signatures (arrays over K, or one event's values; ph a `Physics`):

    ball_ball  (pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, ph) -> (vi, vj, wi, wj)
    sink       (pi, pj, ri, rj, mi, mj) -> (pi, pj)    two balls' overlap undone
    cushion    (n, v, w, r, m, ph) -> (v, w)           n the feature's normal into the table
    lift       (p, ref, n, rc) -> p                    a ball's sink into a cushion undone
    pocket     (centre) -> (p, v, w)                   a ball drops into a hole
    transition (state, v, w, R) -> (v, w)              a motion state ends
    start      (ph, t, p, v, w, R, rate, pocketed) -> (state, t_trans, row)
                                                       a ball's motion on the cloth begins
    at         (row, t) -> (p, v, w)                   a ball's motion evaluated
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from termpool.physics import motion, pocket, transition
from termpool.physics.ball_ball import MODELS as BALL_BALL
from termpool.physics.ball_ball import sink
from termpool.physics.cushion import MODELS as CUSHIONS
from termpool.physics.cushion import sink as cushion_sink


@dataclass(frozen=True)
class Model:
    family: str  # the event it answers, which fixes its signature (above)
    name: str
    many: Callable[..., tuple]
    one: Callable[..., tuple]


def _models() -> tuple[Model, ...]:
    out = [Model("ball_ball", k, m.collide, m.collide_one) for k, m in BALL_BALL.items()]
    out.append(Model("sink", "inverse_mass", sink.undo, sink.undo_one))
    # A cushion model's `bounce` may hand a few balls to `bounce_one` itself (mathavan): its
    # array form proper is then `bounce_many`.
    out += [Model("cushion", k, getattr(m, "bounce_many", m.bounce), m.bounce_one)
            for k, m in CUSHIONS.items()]
    out.append(Model("lift", "normal", cushion_sink.lift, cushion_sink.lift_one))
    out.append(Model("pocket", "drop", pocket.drop, pocket.drop_one))
    out.append(Model("transition", "cloth", transition.end, transition.end_one))
    out.append(Model("start", "cloth", motion.start_many, motion.start))
    out.append(Model("at", "cloth", motion.at_many, motion.at))
    return tuple(out)


MODELS = _models()
