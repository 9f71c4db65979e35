"""`termpool bench`: the speed benchmark runs and reports sane figures (no timing thresholds)."""

from __future__ import annotations

import json
import math

import pytest

import bench
from bench import speed

FIGURES = (
    "break_ms",
    "break_ms_min",
    "break_ms_max",
    "batch_breaks_per_s",
    "batch_wall_s",
    "break_cpu_ms",
    "batch_cpu_s",
    "batch_stepped_cpu_s",
    "import_s",
    "run_events_ms",
)
COUNTS = ("break_steps", "break_passes", "batch_passes", "batch_steps", "events_total")


def _positive_finite(x: object) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) and x > 0


def test_speed_json(capsys: pytest.CaptureFixture[str]) -> None:
    rc = bench.main(["speed", "--json", "--repeat", "1", "--batch", "4"])
    out = capsys.readouterr().out
    assert rc == 0
    result = json.loads(out)  # exactly one JSON object
    assert isinstance(result, dict)
    for key in FIGURES + COUNTS:
        assert key in result, key
        assert _positive_finite(result[key]), (key, result[key])
    assert result["batch"] == 4
    assert result["repeat"] == 1
    assert result["batch_at_rest"] == 4
    # The batch's peak memory, from a fresh interpreter (RSS: may not grow at all for 4).
    assert math.isfinite(result["batch_peak_kb_per_table"])
    assert result["batch_peak_kb_per_table"] >= 0 and result["batch_peak_mb"] >= 0
    assert result["break_ms_min"] <= result["break_ms"] <= result["break_ms_max"]
    assert sum(result["events"].values()) == result["events_total"]
    assert result["events"].get("ball_ball", 0) > 0
    assert set(result["pass"]) == {"break_ms", "batch_breaks_per_s", "import_s"}
    assert {"platform", "python", "numpy", "cpu_count", "date"} <= set(result["machine"])


def test_batch_breaks_are_deterministic_and_distinct() -> None:
    scene = speed.break_scene()
    pos, vel, w = speed.batch_breaks(scene, 8)
    pos2, vel2, w2 = speed.batch_breaks(scene, 8)
    assert (pos == pos2).all() and (vel == vel2).all() and (w == w2).all()
    cue = scene.index("cue")
    assert len({float(y) for y in pos[:, cue, 1]}) == 8
    assert abs(pos[:, cue, 1] - scene.pos[cue, 1]).max() <= speed.SPREAD_Y
    speeds = (vel[:, cue] ** 2).sum(axis=1) ** 0.5
    assert abs(speeds - speed.BREAK_SPEED).max() < 1e-9


@pytest.mark.parametrize("argv", [["nope"], [], ["speed", "--batch", "0"], ["speed", "--bogus"]])
def test_bad_usage_returns_2(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("termpool: ") and err.count("\n") == 1


def test_help(capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.main(["--help"]) == 0
    assert "speed" in capsys.readouterr().out


def test_batch_memory_counts_what_a_batch_allocates() -> None:
    """bench/memory.py: tracemalloc sees the engine of a small batch allocate (its arrays),
    the figure is per table, and an unknown method is refused by name."""
    from bench.memory import batch_peak

    r = batch_peak(4, "tracemalloc")
    assert r["at_rest"] == 4 and r["peak_bytes"] > 4 * 5_000  # at least its state arrays
    assert r["kb_per_table"] == pytest.approx(r["peak_bytes"] / 4 / 1e3)
    with pytest.raises(ValueError, match="method"):
        batch_peak(4, "guess")
