"""`termpool bench accuracy` and the frame-stepping baselines it compares with the engine."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import bench
from bench import accuracy as bench_accuracy
from bench.naive import EulerSim, NaiveSim
from termpool.physics.engine import Engine
from termpool.physics.params import BALL_RADIUS, Physics
from termpool.physics.table import Table
from termpool.scene import load_scene

ROOT = Path(__file__).resolve().parent.parent
SCENES = ROOT / "bench" / "scenes"
ROW_KEYS = {
    "scheme", "dt", "wall_s", "steps", "sim_s", "at_rest", "ckpt_mm", "err_ckpt_mm",
    "err_rest_mm", "err_mm", "events", "events_ref", "events_matched", "same_events",
    "event_dt_max_s", "agree_s", "agree_whole", "agree_events",
}
R = BALL_RADIUS


def _run_to_rest(sim, dt: float, limit: float = 60.0) -> None:
    while not np.all(sim.at_rest()) and sim.time < limit:
        sim.step(dt)


# ------------------------------------------------------------------- the baselines' errors


def test_naive_tunnels_where_the_engine_does_not() -> None:
    """20 m/s at dt 1/30 is 0.67 m a frame: frame-end overlap tests miss a ball 0.5 m ahead."""
    table, ph = Table(pockets="none"), Physics()
    pos = [[0.5, 0.635], [1.0, 0.635]]
    vel = [[20.0, 0.0], [0.0, 0.0]]
    naive = NaiveSim(table, ph, pos, vel)
    eng = Engine(table, ph, pos, vel)
    for _ in range(2):
        naive.step(1 / 30)
        eng.step(1 / 30)
    # Naive: the cue ball is through the 1 and the 1 never moved.
    assert not [e for e in naive.events if e["type"] == "ball_ball"]
    assert naive.pos[0, 0] > naive.pos[1, 0] == 1.0
    assert (naive.vel[1] == 0).all()
    # Engine: they met when the gap closed (0.5 m - 2R at about 20 m/s) and momentum moved on.
    hits = [e for e in eng.events[0] if e["type"] == "ball_ball"]
    assert len(hits) == 1
    assert hits[0]["t"] == pytest.approx((0.5 - 2 * R) / 20.0, rel=1e-2)
    assert eng.vel[0, 1, 0] > 15.0
    assert eng.pos[0, 0, 0] < eng.pos[0, 1, 0]


def test_rolling_stop_distance_naive_errs_engine_exact() -> None:
    """A rolling ball stops after v0^2 / (2 mu_r g). Euler with friction subtracted per frame
    overshoots by about v0 dt / 2; the engine lands on the law at any dt."""
    table, ph = Table(), Physics()
    v0, dt = 0.6, 1 / 15
    law = v0 * v0 / (2 * ph.mu_roll * ph.g)
    pos, vel, w = [[0.5, 0.635]], [[v0, 0.0]], [[0.0, v0 / R, 0.0]]  # natural roll
    eng = Engine(table, ph, pos, vel, w)
    eng.run(dt)
    assert abs(eng.pos[0, 0, 0] - 0.5 - law) < 1e-9
    naive = NaiveSim(table, ph, pos, vel, w)
    _run_to_rest(naive, dt)
    err = naive.pos[0, 0] - 0.5 - law
    assert err == pytest.approx(v0 * dt / 2, rel=0.05)
    # The engine's own model stepped by Euler errs the same way, and converges as dt shrinks.
    errs = []
    for h in (1 / 60, 1 / 600):
        eul = EulerSim(table, ph, pos, vel, w)
        _run_to_rest(eul, h)
        errs.append(abs(eul.pos[0, 0] - 0.5 - law))
    assert errs[1] < errs[0] / 5


def test_substeps_are_the_naive_scheme_at_the_smaller_step() -> None:
    scene = load_scene(SCENES / "cut_thick.json")
    args = (scene.table, scene.physics, scene.pos, scene.vel, scene.w, scene.radius, scene.mass)
    sub = NaiveSim(*args, substeps=10)
    fine = NaiveSim(*args)
    dt = 1 / 30
    for _ in range(30):
        sub.step(dt)
        for _ in range(10):
            fine.step(dt / 10)
    assert (sub.pos == fine.pos).all()
    assert [(e["type"], e["i"]) for e in sub.events] == [(e["type"], e["i"]) for e in fine.events]


# ------------------------------------------------------------------- the scenes


def test_the_default_scenes_are_bench_scenes_and_load() -> None:
    names = sorted(p.name for p in SCENES.glob("*.json"))
    assert len(names) >= 13
    assert [Path(p).name for p in bench_accuracy.scene_paths()] == names
    for name in names:
        load_scene(SCENES / name)
    assert len(load_scene(SCENES / "break.json").ids) == 16
    for name in names:
        if name.startswith("bank"):
            assert load_scene(SCENES / name).table.pockets == "none"


def test_jaw_scene_meets_a_jaw() -> None:
    scene = load_scene(SCENES / "jaw.json")
    eng = Engine(scene.table, scene.physics, scene.pos, scene.vel, scene.w)
    eng.run_events()
    features = [e.get("feature") for e in eng.events[0] if e["type"] == "cushion"]
    assert {"jaw", "tip"} & set(features)


# ------------------------------------------------------------------- the subcommand


def _finite(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def test_accuracy_json_one_scene(capsys: pytest.CaptureFixture[str]) -> None:
    rc = bench.main(["accuracy", "--json", "--no-png", "--scenes", str(SCENES / "stun.json"),
                     "--dts", "1/15", "1/150", "--closed", "none"])
    out = capsys.readouterr().out
    assert rc == 0
    result = json.loads(out)
    (scene,) = result["scenes"]
    assert scene["name"] == "stun"
    rows = scene["rows"]
    assert {(r["scheme"], round(1 / r["dt"])) for r in rows} == {
        ("engine", 15), ("engine", 150), ("naive", 15), ("naive", 150), ("substep", 15),
        ("euler", 15), ("euler", 150)}
    for r in rows:
        assert ROW_KEYS <= set(r), ROW_KEYS - set(r)
        for key in ("wall_s", "err_ckpt_mm", "err_rest_mm", "err_mm", "agree_s", "sim_s"):
            assert _finite(r[key]) and r[key] >= 0, (r["scheme"], key, r[key])
        assert all(_finite(v) for v in r["ckpt_mm"].values())
        assert r["event_dt_max_s"] is None or _finite(r["event_dt_max_s"])
        assert r["steps"] > 0 and r["at_rest"]
        if r["scheme"] == "engine":
            assert r["err_mm"] <= 1e-9
            assert r["same_events"] and r["event_dt_max_s"] == 0
            assert r["agree_whole"] and r["agree_events"] == scene["reference"]["events"]
        else:  # no spin or frame-end contacts: a stun shot is visibly off
            assert r["err_mm"] > 1.0
    assert {s["scheme"] for s in result["summary"]} == {"engine", "naive", "substep", "euler"}
    assert result["closed_form"] == {"cases": [], "summary": []}
    assert result["png"] is None
    assert {"python", "numpy", "cpu", "date"} <= set(result["machine"])


def test_accuracy_text_prints_zero_errors_and_a_chart(capsys) -> None:
    rc = bench.main(["accuracy", "--no-png", "--scenes", str(SCENES / "jaw.json"),
                     "--dts", "1/30", "--schemes", "engine,naive", "--closed", "none"])
    out = capsys.readouterr().out
    assert rc == 0
    engine_row = next(line for line in out.splitlines() if line.strip().startswith("engine"))
    assert engine_row.split()[4:7] == ["0", "0", "0"]  # ckpt, rest, event-time errors
    assert "work-precision" in out and "E engine" in out and "1e-09 |" in out
    assert "no PNG" in out


def test_chart_survives_zero_errors() -> None:
    summary = [{"scheme": "engine", "dt": 1 / 60, "wall_s": 0.01, "err_median_mm": 0.0},
               {"scheme": "naive", "dt": 1 / 60, "wall_s": 0.02, "err_median_mm": 350.0}]
    lines = bench_accuracy.text_chart(summary)
    assert any("E" in line and line.startswith(" 1e-09") for line in lines)
    assert bench_accuracy.fmt_mm(0.0) == "0"


def test_png_when_matplotlib_is_installed(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    summary = [{"scheme": "engine", "dt": 1 / 60, "wall_s": 0.01, "err_median_mm": 0.0},
               {"scheme": "naive", "dt": 1 / 60, "wall_s": 0.02, "err_median_mm": 350.0}]
    path = bench_accuracy.png_chart(summary, str(tmp_path / "chart.png"))
    assert path and Path(path).stat().st_size > 0


@pytest.mark.parametrize("argv", [["--dts", "0"], ["--schemes", "rk4"], ["--scenes", "/nope"],
                                  ["--closed", "spiral"]])
def test_accuracy_bad_usage(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.main(["accuracy", "--no-png", *argv]) in (1, 2)
    err = capsys.readouterr().err
    assert err.startswith("termpool: ") and err.count("\n") == 1


# ------------------------------------------------------------------- the closed-form section


def test_closed_form_rows_in_json_and_text(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["accuracy", "--no-png", "--scenes", str(SCENES / "jaw.json"), "--dts", "1/30",
            "1/300", "--schemes", "engine,naive,substep", "--closed", "slide_roll,stun"]
    assert bench.main([*argv, "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    closed = result["closed_form"]
    assert [c["name"] for c in closed["cases"]] == ["slide_roll", "stun"]
    for case in closed["cases"]:
        ref = case["reference"]
        assert ref["within"] and ref["matched"] == ref["expected"]
        assert {f["label"] for f in ref["facts"]} and all(_finite(f["error"])
                                                          for f in ref["facts"])
        assert case["scene"]["table"]["pockets"] == "none"
        rows = {(r["scheme"], round(1 / r["dt"])): r for r in case["rows"]}
        assert set(rows) == {(s, n) for s in ("engine", "naive") for n in (30, 300)} | {
            ("substep", 30)}
        for (scheme, _), r in rows.items():
            assert (r["own"] is not None) == (scheme in ("naive", "substep"))
            if scheme == "engine":
                assert r["within"] and r["model"]["err_mm"] <= case["tolerance"]["mm"]
        # The seed scheme converges on its own model, not on the engine's.
        own = [rows[("naive", n)]["own"]["err_mm"] for n in (30, 300)]
        assert own[1] < own[0] / 5
        assert rows[("naive", 300)]["model"]["err_mm"] > 100 * own[1]
    assert {(s["scheme"], round(1 / s["dt"])) for s in closed["summary"]} >= {("engine", 30)}
    out = bench_accuracy.format_accuracy(result)
    assert "closed-form references: 2 scene(s)" in out
    assert "NO SLIDING AND NO SPIN" in out  # the seed model is named a different model
    assert "slide distance (m)" in out and "closed-form summary over 2 scenes" in out
