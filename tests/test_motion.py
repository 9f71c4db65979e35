"""The engine's plain-float paths for one or two balls against its array paths, bit for bit.

A batch must give each table exactly what the table gives alone, and alone a pass usually
takes the plain-float path while in a batch it takes the array path: the two must agree to
the last bit on every kind of motion (sliding, rolling, tiny slips completed at once,
spinning, still, pocketed) and on frictionless cloth.
"""

from __future__ import annotations

import numpy as np
import pytest

from termpool.physics import motion, roots
from termpool.physics.ball_ball import MODELS as BALL_BALL
from termpool.physics.balls import FEW
from termpool.physics.cushion import MODELS
from termpool.physics.engine import Engine
from termpool.physics.params import BALL_RADIUS, Physics
from termpool.physics.roots import SINK, first_contact, first_contact_few
from termpool.physics.state import EPS_U, POCKETED
from termpool.physics.table import Table
from termpool.scene import load_scene

TABLE = Table(length=20.0, width=10.0, pockets="none")
K = 400  # balls started per case


def _inputs(seed: int):
    """Random starts of K balls covering every kind of motion."""
    rng = np.random.default_rng(seed)
    R = BALL_RADIUS
    p = rng.uniform(1.0, 9.0, (K, 2))
    v = rng.normal(0.0, 2.0, (K, 2)) * rng.choice([1.0, 1e-3, 1e-9, 0.0], (K, 1))
    w = rng.normal(0.0, 60.0, (K, 3))
    kind = rng.integers(0, 5, K)
    # 1: rolling exactly; 2: a slip under EPS_U (completed at once); 3: side spin only;
    # 4: nothing at all.
    roll = np.stack([-v[:, 1], v[:, 0]], axis=1) / R
    w[kind == 1, :2] = roll[kind == 1]
    tiny = rng.uniform(0.0, EPS_U, K)
    w[kind == 2, :2] = roll[kind == 2] + tiny[kind == 2, None] / R * np.array([0.6, -0.8])
    v[kind >= 3] = 0.0
    w[kind >= 3, :2] = 0.0
    w[kind == 4, 2] = 0.0
    t = rng.uniform(0.0, 5.0, K)
    pocketed = rng.random(K) < 0.05
    return t, p, v, w, pocketed


def _started(physics: Physics, seed: int, path: str) -> Engine:
    t, p, v, w, pocketed = _inputs(seed)
    eng = Engine(TABLE, physics, np.column_stack([np.arange(K) * 0.001 + 1, np.ones(K)]))
    b, i = np.zeros(K, dtype=np.int64), np.arange(K)
    eng.state[b, i] = np.where(pocketed, POCKETED, eng.state[b, i])
    if path == "few":
        for n in range(0, K, 2):  # two balls per call, as a ball-ball contact starts them
            s = slice(n, n + 2)
            eng.balls.set_few(b[s], i[s], t[s], p[s], v[s], w[s].copy())
    else:
        eng.balls.set_many(b, i, t, p, v, w.copy())
    return eng


