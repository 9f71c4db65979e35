"""Every response model's array form against its plain-float form, bit for bit
(physics/models.py lists them): generated for each model of the registry, on random inputs
and on the exact geometry games are made of (frozen balls, balls exactly 2R apart, balls on a
rail, straight hits), for several physics."""

from __future__ import annotations

import numpy as np
import pytest

from termpool.physics import motion
from termpool.physics.models import MODELS
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics
from termpool.physics.state import EPS_U

R, M = BALL_RADIUS, BALL_MASS
K = 400  # random rows per family


def _bits(x) -> bytes:
    """The values' bits, NaNs made one NaN (a NaN's payload is no result); -0.0 kept."""
    a = np.asarray(x, dtype=float)
    return np.where(np.isnan(a), np.nan, a).tobytes()


def _rows(*cols) -> list[np.ndarray]:
    return [np.array(c, dtype=float) for c in cols]


def _ball_ball(rng) -> list[np.ndarray]:
    """Contacts: random ones (touching or sunk a little, closing, any spin), then exact ones:
    balls exactly 2R apart along an axis, the object ball frozen, stun and rolling hits
    straight and at a cut, grazing and parting pairs, a closing speed of exactly v_inelastic."""
    ri, rj = rng.uniform(0.02, 0.04, K), rng.uniform(0.02, 0.04, K)
    ang = rng.uniform(0, 2 * np.pi, K)
    n = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    pi = rng.uniform(1.0, 9.0, (K, 2))
    pj = pi + n * (ri + rj - rng.choice([0.0, 1e-7], K))[:, None]
    vi = rng.normal(0.0, 2.0, (K, 2)) + 2.0 * n
    vj = rng.normal(0.0, 2.0, (K, 2)) * rng.choice([1.0, 0.0], (K, 1))
    wi, wj = rng.normal(0.0, 80.0, (K, 3)), rng.normal(0.0, 80.0, (K, 3))
    mi, mj = rng.uniform(0.1, 0.2, K), rng.uniform(0.1, 0.2, K)
    rows = list(zip(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, strict=True))
    x0, y0 = 1.25, 0.635
    for d in ((2 * R, 0.0), (0.0, 2 * R), (-2 * R, 0.0), (0.0, -2 * R)):
        ux, uy = np.sign(d[0]), np.sign(d[1])
        for speed in (8.0, 2.0, 0.005, 1e-7, 0.0):
            v = (speed * ux, speed * uy)
            roll = (-v[1] / R, v[0] / R, 0.0)
            cut = (speed * ux + 0.3 * uy, speed * uy + 0.3 * ux)  # a cut, also grazing at 0
            for vi_, wi_ in ((v, (0.0, 0.0, 0.0)), (v, roll), (cut, (0.0, 0.0, 20.0)),
                             ((-v[0], -v[1]), (0.0, 0.0, 0.0))):  # the last ones part
                rows.append(((x0, y0), (x0 + d[0], y0 + d[1]), vi_, (0.0, 0.0), wi_,
                             (0.0, 0.0, 0.0), R, R, M, M))
    return _rows(*zip(*rows, strict=True))


def _sink(rng) -> list[np.ndarray]:
    """Pairs exactly touching, sunk by up to 2 SINK, or apart; any masses."""
    pi, pj, _, _, _, _, ri, rj, mi, mj = _ball_ball(rng)
    d = pj - pi
    u = d / np.hypot(d[:, 0], d[:, 1])[:, None]
    gap = rng.choice([0.0, -4.5e-7, -9e-7, 1e-6, 0.0], len(pi))
    pj = pi + u * (ri + rj + gap)[:, None]
    return [pi, pj, ri, rj, mi, mj]


