"""Property tests of the physics engine on random scenes (hypothesis).

Every test checks a law of the model, not a number taken from the engine's output:
finite state, kinetic energy that never rises (contacts and friction only remove it),
momentum kept by each ball-ball impulse, no interpenetration, balls kept within the
cushion noses, runs that come to rest in bounded work, determinism, independence of the
step length (the engine is exact inside each step) and independence of the batch.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from physics_laws import (
    ENERGY_TOL,
    check_positions,
    check_state,
    kinetic,
    momentum,
    nose_reach,
    run_checked,
    seg_distance,
)

from termpool.physics.ball_ball import MODELS as BALL_BALL
from termpool.physics.engine import POCKETED, SPINNING, STATIONARY, Engine
from termpool.physics.params import BALL_MASS, BALL_RADIUS, Physics
from termpool.physics.table import Table
from termpool.scene import rack

R = BALL_RADIUS
M = BALL_MASS
TABLES = {"standard": Table(pockets="standard"), "none": Table(pockets="none")}
CELL = 2.54 / 16  # the 9-ft playing area is 16 x 8 cells of this size
COLS, ROWS = 16, 8
JITTER = CELL / 2 - R - 5e-4  # balls in neighbouring cells stay >= 1 mm apart
SETTINGS = dict(deadline=None, suppress_health_check=[HealthCheck.too_slow],
                report_multiple_bugs=False)


# ------------------------------------------------------------------------------ scenes


def _pocket_cells() -> set[tuple[int, int]]:
    """Cells too close to a pocket mouth to place a ball in (on pocketed tables)."""
    t = TABLES["standard"]
    mouths = np.concatenate([t.points, t.hole_c])
    bad = set()
    for cx in range(COLS):
        for cy in range(ROWS):
            c = np.array([(cx + 0.5) * CELL, (cy + 0.5) * CELL])
            if (np.linalg.norm(mouths - c, axis=1) < 0.2).any():
                bad.add((cx, cy))
    return bad


POCKET_CELLS = _pocket_cells()


@st.composite
def physics_st(draw) -> Physics:
    return Physics(
        ball_ball=draw(st.sampled_from(["frictional", "frictionless"])),
        e_ball=draw(st.sampled_from([0.95, 1.0, 0.5])),
        e_cushion=draw(st.sampled_from([0.85, 1.0, 0.3])),
        mu_cushion=draw(st.sampled_from([0.2, 0.0, 0.6])),
        mu_roll=draw(st.sampled_from([0.01, 0.03])),
    )


@st.composite
def motion_st(draw, n: int, vmax: float = 10.0) -> tuple[np.ndarray, np.ndarray]:
    """Velocities up to vmax and spins up to those of an extreme cue strike."""
    vel = np.zeros((n, 2))
    w = np.zeros((n, 3))
    for k in range(n):
        if k > 0 and draw(st.booleans()):
            continue  # at rest, as most object balls are
        speed = draw(st.floats(0.0, vmax))
        ang = draw(st.floats(0.0, 2 * math.pi))
        vel[k] = speed * math.cos(ang), speed * math.sin(ang)
        if draw(st.booleans()):
            w[k] = draw(st.lists(st.floats(-400.0, 400.0), min_size=3, max_size=3))
    return vel, w


@st.composite
def layout_st(draw, n: int, pockets: str) -> np.ndarray:
    """n non-overlapping balls inside the cushion noses: one per grid cell, jittered; or a
    piece of the 8-ball rack (touching balls) plus the cue ball."""
    if draw(st.integers(0, 3)) == 0 and n <= 16:
        spots = rack("8ball", TABLES[pockets])
        idx = [0] + sorted(draw(st.lists(st.integers(1, 15), min_size=n - 1, max_size=n - 1,
                                         unique=True)))
        return np.array([[spots[k]["x"], spots[k]["y"]] for k in idx])
    cells = [(cx, cy) for cx in range(COLS) for cy in range(ROWS)
             if pockets == "none" or (cx, cy) not in POCKET_CELLS]
    chosen = draw(st.lists(st.sampled_from(cells), min_size=n, max_size=n, unique=True))
    pos = np.empty((n, 2))
    for k, (cx, cy) in enumerate(chosen):
        jx = draw(st.floats(-JITTER, JITTER))
        jy = draw(st.floats(-JITTER, JITTER))
        pos[k] = (cx + 0.5) * CELL + jx, (cy + 0.5) * CELL + jy
    return pos


@st.composite
def scene_st(draw, nmin: int = 2, nmax: int = 16, vmax: float = 10.0) -> dict:
    n = draw(st.integers(nmin, nmax))
    pockets = draw(st.sampled_from(["standard", "none"]))
    pos = draw(layout_st(n, pockets))
    vel, w = draw(motion_st(n, vmax))
    mass = np.full(n, M)
    if draw(st.booleans()):
        mass = np.array(draw(st.lists(st.floats(0.5 * M, 2.0 * M), min_size=n, max_size=n)))
    return dict(table=TABLES[pockets], physics=draw(physics_st()), pos=pos, vel=vel, w=w,
                radius=np.full(n, R), mass=mass)


dt_st = st.floats(-3.0, -1.0).map(lambda e: 10.0**e)  # 1 ms to 0.1 s, log-uniform


def make(sc: dict, **kw) -> Engine:
    return Engine(sc["table"], sc["physics"], sc["pos"], sc["vel"], sc["w"],
                  radius=sc["radius"], mass=sc["mass"], **kw)


# ------------------------------------------------------------------------------ tests


@settings(max_examples=60, **SETTINGS)
@given(sc=scene_st(), dt=dt_st)
def test_random_scene_keeps_laws_at_every_step(sc, dt):
    eng = make(sc, record=False)
    run_checked(eng, dt)
    assert eng.at_rest().all()
    assert np.isin(eng.state, [STATIONARY, SPINNING, POCKETED]).all(), eng.state
    n = eng.N
    assert eng.passes < 5000 * max(1, n / 16), f"{eng.passes} event passes for {n} balls"
    # At rest means no ball translates; only side spin may remain (and it is decaying).
    v = eng.vel
    assert np.abs(v).max() == 0.0, f"at rest with velocity {np.abs(v).max()}"


@settings(max_examples=40, **SETTINGS)
@given(sc=scene_st(nmax=8))
def test_energy_never_rises_from_event_to_event(sc):
    """Energy sampled right after every event: run_events up to the table's next event time."""
    eng = make(sc, record=False)
    e_prev = float(kinetic(eng)[0])
    hops = 0
    while not eng.at_rest().all():
        t_next = float(eng.t_next[0])
        eng.run_events(duration=t_next)  # exactly the next event (and any at that instant)
        hops += 1
        assert hops < 20000, "too many events"
        e = float(kinetic(eng)[0])
        assert e <= e_prev * (1 + ENERGY_TOL) + 1e-15, (
            f"event {hops} at t={t_next!r}: kinetic energy rose from {e_prev!r} to {e!r} J")
        e_prev = e
        check_state(eng, f"event {hops}")


