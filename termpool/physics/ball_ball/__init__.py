"""Ball-ball contact models: how two balls' velocities and spins change when they meet. A scene
picks one with `"physics": {"ball_ball": name}`.

Each model is one module with two functions of the same signature:

    collide(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, ph) -> (vi, vj, wi, wj)
        arrays over K contacts: positions p (K, 2), velocities v (K, 2), spins w (K, 3),
        radii r and masses m (K,); ph the physics (e_ball, v_inelastic)
    collide_one(...) -> (vi, vj, wi, wj)
        one contact in plain floats (lists in, lists out)

Impulses act at the contact point of rigid spheres, along the line of centres; a closing
speed at or below `v_inelastic` is met perfectly inelastically. Vertical components of
linear velocity that an impulse would give are absorbed by the slate (no jumping), which can
only remove energy. The two functions must agree bit for bit (`tests/test_models.py`). To add
a model, write its module and list it in MODELS.
"""

from __future__ import annotations

from types import ModuleType

from termpool.physics.ball_ball import frictional, frictionless

MODELS: dict[str, ModuleType] = {"frictional": frictional, "frictionless": frictionless}