def _cushion(rng) -> list[np.ndarray]:
    """Balls meeting a rail, jaw or jaw tip: random normals, speeds and spins, some slow or
    with a nearly still contact point; then balls on the four rails exactly: rolling along
    them, frozen to them, struck straight in, spinning on the spot, closing at exactly
    v_inelastic."""
    k = 3 * K
    n = rng.normal(0.0, 1.0, (k, 2))
    n /= np.hypot(n[:, 0], n[:, 1])[:, None]
    v = rng.normal(0.0, 2.0, (k, 2)) - rng.uniform(0.0, 3.0, (k, 1)) * n
    v[::7] *= 1e-3
    w = rng.normal(0.0, 80.0, (k, 3))
    w[::5] *= 1e-9
    r, m = rng.uniform(0.02, 0.04, k), rng.uniform(0.1, 0.2, k)
    rows = list(zip(n, v, w, r, m, strict=True))
    for nn in ((0.0, 1.0), (0.0, -1.0), (1.0, 0.0), (-1.0, 0.0)):
        along = (nn[1], -nn[0])
        for speed in (3.0, 0.005, 1e-6, 0.0):
            into = (-speed * nn[0], -speed * nn[1])
            par = (speed * along[0], speed * along[1])
            for v_, w_ in ((into, (0.0, 0.0, 0.0)), (into, (-into[1] / R, into[0] / R, 0.0)),
                           (par, (-par[1] / R, par[0] / R, 0.0)), ((0.0, 0.0), (0.0, 0.0, 30.0)),
                           ((into[0] + par[0], into[1] + par[1]), (0.0, 0.0, -40.0))):
                rows.append((nn, v_, w_, R, M))
    return _rows(*zip(*rows, strict=True))


def _start(rng) -> list[np.ndarray]:
    """Balls starting every kind of motion: random ones (sliding, rolling exactly, a slip under
    EPS_U, side spin only, nothing, some pocketed), then exact ones: frozen balls, rolling
    along an axis, a slip of exactly EPS_U, spinning on the spot, at t = 0."""
    t = rng.uniform(0.0, 5.0, K)
    p = rng.uniform(1.0, 9.0, (K, 2))
    v = rng.normal(0.0, 2.0, (K, 2)) * rng.choice([1.0, 1e-3, 1e-9, 0.0], (K, 1))
    w = rng.normal(0.0, 60.0, (K, 3))
    kind = rng.integers(0, 5, K)
    roll = np.stack([-v[:, 1], v[:, 0]], axis=1) / R
    w[kind == 1, :2] = roll[kind == 1]
    tiny = rng.uniform(0.0, EPS_U, K)
    w[kind == 2, :2] = roll[kind == 2] + tiny[kind == 2, None] / R * np.array([0.6, -0.8])
    v[kind >= 3] = 0.0
    w[kind >= 3, :2] = 0.0
    w[kind == 4, 2] = 0.0
    rate = np.full(K, 2.5 * 0.0127 * 9.81 / R)
    pocketed = rng.random(K) < 0.05
    rows = list(zip(t, p, v, w, np.full(K, R), rate, pocketed, strict=True))
    for speed in (2.0, EPS_U, 1e-9, 0.0):
        for d in ((1.0, 0.0), (0.0, -1.0)):
            v_ = (speed * d[0], speed * d[1])
            for w_ in ((0.0, 0.0, 0.0), (-v_[1] / R, v_[0] / R, 0.0), (0.0, 0.0, 25.0),
                       (-v_[1] / R, v_[0] / R, -3.0)):
                for pocketed_ in (False, True):
                    rows.append((0.0, (1.25, 0.635), v_, w_, R, rate[0], pocketed_))
    return _rows(*zip(*rows, strict=True))


def _at(rng) -> list[np.ndarray]:
    """Motions started as `_start` gives them, evaluated before their clock (a completed tiny
    slide), at it, inside their state and beyond its end."""
    t, p, v, w, r, rate, pocketed = _start(rng)
    with np.errstate(all="ignore"):
        _, _, rows = motion.start_many(Physics(), t, p, v, w, r, rate, pocketed.astype(bool))
    rows = np.concatenate([rows, rate[:, None], r[:, None], np.full((len(r), 1), M)], axis=1)
    when = rows[:, 0] + rng.choice([-1e-4, 0.0, 0.3, 7.0], len(r))
    return [rows, when]