@settings(max_examples=40, **SETTINGS)
@given(sc=scene_st(nmax=10), frictional=st.booleans())
def test_ball_ball_impulse_conserves_momentum(sc, frictional):
    """Spy on every ball-ball impulse the engine applies: m_i v_i + m_j v_j is the same before
    and after, and the relative normal speed does not grow (e <= 1)."""
    sc["physics"] = Physics(ball_ball="frictional" if frictional else "frictionless",
                            e_ball=sc["physics"].e_ball)
    seen = []
    model = BALL_BALL[sc["physics"].ball_ball]
    real = model.collide

    def spy(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, *rest):
        out = real(pi, pj, vi, vj, wi, wj, ri, rj, mi, mj, *rest)
        seen.append((pi.copy(), pj.copy(), vi.copy(), vj.copy(), mi.copy(), mj.copy(),
                     out[0].copy(), out[1].copy()))
        return out

    model.collide = spy
    try:
        eng = make(sc, record=False)
        eng.run(1 / 60, max_steps=20000)
    finally:
        model.collide = real
    for pi, pj, vi, vj, mi, mj, vi2, vj2 in seen:
        before = mi[:, None] * vi + mj[:, None] * vj
        after = mi[:, None] * vi2 + mj[:, None] * vj2
        scale = (mi * np.linalg.norm(vi, axis=1) + mj * np.linalg.norm(vj, axis=1)).max() + 1e-12
        err = np.abs(after - before).max()
        assert err <= 1e-12 * max(scale, 1.0), f"momentum changed by {err} kg m/s"
        n = (pj - pi) / np.linalg.norm(pj - pi, axis=1)[:, None]
        closing = ((vi - vj) * n).sum(1)
        closing2 = ((vi2 - vj2) * n).sum(1)
        # After the impulse the pair separates (or at most keeps touching), never faster than
        # it approached.
        assert (closing2 <= 1e-12).all(), f"still closing after impulse: {closing2.max()}"
        assert (-closing2 <= np.abs(closing) + 1e-12).all()


