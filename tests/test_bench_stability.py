"""`termpool bench stability`: every stiff and extreme case passes, the report has its shape,
and the watch behind it does catch what it is there to catch."""

from __future__ import annotations

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest
from physics_laws import check_positions

import bench
from bench.stability_cases import (
    CASES,
    OVERLAP_TOL,
    PLAIN,
    QUICK_LONG_RUN_S,
    Case,
    M,
    R,
    W,
    Watch,
    run_case,
)
from termpool.physics.engine import Engine
from termpool.physics.params import Physics

ROW_KEYS = {
    "case", "group", "ok", "figure", "checks", "laws", "wall_s", "wall_s_repeat", "engines",
    "steps", "passes", "max_passes", "sim_s", "looks", "overlap_m", "cushion_m", "energy_rise",
    "deterministic", "digest", "error",
}
LAWS = {"finite", "overlap", "cushion", "energy", "passes", "deterministic"}
CHECK_KEYS = {"figure", "value", "op", "limit", "ok"}


def test_every_case_passes_quick_json(capsys: pytest.CaptureFixture[str]) -> None:
    rc = bench.main(["stability", "--json", "--quick"])
    out = capsys.readouterr().out
    result = json.loads(out)  # exactly one strict JSON object
    failed = [(c["case"], [ch["figure"] for ch in c["checks"] if not ch["ok"]])
              for c in result["cases"] if not c["ok"]]
    assert not failed, failed
    assert rc == 0
    assert result["all_passed"] is True and result["failed"] == 0
    assert result["passed"] == len(CASES) == len(result["cases"])
    assert [c["case"] for c in result["cases"]] == [c.name for c in CASES]
    assert len({c.name for c in CASES}) == len(CASES), "case names must be unique"
    assert result["quick"] is True and result["long_run_s"] == QUICK_LONG_RUN_S
    assert {"platform", "python", "numpy", "cpu_count", "date"} <= set(result["machine"])
    assert result["limits"]["overlap_m"] == OVERLAP_TOL
    assert set(result["worst"]) == {"overlap_m", "cushion_m", "energy_rise", "max_passes"}
    for row in result["cases"]:
        assert ROW_KEYS <= set(row), (row["case"], ROW_KEYS - set(row))
        assert row["figure"] and row["error"] is None
        assert row["deterministic"] is True
        assert LAWS <= set(row["laws"]), row["case"]
        assert all(law["ok"] for law in row["laws"].values())
        assert row["checks"] and all(set(ch) == CHECK_KEYS for ch in row["checks"])
        assert all(ch["ok"] for ch in row["checks"])
        assert row["engines"] >= 1 and row["looks"] >= 2 and row["steps"] + row["passes"] > 0
        assert 0 <= row["overlap_m"] <= OVERLAP_TOL and 0 <= row["cushion_m"] <= OVERLAP_TOL
        assert math.isfinite(row["wall_s"]) and row["wall_s"] >= 0
    # Every group of stiff and extreme cases is there.
    assert {c["group"] for c in result["cases"]} == {
        "speed", "dt", "restitution", "friction", "mass", "radius", "rack", "cradle",
        "contact", "spin", "long run"}
    long = next(c for c in result["cases"] if c["group"] == "long run")
    assert f"over {QUICK_LONG_RUN_S:g} s" in long["figure"]


def test_text_table_for_selected_cases(capsys: pytest.CaptureFixture[str]) -> None:
    rc = bench.main(["stability", "--case", "cradle", "--case", "1 mm/s"])
    out = capsys.readouterr().out
    assert rc == 0
    rows = [line for line in out.splitlines() if " PASS " in line or " FAIL " in line]
    assert len(rows) == 4, out
    assert all(" PASS " in line and line.rstrip().endswith(" ms") for line in rows)
    assert "exactly 5" in out and ">= 0.85" in out
    assert "4 cases: 4 PASS, 0 FAIL" in out and "machine:" in out


@pytest.mark.parametrize("argv", [["stability", "--case", "no such case"],
                                  ["stability", "--bogus"]])
def test_bad_usage_returns_2(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("termpool: bench stability") or "usage" in err


# --------------------------------------------------------------- the watch catches failures


def _figure(fn) -> tuple[str, bool, dict]:
    return run_case(Case("test", "test", fn), quick=True)


def test_overlap_fails_the_case() -> None:
    def overlapping(w: Watch, quick: bool) -> None:
        w.add(Engine(PLAIN, Physics(), [[1.0, W / 2], [1.0 + 2 * R - 1e-5, W / 2]]))

    figure, ok, details = _figure(overlapping)
    assert not ok
    assert figure.startswith("max overlap 1e-05 m (limit 1e-06)"), figure
    assert not details["laws"]["overlap"]["ok"]


def test_ball_through_a_cushion_fails_the_case() -> None:
    def outside(w: Watch, quick: bool) -> None:
        w.add(Engine(PLAIN, Physics(), [[PLAIN.length + 0.01, W / 2]]))

    figure, ok, _ = _figure(outside)
    assert not ok and figure.startswith("max cushion depth"), figure


def _fake(vel: float) -> SimpleNamespace:
    """An object with the engine's public state, for states the engine never produces."""
    return SimpleNamespace(
        table=PLAIN, physics=Physics(), pos=np.array([[[1.0, W / 2]]]),
        vel=np.array([[[vel, 0.0]]]), w=np.zeros((1, 1, 3)), state=np.zeros((1, 1), np.int8),
        radius=np.array([[R]]), mass=np.array([[M]]), steps=0, passes=0, time=0.0,
        events=[[]])


def test_energy_gain_and_nan_fail_the_case() -> None:
    def gains(w: Watch, quick: bool) -> None:
        eng = w.add(_fake(1.0))
        eng.vel = eng.vel * 1.001
        w.look(eng, "later")

    figure, ok, _ = _figure(gains)
    assert not ok and figure.startswith("max energy rise 0.002 relative"), figure

    def nan(w: Watch, quick: bool) -> None:
        w.add(_fake(math.nan))

    figure, ok, _ = _figure(nan)
    assert not ok and figure.startswith("non-finite numbers 1 "), figure


def test_nondeterminism_and_errors_fail_the_case() -> None:
    runs = []

    def drifting(w: Watch, quick: bool) -> None:
        runs.append(1)
        eng = w.add(Engine(PLAIN, Physics(), [[1.0, W / 2]], [[1.0 + 1e-15 * len(runs), 0.0]]))
        w.run(eng, 1 / 60)

    figure, ok, details = _figure(drifting)
    assert not ok and figure == "2 runs differ" and details["deterministic"] is False

    def crashing(w: Watch, quick: bool) -> None:
        raise ValueError("boom")

    figure, ok, details = _figure(crashing)
    assert not ok and figure == "error: ValueError: boom"


def test_a_failed_own_check_decides() -> None:
    def short(w: Watch, quick: bool) -> None:
        w.check("last ball 0.5 m/s of 1", 0.5, ">=", 0.85)
        w.check("passes 1", 1, "<", 5000)

    figure, ok, _ = _figure(short)
    assert not ok and figure == "last ball 0.5 m/s of 1 (>= 0.85)"


def test_strict_checks_raise_with_the_figure() -> None:
    pos = np.array([[[1.0, W / 2], [1.0 + 2 * R - 1e-5, W / 2]]])
    with pytest.raises(AssertionError, match="overlap by 1e-05 m"):
        check_positions(PLAIN, Physics(), pos, np.zeros((1, 2), np.int8), np.full((1, 2), R),
                        "here")