@pytest.mark.parametrize("physics", [
    Physics(),
    Physics(mu_slide=0.0),
    Physics(mu_roll=0.0, mu_spin=0.0),
    Physics(mu_slide=0.5, mu_roll=0.03, mu_spin=0.05, g=3.0),
], ids=["default", "frictionless", "no-roll-no-spin-friction", "other"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_starting_one_ball_in_floats_matches_the_array_path_bit_for_bit(physics, seed):
    with np.errstate(all="ignore"):  # as the engine runs: infinities stand for "never"
        few = _started(physics, seed, "few")
        many = _started(physics, seed, "many")
    assert np.array_equal(few.state, many.state)
    assert np.array_equal(few.t_trans, many.t_trans)
    assert np.array_equal(few.balls.motion, many.balls.motion, equal_nan=True)
    # The cases are all there: every state, and (with cloth friction) tiny slips completed
    # at once, which move the ball's clock on.
    assert set(np.unique(many.state).tolist()) == {0, 1, 2, 3, 4}
    t = _inputs(seed)[0]
    assert (many.balls.t0[0] > t).any() == (physics.mu_slide > 0)


@pytest.mark.parametrize("seed", [4, 5])
def test_evaluating_one_ball_in_floats_matches_the_array_path_bit_for_bit(seed):
    with np.errstate(all="ignore"):
        eng = _started(Physics(), seed, "many")
    rng = np.random.default_rng(seed)
    b, i = np.zeros(K, dtype=np.int64), np.arange(K)
    # Before a ball's clock (a completed tiny slide), inside its motion and beyond its end.
    t = eng.balls.t0[0] + rng.choice([-1e-4, 0.0, 0.3, 7.0], K)
    p, v, w = eng.balls.eval(b, i, t)
    for n, row in enumerate(eng.balls.motion[0].tolist()):
        assert motion.at(row, float(t[n])) == (p[n].tolist(), v[n].tolist(), w[n].tolist())


@pytest.mark.parametrize("seed", [4, 5])
def test_evaluating_whole_tables_in_planes_matches_eval_bit_for_bit(seed):
    """Balls.planes (the renewals' evaluation of every ball of some tables, as six planes)
    gives what `eval` gives, bit for bit, at clocks before, inside and beyond the motions."""
    with np.errstate(all="ignore"):
        eng = _started(Physics(), seed, "many")
    rows = eng.balls.motion.reshape(20, K // 20, -1)  # the K balls as 20 tables
    balls = eng.balls
    balls.motion, balls.N = rows, K // 20
    tabs = np.array([3, 0, 17, 3])
    t = np.array([[-1e-4], [0.0], [0.3], [7.0]]) + rows[tabs, :1, 0]
    Q = balls.planes(tabs, t)
    b, i = np.divmod(np.arange(tabs.size * balls.N), balls.N)
    p, v, _ = motion.at_many(rows[tabs[b], i], t[b, 0], spin=False)
    assert Q.shape == (6, tabs.size * balls.N)
    a = rows[tabs[b], i, motion.Col.AX:motion.Col.AY + 1]
    for plane, want in ((Q[:2], p), (Q[2:4], v), (Q[4:], a)):
        assert np.ascontiguousarray(plane.T).tobytes() == np.ascontiguousarray(want).tobytes()


@pytest.mark.parametrize("physics", [Physics(), Physics(mu_slide=0.0)],
                         ids=["default", "frictionless"])
@pytest.mark.parametrize("seed", [6, 7])
def test_transitions_in_floats_match_the_array_path_bit_for_bit(physics, seed):
    engines = []
    for path in ("few", "many"):
        with np.errstate(all="ignore"):
            eng = _started(physics, seed, "many")
            b, i = np.nonzero(np.isfinite(eng.t_trans))
            eng.tb[:] = 0.0
            for n in range(i.size):  # each ball at its own transition time
                eng.tb[0] = eng.t_trans[0, i[n]]
                one = slice(n, n + 1)
                if path == "few":
                    eng.respond.transition_few(b[one], i[one])
                else:
                    eng.respond.transition(np.repeat(b[one], FEW + 1), np.repeat(i[one], FEW + 1))
        engines.append(eng)
    few, many = engines
    assert i.size > K // 4  # transitions of every kind were run
    assert np.array_equal(few.state, many.state)
    assert np.array_equal(few.t_trans, many.t_trans)
    assert np.array_equal(few.balls.motion, many.balls.motion, equal_nan=True)


def _contacts(seed: int, k: int = 300):
    """k ball-ball contacts: touching (or sunk a little) and closing, random spins."""
    rng = np.random.default_rng(seed)
    ri = rng.uniform(0.02, 0.04, k)
    rj = rng.uniform(0.02, 0.04, k)
    ang = rng.uniform(0, 2 * np.pi, k)
    n = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    pi = rng.uniform(1.0, 9.0, (k, 2))
    pj = pi + n * (ri + rj - rng.choice([0.0, 1e-7], k))[:, None]
    vi = rng.normal(0.0, 2.0, (k, 2)) + 2.0 * n
    vj = rng.normal(0.0, 2.0, (k, 2)) * rng.choice([1.0, 0.0], (k, 1))
    wi = rng.normal(0.0, 80.0, (k, 3))
    wj = rng.normal(0.0, 80.0, (k, 3))
    mi = rng.uniform(0.1, 0.2, k)
    mj = rng.uniform(0.1, 0.2, k)
    return pi, pj, vi, vj, wi, wj, ri, rj, mi, mj


@pytest.mark.parametrize("frictional", [True, False])
@pytest.mark.parametrize("seed", [8, 9])
def test_one_collision_in_floats_matches_the_array_path_bit_for_bit(frictional, seed):
    args = _contacts(seed)
    ph = Physics(e_ball=0.95, v_inelastic=0.005,
                 ball_ball="frictional" if frictional else "frictionless")
    model = BALL_BALL[ph.ball_ball]
    many = model.collide(*args, ph)
    for n in range(len(args[0])):
        one = model.collide_one(*(x[n].tolist() for x in args), ph)
        assert one == tuple(x[n].tolist() for x in many)


@pytest.mark.parametrize("seed", [10, 11])
def test_contacts_handled_one_by_one_match_a_batch_bit_for_bit(seed):
    pi, pj, vi, vj, wi, wj, ri, rj, mi, mj = _contacts(seed)
    k = len(pi)
    engines = []
    for path in ("one by one", "together"):
        eng = Engine(TABLE, Physics(), np.stack([pi, pj], axis=1), np.stack([vi, vj], axis=1),
                     np.stack([wi, wj], axis=1), np.stack([ri, rj], axis=1),
                     np.stack([mi, mj], axis=1))
        b, i, j = np.arange(k), np.zeros(k, dtype=np.int64), np.ones(k, dtype=np.int64)
        with np.errstate(all="ignore"):
            if path == "one by one":
                for n in range(k):
                    eng.slow.pairs(b[n:n + 1], i[n:n + 1], j[n:n + 1], b[n:n + 1], None)
            else:
                eng.slow.pairs(b, i, j, b, None)
        engines.append(eng)
    one, together = engines
    assert np.array_equal(one.state, together.state)
    assert np.array_equal(one.t_trans, together.t_trans)
    assert np.array_equal(one.balls.motion, together.balls.motion)
    assert (one.balls.v0[:, 0] != vi).any(axis=1).mean() > 0.7  # most contacts were fast ones


@pytest.mark.parametrize("seed", [12, 13])
def test_cushion_lines_of_a_few_balls_in_floats_match_the_array_path_bit_for_bit(seed):
    rng = np.random.default_rng(seed)
    table = Table.preset("9ft")
    eng = Engine(table, Physics(), [[1.0, 0.6]])
    k = 600
    rc = np.full(k, float(eng.rc[0, 0]))
    # Balls anywhere on the bed, and balls touching a rail (or just off it) exactly.
    p = np.column_stack([rng.uniform(-0.05, table.length + 0.05, k),
                         rng.uniform(-0.05, table.width + 0.05, k)])
    rail = rng.random(k) < 0.3
    p[rail, 1] = np.where(rng.random(rail.sum()) < 0.5, rc[rail], table.width - rc[rail])
    p[rail, 1] += rng.choice([0.0, 5e-10, -2e-7, 1e-6], rail.sum())
    v = rng.normal(0.0, 1.5, (k, 2)) * rng.choice([1.0, 0.01], (k, 1))
    a = rng.normal(0.0, 2.0, (k, 2)) * rng.choice([1.0, 0.05, 0.0], (k, 1))
    horizon = rng.uniform(0.01, 2.0, k)
    reach = np.hypot(v[:, 0], v[:, 1]) * horizon + 0.5 * np.hypot(a[:, 0], a[:, 1]) * horizon ** 2
    reach += rc
    with np.errstate(all="ignore"):
        many = eng.features.lines(np.concatenate([p.T, v.T, a.T]), rc, horizon)  # (planes)
        few = np.concatenate([eng.features.lines_few(p[n:n + 2], v[n:n + 2], a[n:n + 2],
                                                     rc[n:n + 2], horizon[n:n + 2],
                                                     reach[n:n + 2])
                              for n in range(0, k, 2)])
    assert np.array_equal(few, many)
    assert np.isfinite(many).sum() > k // 4  # many balls do meet a cushion
    assert (many == 0).any()  # and some are resting against one, closing


@pytest.mark.parametrize("model", sorted(MODELS))
@pytest.mark.parametrize("seed", [14, 15])
def test_one_cushion_bounce_in_floats_matches_the_array_path_bit_for_bit(seed, model):
    rng = np.random.default_rng(seed)
    k = 1500
    n = rng.normal(0.0, 1.0, (k, 2))
    n /= np.hypot(n[:, 0], n[:, 1])[:, None]
    v = rng.normal(0.0, 2.0, (k, 2)) - rng.uniform(0.0, 3.0, (k, 1)) * n
    v[::7] *= 1e-3  # slow contacts, below v_inelastic
    w = rng.normal(0.0, 80.0, (k, 3))
    w[::5] *= 1e-9  # nearly still contact points
    r = rng.uniform(0.02, 0.04, k)
    m = rng.uniform(0.1, 0.2, k)
    mod = MODELS[model]
    many = getattr(mod, "bounce_many", mod.bounce)  # the array path, whatever the size
    for e, mu in ((0.85, 0.2), (0.0, 0.6), (1.0, 0.0)):
        ph = Physics(e_cushion=e, mu_cushion=mu, cushion=model)
        with np.errstate(all="ignore"):
            V, W = many(n, v, w, r, m, ph)
        for x in range(k):
            one = mod.bounce_one(n[x].tolist(), v[x].tolist(), w[x].tolist(), float(r[x]),
                                 float(m[x]), ph)
            assert one == (V[x].tolist(), W[x].tolist())


@pytest.mark.parametrize("model", sorted(MODELS))
@pytest.mark.parametrize("seed", [16, 17])
def test_cushion_bounces_one_by_one_match_a_batch_bit_for_bit(seed, model):
    rng = np.random.default_rng(seed)
    table = Table.preset("9ft")
    k = 1500
    # One ball per table, sent at the cushions from anywhere, some of them slowly.
    pos = np.column_stack([rng.uniform(0.1, table.length - 0.1, k),
                           rng.uniform(0.1, table.width - 0.1, k)])[:, None]
    vel = rng.normal(0.0, 2.0, (k, 1, 2)) * rng.choice([1.0, 0.002], (k, 1, 1))
    w = rng.normal(0.0, 60.0, (k, 1, 3))
    engines = []
    for path in ("one by one", "together"):
        eng = Engine(table, Physics(cushion=model), pos, vel, w)
        b = np.flatnonzero(np.isfinite(eng.t_cush[:, 0]))  # bounces, and balls pocketed
        eng.tb[b] = eng.t_cush[b, 0]
        i = np.zeros(b.size, dtype=np.int64)
        with np.errstate(all="ignore"):
            if path == "one by one":
                for n in range(b.size):
                    eng.respond.cushion(b[n:n + 1], i[n:n + 1])
            else:
                eng.respond.cushion(b, i)
        engines.append(eng)
    one, together = engines
    assert b.size > k // 5
    assert (one.f_cush[b, 0] >= one.features.nseg).any()  # jaw tips too
    assert (one.state[b, 0] == POCKETED).any() and (one.state[b, 0] != POCKETED).any()
    assert np.array_equal(one.state, together.state)
    assert np.array_equal(one.t_trans, together.t_trans)
    assert np.array_equal(one.balls.motion, together.balls.motion)


@pytest.mark.parametrize("field", ["radius", "mass"])
@pytest.mark.parametrize("bad", [0.0, -0.02, float("nan"), float("inf")])
def test_engine_refuses_a_radius_or_mass_that_is_not_positive(field, bad):
    # The plain-float paths divide by both, so they must be positive (as scenes ensure).
    with pytest.raises(ValueError, match=f"^{field}: must be positive and finite$"):
        Engine(TABLE, Physics(), [[1.0, 1.0], [2.0, 1.0]], **{field: [0.03, bad]})


def _relative_motions(seed: int, k: int = 3000):
    """Relative motions of k pairs or ball-and-point candidates: random ones, and the exact
    geometries games are made of (touching at exactly the contact distance or a rounding
    off it, sunk by SINK, resting with the pair pressed together or parting, at the same
    centre, at rest, and with an empty window)."""
    rng = np.random.default_rng(seed)
    dist = rng.choice([2 * BALL_RADIUS, BALL_RADIUS + 0.01, 0.06], k)
    ang = rng.uniform(0, 2 * np.pi, k)
    u = np.column_stack([np.cos(ang), np.sin(ang)])
    r = dist + rng.choice([0.0, 5e-10, -5e-10, -SINK, 1e-4, 0.3, 1.5], k)
    p = u * r[:, None]
    v = rng.normal(0.0, 2.0, (k, 2)) * rng.choice([1.0, 1e-3, 0.0], (k, 1))
    a = rng.normal(0.0, 3.0, (k, 2)) * rng.choice([1.0, 1e-7, 0.0], (k, 1))
    side = rng.random(k) < 0.2  # moving along the line of centres, exactly: head on or apart
    v[side] = -u[side] * rng.normal(0.0, 2.0, side.sum())[:, None]
    slide = rng.random(k) < 0.15  # tangent: no closing speed, pressed or pulled by a
    v[slide] = np.column_stack([-u[slide, 1], u[slide, 0]]) * rng.normal(0, 1, slide.sum())[:, None]
    a[slide] = u[slide] * rng.choice([-2.0, 2.0, 1e-8], slide.sum())[:, None]
    p[rng.random(k) < 0.01] = 0.0
    horizon = rng.uniform(0.0, 2.0, k) * rng.choice([1.0, 0.0], k, p=[0.95, 0.05])
    return p, v, a, dist, horizon


@pytest.mark.parametrize("pressed", [True, False])
@pytest.mark.parametrize("seed", [20, 21, 22])
def test_contact_times_of_a_few_in_floats_match_the_array_path_bit_for_bit(seed, pressed):
    p, v, a, dist, horizon = _relative_motions(seed)
    with np.errstate(all="ignore"):
        many = first_contact(p, v, a, dist, horizon, pressed=pressed)
        cands = list(zip(*p.T.tolist(), *v.T.tolist(), *a.T.tolist(), dist.tolist(),
                         horizon.tolist(), strict=True))
        few = [t for n in range(0, len(cands), 7)
               for t in first_contact_few(cands[n:n + 7], pressed=pressed)]
    assert np.array_equal(np.array(few), many)
    assert (many == 0).sum() > 50 and np.isfinite(many[many > 0]).sum() > 100  # both kinds


@pytest.mark.parametrize("seed", [23, 24, 25])
def test_predictions_of_a_few_balls_in_floats_match_the_array_path_bit_for_bit(seed):
    """A racked 9-ft table (frozen balls, pockets, jaw tips) with some balls moving and
    some pocketed: renewing one or two balls' predictions in plain floats gives the same
    times and features as the array path."""
    rng = np.random.default_rng(seed)
    scene = load_scene({"balls": "8ball", "shot": {"speed": 8.0}})
    n = len(scene.ids)
    pos = scene.pos.copy()
    pos[:6] = rng.uniform([0.05, 0.05], [2.49, 1.22], (6, 2))  # anywhere: rails, pockets
    vel = rng.normal(0.0, 1.5, (n, 2)) * (rng.random((n, 1)) < 0.5)
    w = rng.normal(0.0, 40.0, (n, 3)) * (rng.random((n, 1)) < 0.5)
    # Two balls headed for a corner and a side pocket (their holes and jaw tips).
    pos[6], vel[6] = [0.12, 0.1], rng.uniform([-1.0, -1.0], [-0.2, -0.2])
    pos[7], vel[7] = [1.27, 1.1], [rng.uniform(-0.2, 0.2), 1.0]
    # And two straight down past a corner's and a side pocket's jaw tips, overlapping them
    # by half a radius (the jaw tip, not the rail, is met).
    (x8, _), (x9, _) = scene.table.points.reshape(-1, 2)[[0, 5]]
    pos[8], vel[8] = [x8 - 0.5 * BALL_RADIUS, 0.1], [0.0, -rng.uniform(0.5, 2.0)]
    pos[9], vel[9] = [x9 + 0.5 * BALL_RADIUS, 0.1], [0.0, -rng.uniform(0.5, 2.0)]
    engines = [Engine(scene.table, scene.physics, pos, vel, w) for _ in range(2)]
    gone = rng.integers(0, n)
    for eng in engines:
        eng.state[0, gone] = POCKETED
    pairs = cushions = 0  # finite predictions met on the way
    for _ in range(40):
        t = float(rng.uniform(0.0, 0.02))
        balls = rng.integers(0, n, int(rng.integers(1, 3)))
        b = np.zeros(balls.size, dtype=np.int64)
        for eng, way in zip(engines, ("predict_few", "predict_many"), strict=True):
            eng.tb[0] = t
            with np.errstate(all="ignore"):
                getattr(eng.schedule, way)(b, balls)
        pairs += int(np.isfinite(engines[0].schedule.t_pair[0, balls]).sum())
        cushions += int(np.isfinite(engines[0].t_cush[0, balls]).sum())
    few, many = engines
    assert np.array_equal(few.schedule.times, many.schedule.times)
    assert np.array_equal(few.f_cush, many.f_cush)
    assert pairs > 10 and cushions > 5


def test_the_quartics_eigenvalues_are_numpys_bit_for_bit_and_refused_as_numpy_refuses():
    """roots.eigvals skips np.linalg.eigvals' checks around LAPACK: the same numbers on
    companion matrices of the quartics the root finder meets (random ones; double roots;
    roots exactly 0 and 1; all roots complex), and a matrix numpy refuses is refused."""
    rng = np.random.default_rng(26)
    tops = [rng.normal(0.0, 10.0 ** rng.uniform(-3, 3, 4)) for _ in range(300)]
    tops += [[-2.0, 1.0, 0.0, 0.0],  # s^2 (s - 1)^2: double roots at 0 and 1
             [-4.0, 6.0, -4.0, 1.0],  # (s - 1)^4
             [0.0, 2.0, 0.0, 1.0],  # (s^2 + 1)^2: no real root
             [-1.0, 0.0, 0.0, 0.0]]  # s^3 (s - 1)
    comp = np.zeros((len(tops), 4, 4))
    comp[:, 0] = np.negative(tops)
    comp[:, 1, 0] = comp[:, 2, 1] = comp[:, 3, 2] = 1.0
    with np.errstate(all="ignore"):
        assert roots.eigvals(comp).tobytes() == np.linalg.eigvals(comp).astype(complex).tobytes()
        for bad in (np.inf, np.nan):
            comp[7, 0, 2] = bad
            with pytest.raises(np.linalg.LinAlgError):
                roots.eigvals(comp)