FRICTIONLESS_CLOTH = dict(mu_slide=0.0, mu_roll=0.0)


@settings(max_examples=50, **SETTINGS)
@given(data=st.data(), frictional=st.booleans(), e=st.sampled_from([0.0, 0.5, 0.95, 1.0]))
def test_two_ball_collision_conserves_momentum(data, frictional, e):
    """Two balls on frictionless cloth: velocities stay the initial ones until the first event;
    if it is the balls' collision, the pair's momentum just after it equals the initial one,
    and the relative normal speed is reversed times e (or the pair stops closing)."""
    pos = data.draw(layout_st(2, "none"))
    vel, w = data.draw(motion_st(2))
    mass = np.array(data.draw(st.lists(st.floats(0.05, 2.0), min_size=2, max_size=2)))
    # Aim ball 0 at ball 1 (with a random cut) so that most examples collide.
    d = pos[1] - pos[0]
    cut = data.draw(st.floats(-0.95, 0.95)) * 2 * R / np.linalg.norm(d)
    speed = data.draw(st.floats(0.1, 10.0))
    c, s_ = math.cos(math.asin(cut)), cut
    vel[0] = speed * np.array([c * d[0] - s_ * d[1], s_ * d[0] + c * d[1]]) / np.linalg.norm(d)
    ph = Physics(ball_ball="frictional" if frictional else "frictionless", e_ball=e,
                 **FRICTIONLESS_CLOTH)
    eng = Engine(TABLES["none"], ph, pos, vel, w, radius=R, mass=mass)
    v_start = eng.vel[0]
    eng.run_events(duration=float(eng.t_next[0]))  # exactly the first event
    evs = eng.events[0]
    assume(evs and evs[0]["type"] == "ball_ball")
    p0 = (mass[:, None] * v_start).sum(0)
    v_after = eng.vel[0]
    p1 = (mass[:, None] * v_after).sum(0)
    scale = float((mass * np.linalg.norm(v_start, axis=1)).sum())
    assert np.abs(p1 - p0).max() <= 1e-12 * max(scale, 1e-3), (
        f"momentum {p0.tolist()} -> {p1.tolist()} (change {np.abs(p1 - p0).max():.3g})")
    n = eng.pos[0, 1] - eng.pos[0, 0]
    n /= np.linalg.norm(n)
    before = float((v_start[0] - v_start[1]) @ n)
    after = float((v_after[0] - v_after[1]) @ n)
    assert before > 0, "collided while separating"
    expect = -e * before if before > ph.v_inelastic else 0.0
    assert abs(after - expect) <= 1e-9 * max(1.0, before), (
        f"closing speed {before} -> {after}, expected {expect} (e={e})")
    # The recorded event carries the same post-collision velocities.
    rec = np.array([[b["vx"], b["vy"]] for b in evs[0]["balls"]])
    assert np.array_equal(rec[np.argsort(evs[0]["i"])], v_after)


def _near_cushion(eng: Engine, margin: float = 1e-5) -> bool:
    """True if any unpocketed ball is within `margin` of touching a cushion feature."""
    pos = eng.pos[0]
    for k in np.flatnonzero(eng.state[0] != POCKETED):
        rc = nose_reach(float(eng.radius[0, k]), eng.physics)
        if seg_distance(eng.table, pos[k]).min() < rc + margin:
            return True
    return False


