"""Cushion response models: how a ball's velocity and spin change when it meets a rail, a jaw or
a jaw tip. A scene picks one with `"physics": {"cushion": name}`.

Each model is one module with two functions of the same signature:

    bounce(n, v, w, r, m, ph) -> (v, w)       arrays over K balls: n (K, 2) horizontal unit
                                              normals into the table, v (K, 2), w (K, 3),
                                              r and m (K,), ph a `Physics`
                                              (typed as `model.CushionPhysics`)
    bounce_one(n, v, w, r, m, ph) -> (v, w)   one ball in plain floats (lists in, lists out)

and two numbers, E_CUSHION and MU_CUSHION: the restitution and nose friction a scene gets when
it gives none (each model means its own thing by them). The two functions must agree bit for
bit (`tests/test_models.py` holds them to it), must never add energy, and must leave the ball
not moving into the cushion (`tests/test_cushion.py`). To add a model, write its module and
list it in MODELS.
"""

from __future__ import annotations

from types import ModuleType

from termpool.physics.cushion import han, mathavan, simple

MODELS: dict[str, ModuleType] = {"simple": simple, "han": han, "mathavan": mathavan}