def _lift(rng) -> list[np.ndarray]:
    """Balls at a rail, jaw or tip: exactly at their reach, sunk by up to 2 SINK, or clear;
    normals along the axes (rails) and any way (jaws, tips)."""
    k = K
    n = rng.normal(0.0, 1.0, (k, 2))
    n /= np.hypot(n[:, 0], n[:, 1])[:, None]
    axes = np.array([[0.0, 1.0], [0.0, -1.0], [1.0, 0.0], [-1.0, 0.0]])
    n[: k // 2] = axes[rng.integers(0, 4, k // 2)]
    ref = rng.uniform(0.0, 2.5, (k, 2))
    ref[: k // 4] = np.round(ref[: k // 4], 1)  # exact decimals, as a table's rails
    rc = rng.uniform(0.02, 0.03, k)
    rc[: k // 4] = R
    sunk = rng.choice([0.0, 4.5e-7, 9e-7, -1e-6, -0.5], k)
    along = rng.normal(0.0, 0.3, k)[:, None] * np.stack([-n[:, 1], n[:, 0]], axis=1)
    along[: k // 8] = 0.0
    p = ref + along + n * (rc - sunk)[:, None]
    return [p, ref, n, rc]


def _pocket(rng) -> list[np.ndarray]:
    from termpool.physics.table import Table
    return [np.concatenate([Table.preset(s).hole_c for s in ("7ft", "8ft", "9ft")])]


def _transition(rng) -> list[np.ndarray]:
    """Motions at their ends: balls started as `_start` gives them, in every state."""
    t, p, v, w, r, rate, pocketed = _start(rng)
    with np.errstate(all="ignore"):
        st, _, _ = motion.start_many(Physics(), t, p, v, w.copy(), r, rate, pocketed.astype(bool))
    assert set(st.tolist()) == set(range(5))  # every state ends, a pocketed ball's never
    return [st.astype(float), v, w, r]


# Each family: its inputs, the physics it is run with, and how a form is called with them.
FAMILIES = {
    "ball_ball": (_ball_ball, [Physics(), Physics(e_ball=1.0, v_inelastic=0.0),
                               Physics(e_ball=0.0)]),
    "sink": (_sink, [None]),
    "start": (_start, [Physics(), Physics(mu_slide=0.0), Physics(mu_roll=0.0, mu_spin=0.0),
                       Physics(mu_slide=0.5, mu_roll=0.03, mu_spin=0.05, g=3.0)]),
    "at": (_at, [None]),
    "lift": (_lift, [None]),
    "pocket": (_pocket, [None]),
    "transition": (_transition, [None]),
    "cushion": (_cushion, [dict(e_cushion=0.85, mu_cushion=0.2),
                           dict(e_cushion=0.0, mu_cushion=0.6),
                           dict(e_cushion=1.0, mu_cushion=0.0, cushion_height=0.028575)]),
}


def _physics(family: str, name: str, ph):
    if family == "cushion":
        return Physics(cushion=name, **ph)
    if family == "ball_ball":
        return Physics(**{**ph.to_dict(), "ball_ball": name})
    return ph


def _call(family: str, form, args: list, ph):
    if family == "start":
        args[-1] = np.asarray(args[-1], dtype=bool) if isinstance(args[-1], np.ndarray) \
            else bool(args[-1])
        return form(ph, *args)
    if family == "transition":  # the state is an integer code
        args[0] = args[0].astype(np.int64) if isinstance(args[0], np.ndarray) else int(args[0])
    out = form(*args) if ph is None else form(*args, ph)
    return out if isinstance(out, tuple) else (out,)


def test_every_family_of_the_registry_has_its_generated_inputs():
    assert {m.family for m in MODELS} <= set(FAMILIES)
    assert len({(m.family, m.name) for m in MODELS}) == len(MODELS)


@pytest.mark.parametrize("model", MODELS, ids=[f"{m.family}-{m.name}" for m in MODELS])
@pytest.mark.parametrize("seed", [1, 2])
def test_the_array_and_plain_float_forms_of_every_model_agree_bit_for_bit(model, seed):
    make, physics = FAMILIES[model.family]
    args = make(np.random.default_rng(seed))
    for ph in physics:
        ph = _physics(model.family, model.name, ph)
        with np.errstate(all="ignore"):  # as the engine runs them
            many = _call(model.family, model.many, [a.copy() for a in args], ph)
        for k in range(len(args[0])):
            one = _call(model.family, model.one, [a[k].tolist() for a in args], ph)
            assert len(one) == len(many)
            for x, y in zip(one, many, strict=True):
                assert _bits(x) == _bits(y[k]), (k, [a[k].tolist() for a in args])