@settings(max_examples=40, **SETTINGS)
@given(sc=scene_st(nmax=10, vmax=5.0))
def test_ball_contacts_conserve_total_momentum(sc):
    """On frictionless cloth only cushions, jaws and pockets can change a table's momentum.
    Hopping from event instant to event instant, every instant with ball-ball contacts only
    (no cushion or pocket event, no ball touching a cushion) keeps the total momentum of
    all balls, including balls moved by a cluster without their own event."""
    ph = sc["physics"]
    sc["physics"] = Physics(ball_ball=ph.ball_ball, e_ball=ph.e_ball, e_cushion=ph.e_cushion,
                            mu_cushion=ph.mu_cushion, **FRICTIONLESS_CLOTH)
    eng = make(sc, record=True)
    checked = 0
    for hop in range(300):
        t_next = float(eng.t_next[0])
        if not t_next < 2.0:
            break
        P0 = momentum(eng)[0]
        scale = float((eng.mass[0] * np.linalg.norm(eng.vel[0], axis=1)).sum())
        quiet = not _near_cushion(eng)
        n_ev = len(eng.events[0])
        eng.run_events(duration=t_next)
        new = eng.events[0][n_ev:]
        if quiet and new and all(e["type"] == "ball_ball" for e in new) and not _near_cushion(eng):
            P1 = momentum(eng)[0]
            err = float(np.abs(P1 - P0).max())
            assert err <= 1e-12 * max(scale, 1e-3), (
                f"hop {hop} at t={t_next!r}: events {[e['i'] for e in new]} changed the "
                f"total momentum {P0.tolist()} -> {P1.tolist()} ({err:.3g} kg m/s)")
            checked += 1
    assume(checked > 0)


@settings(max_examples=40, **SETTINGS)
@given(sc=scene_st(nmax=10, vmax=5.0))
def test_event_log_names_every_ball_whose_motion_changes(sc):
    """With no friction on the cloth (and no spin decay) a ball's velocity and spin change only
    at its events, so at every event instant each ball whose velocity or spin changed must be
    listed in an event of that instant, with its new state."""
    ph = sc["physics"]
    sc["physics"] = Physics(ball_ball=ph.ball_ball, e_ball=ph.e_ball, e_cushion=ph.e_cushion,
                            mu_cushion=ph.mu_cushion, mu_spin=0.0, **FRICTIONLESS_CLOTH)
    eng = make(sc, record=True)
    for hop in range(200):
        t_next = float(eng.t_next[0])
        if not t_next < 2.0:
            break
        v0, w0 = eng.vel[0], eng.w[0]
        n_ev = len(eng.events[0])
        eng.run_events(duration=t_next)
        new = eng.events[0][n_ev:]
        named = {k for e in new for k in e["i"]}
        v1, w1 = eng.vel[0], eng.w[0]
        changed = np.flatnonzero((v1 != v0).any(1) | (w1 != w0).any(1))
        silent = sorted(set(changed.tolist()) - named)
        assert not silent, (
            f"hop {hop} at t={t_next!r}: balls {silent} changed motion without an event "
            f"(events {[(e['type'], e['i']) for e in new]}; "
            f"v {v0[silent].tolist()} -> {v1[silent].tolist()})")
        last = {k: (e, b) for e in new for k, b in zip(e["i"], e["balls"], strict=True)}
        for k, (e, b) in last.items():
            assert [b["vx"], b["vy"]] == v1[k].tolist(), (
                f"hop {hop} at t={t_next!r}: the instant's last event naming ball {k} "
                f"({e['type']} {e['i']}) records {[b['vx'], b['vy']]}, but it leaves the "
                f"instant at {v1[k].tolist()} (events {[(f['type'], f['i']) for f in new]})")


@settings(max_examples=30, **SETTINGS)
@given(sc=scene_st(), dt=dt_st)
def test_deterministic(sc, dt):
    runs = []
    for _ in range(2):
        eng = make(sc, record=True)
        eng.run(dt)
        runs.append(eng)
    a, b = runs
    for name in ("pos", "vel", "w", "state", "pocket"):
        x, y = getattr(a, name), getattr(b, name)
        assert np.array_equal(x, y), f"{name} differs between identical runs"
    assert a.events == b.events
    assert a.passes == b.passes and a.steps == b.steps


def _final(eng: Engine) -> tuple:
    return eng.pos, eng.state.copy(), eng.pocket.copy()


@settings(max_examples=30, **SETTINGS)
@given(sc=scene_st())
def test_step_length_does_not_change_the_result(sc):
    """dt = 1/30, dt = 1/240 and the event-to-event driver give the same motion."""
    results = {}
    for label in ("1/30", "1/240", "events"):
        eng = make(sc, record=True)
        if label == "events":
            eng.run_events()
        else:
            eng.run(1 / 30 if label == "1/30" else 1 / 240)
        assert eng.at_rest().all()
        results[label] = (eng, *_final(eng))
    ref, pos0, state0, pocket0 = results["events"]
    for label in ("1/30", "1/240"):
        eng, pos, state, pocket = results[label]
        err = np.abs(pos - pos0).max()
        assert err <= 1e-9, f"dt={label}: final positions differ from run_events by {err} m"
        assert np.array_equal(state, state0) and np.array_equal(pocket, pocket0), label
        assert len(eng.events[0]) == len(ref.events[0]), (
            f"dt={label}: {len(eng.events[0])} events, run_events {len(ref.events[0])}")
        for e1, e2 in zip(eng.events[0], ref.events[0], strict=True):
            assert e1["type"] == e2["type"] and e1["i"] == e2["i"], (e1, e2)
            assert abs(e1["t"] - e2["t"]) <= 1e-9, (e1["t"], e2["t"])


@settings(max_examples=30, **SETTINGS)
@given(data=st.data(), B=st.integers(2, 5), n=st.integers(2, 10), dt=dt_st)
def test_batch_equals_tables_run_alone(data, B, n, dt):
    pockets = data.draw(st.sampled_from(["standard", "none"]))
    ph = data.draw(physics_st())
    pos = np.stack([data.draw(layout_st(n, pockets)) for _ in range(B)])
    motions = [data.draw(motion_st(n)) for _ in range(B)]
    vel = np.stack([m[0] for m in motions])
    w = np.stack([m[1] for m in motions])
    mass = np.array(data.draw(st.lists(st.floats(0.5 * M, 2 * M), min_size=B * n,
                                       max_size=B * n))).reshape(B, n)
    table = TABLES[pockets]
    batch = Engine(table, ph, pos, vel, w, radius=R, mass=mass)
    batch.run(dt)
    bp, bv, bw = batch.pos, batch.vel, batch.w
    for b in range(B):
        alone = Engine(table, ph, pos[b], vel[b], w[b], radius=R, mass=mass[b])
        alone.run(dt)
        err = max(np.abs(alone.pos[0] - bp[b]).max(), np.abs(alone.vel[0] - bv[b]).max(),
                  np.abs(alone.w[0] - bw[b]).max())
        assert err <= 1e-9, f"table {b} of {B}: batch and alone differ by {err}"
        assert np.array_equal(alone.state[0], batch.state[b])
        assert np.array_equal(alone.pocket[0], batch.pocket[b])
        ev_a, ev_b = alone.events[0], batch.events[b]
        assert [(e["type"], e["i"]) for e in ev_a] == [(e["type"], e["i"]) for e in ev_b]
        for e1, e2 in zip(ev_a, ev_b, strict=True):
            assert abs(e1["t"] - e2["t"]) <= 1e-9


@settings(max_examples=30, **SETTINGS)
@given(sc=scene_st(nmax=16), dt=dt_st)
def test_sampled_run_is_finite_and_within_table(sc, dt):
    """run() with sample_hz: samples at rising times, each finite, inside the cushions and
    without overlaps; the run ends with every ball stationary, spinning in place or potted."""
    eng = make(sc, record=False)
    samples = eng.run(dt, sample_hz=30.0)
    assert eng.at_rest().all()
    assert samples and samples[0][0] == 0.0
    times = [s[0] for s in samples]
    assert all(b > a for a, b in zip(times, times[1:], strict=False)), "sample times not rising"
    for t, pos, state in samples:
        check_positions(eng.table, eng.physics, pos, state, eng.radius, f"sample t={t}")
    assert np.isin(eng.state, [STATIONARY, SPINNING, POCKETED]).all(), eng.state


@pytest.mark.parametrize("pockets", ["standard", "none"])
def test_examples_of_the_strategy_are_valid(pockets):
    """The scene strategy itself: non-overlapping and inside the noses (so failures above are
    the engine's)."""
    @settings(max_examples=30, deadline=None)
    @given(sc=scene_st())
    def inner(sc):
        eng = make(sc, record=False)
        check_state(eng, "initial")
    inner()


# ------------------------------------------------------------------------ found by the above


def _rack_spots(ids: list[str]) -> np.ndarray:
    spots = {b["id"]: (b["x"], b["y"]) for b in rack("8ball", TABLES["standard"])}
    return np.array([spots[k] for k in ids])


def test_slow_push_into_rack_does_not_sink_balls():
    """Found by test_random_scene_keeps_laws_at_every_step: two rack balls nudged at 15.6 mm/s
    into their touching neighbours; after the first step of 46.875 ms balls 2 and 3 overlapped
    by more than 1 micrometre (a resting contact resolved with a leftover overlap, then
    allowed to sink a further depth measured from that overlap)."""
    pos = _rack_spots(["cue", "1", "2", "3", "4", "5"])
    vel = np.zeros((6, 2))
    vel[1] = vel[2] = (0.015625, 0.0)
    eng = Engine(TABLES["standard"], Physics(), pos, vel)
    run_checked(eng, 0.046875)


def test_batch_regression_slow_pairs_in_the_same_pass():
    """Found by test_batch_equals_tables_run_alone: two tables that each have a slow
    (inelastic) pair contact in the same event pass; the second table (ball 3 with back spin
    pushing ball 2) gave different velocities in the batch than alone."""
    ph = Physics(mu_roll=0.03, e_ball=0.5)
    pos = np.stack([_rack_spots(["cue", "1", "4", "8"]), _rack_spots(["cue", "1", "3", "6"])])
    vel = np.zeros((2, 4, 2))
    vel[0, 1] = (0.21939564, 0.11985638)
    w = np.zeros((2, 4, 3))
    w[1, 3] = (0.0, -95.0, 0.0)
    dt = 0.09375
    batch = Engine(TABLES["standard"], ph, pos, vel, w, mass=0.25)
    batch.run(dt)
    for b in range(2):
        alone = Engine(TABLES["standard"], ph, pos[b], vel[b], w[b], mass=0.25)
        alone.run(dt)
        err = float(np.abs(alone.pos[0] - batch.pos[b]).max())
        assert err <= 1e-9, f"table {b}: final positions differ by {err:.3g} m batch vs alone"
        assert len(alone.events[0]) == len(batch.events[b]), (
            f"table {b}: {len(alone.events[0])} events alone, {len(batch.events[b])} in batch")


def test_ball_pressed_against_the_head_rail_does_not_sink():
    """Found by test_sampled_run_is_finite_and_within_table: a 7.5 m/s shot into a grid of
    still balls (e_ball 0.5, e_cushion 0.3, frictionless ball contacts), 0.1 s steps sampled
    at 30 Hz. Around t = 5.0 s ball 5 rolls into ball 4, which rests against the head rail; the
    pair's repeated slow contacts leave ~0.7 micrometres of overlap each time and the sample
    at t = 5.0333 s shows 1.29 micrometres."""
    pos = np.array([[0.079375, 0.396875], [1.825625, 0.873125], [1.508125, 0.841875],
                    [0.079375, 0.555625], [0.079375, 0.714375], [0.079375, 0.873125],
                    [0.238125, 0.238125], [0.238125, 0.396875], [0.238125, 0.555625],
                    [0.238125, 0.714375], [0.238125, 0.873125], [0.238125, 1.031875],
                    [0.396875, 0.079375], [0.396875, 0.238125]])
    vel = np.zeros_like(pos)
    vel[2] = (7.5, 0.0)
    w = np.zeros((len(pos), 3))
    w[2] = (27.0, 0.0, 0.0)
    ph = Physics(e_ball=0.5, e_cushion=0.3, ball_ball="frictionless")
    eng = Engine(TABLES["standard"], ph, pos, vel, w)
    for t, p, state in eng.run(0.1, sample_hz=30.0):
        check_positions(eng.table, ph, p, state, eng.radius, f"sample t={t}")


def test_slow_cluster_push_on_frictionless_cloth_conserves_momentum():
    """Found by test_ball_contacts_conserve_total_momentum: rack balls 1-4 touching, ball 1
    nudged at 7.8 mm/s on cloth with no friction (mu_slide = mu_roll = 0). Only ball contacts
    act at t = 0, so the total momentum must stay (0.001328, 0) kg m/s."""
    pos = _rack_spots(["cue", "1", "2", "3", "4"])
    vel = np.zeros((5, 2))
    vel[1] = (0.0078125, 0.0)
    eng = Engine(TABLES["none"], Physics(**FRICTIONLESS_CLOTH), pos, vel)
    P0 = momentum(eng)[0]
    eng.run_events(duration=0.0)
    P1 = momentum(eng)[0]
    err = float(np.abs(P1 - P0).max())
    assert err <= 1e-15, f"total momentum {P0.tolist()} -> {P1.tolist()} ({err:.3g} kg m/s)"


def test_rack_push_logs_every_ball_it_moves():
    """Found by test_event_log_names_every_ball_whose_motion_changes: rack balls 1-4 touching,
    ball 1 driven into ball 2 at 1 m/s. Every ball set moving at t = 0 must appear in an
    event at t = 0 (here ball 4 is moved by the cluster solve without one)."""
    pos = _rack_spots(["cue", "1", "2", "3", "4"])
    vel = np.zeros((5, 2))
    vel[1] = (1.0, 0.0)
    eng = Engine(TABLES["none"], Physics(), pos, vel)
    eng.run_events(duration=0.0)
    moving = set(np.flatnonzero((eng.vel[0] != 0).any(1)).tolist()) - {1}
    named = {k for e in eng.events[0] for k in e["i"]}
    assert moving <= named, (
        f"balls {sorted(moving - named)} move at t=0 but no event names them "
        f"(events {[(e['type'], e['i']) for e in eng.events[0]]})")


def test_rack_scatter_keeps_balls_out_of_the_foot_rail():
    """Found by test_sampled_run_is_finite_and_within_table (on the engine of the working copy
    after fd979ae): a full rack with six balls set moving at 1-6 m/s with spin, 0.1 s steps
    sampled at 30 Hz. Ball 14 bounced off the foot-right pocket's rail-side jaw tip at
    t = 0.766 s and then, curving back under its spin, passed through the foot rail without a
    cushion event (2.6 mm into it at t = 0.9667 s, 10.6 mm at t = 1.0 s)."""
    pos = _rack_spots(["cue", "1", "2", "3", "4", "5", "6", "8", "9", "10", "11", "12", "13",
                       "14", "15"])
    vel = np.zeros((15, 2))
    w = np.zeros((15, 3))
    vel[0], w[0] = (-2.41750192, -5.55060561), (131.646908, 0.0, 0.0)
    vel[2], w[2] = (4.48777675, -3.2411487), (-24.8106605, 392.535635, -336.17477)
    w[4] = (32.2834572, -339.892964, -56.9060738)
    w[5] = (-83.6863173, 174.811828, 303.249104)
    vel[6], w[6] = (1.99092773, -5.66511131), (-0.478402257, -87.3058295, 0.0)
    vel[8] = (5.30086968, 0.0)
    vel[9] = (-1.8830474, 5.51186336)
    vel[14], w[14] = (-0.289406068, 0.799214695), w[2]
    ph = Physics(e_ball=0.5, e_cushion=0.3, mu_cushion=0.0, ball_ball="frictionless")
    eng = Engine(TABLES["standard"], ph, pos, vel, w)
    for t, p, state in eng.run(0.1, sample_hz=30.0):
        check_positions(eng.table, ph, p, state, eng.radius, f"sample t={t}")


def test_spin_pinned_against_a_rail_takes_a_handful_of_events():
    """Found by test_random_scene_keeps_laws_at_every_step in a random run: ball 2 (420 rad/s
    of spin) ends up pressed into a corner of the rails by sliding friction. It once took ~3800
    slow cushion contacts (5228 passes) before its spin was spent; pressed to the rails, it
    now moves along them as one constrained motion (physics/joined.py)."""
    tab = TABLES["none"]
    ph = Physics(e_cushion=0.3, mu_cushion=0.0)
    pos = np.array([[1.666875, 1.031875], [0.079375, 0.079375], [0.238125, 0.873125],
                    [1.984375, 1.190625], [1.984375, 1.02534596], [0.079375, 0.238125],
                    [1.031875, 1.190625], [0.079375, 0.396875]])
    vel = np.zeros((8, 2))
    vel[2], vel[6], vel[7] = (-0.72084212, 0.46867037), (9.04009327, 0.0), (0.27561643, 0.05587022)
    w = np.zeros((8, 3))
    w[2], w[6] = (-392.09677245, -151.14268631, 0.0), (-72.7775204, 400.0, 0.0)
    eng = Engine(tab, ph, pos, vel, w)
    run_checked(eng, 0.001)
    assert eng.passes < 150, f"{eng.passes} event passes for 8 balls"
