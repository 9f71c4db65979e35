"""`termpool bench`: the speed benchmark runs and reports sane figures (no timing thresholds)."""

from __future__ import annotations

import json
import math
import shutil

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
    "sim_start_s",
    "sim_start_cpu_s",
    "python_start_s",
    "numpy_start_s",
    "memory_batch_cpu_s",
    "memory_batch_breaks_per_cpu_s",
)
COUNTS = ("break_steps", "break_passes", "batch_passes", "batch_steps", "events_total")


def _positive_finite(x: object) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) and x > 0


def test_speed_json(capsys: pytest.CaptureFixture[str]) -> None:
    rc = bench.main(["speed", "--json", "--repeat", "1", "--batch", "4", "--no-pooltool",
                     "--games", "0", "--memory-batch", "8"])
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
    assert set(result["pass"]) == {"break_ms", "batch_breaks_per_s", "import_s",
                                   "vs_pooltool_cpu", "record_light_pct", "sim_start_s",
                                   "batch_peak_kb_per_table"}
    assert result["memory_batch"] == 8
    assert "decision_cpu_s" not in result  # no games asked for
    # The logs' costs are ratios of noisy times: finite, and a log cannot cost the whole run.
    for key in ("record_light_pct", "record_full_pct"):
        assert math.isfinite(result[key]) and result[key] > -100.0, (key, result[key])
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


def test_decision_time_comes_from_games_of_the_computer_against_itself() -> None:
    from bench.decisions import time_decisions

    r = time_decisions(1, max_shots=3)
    assert r["decision_level"] == "hard" and r["decision_games"] == 1
    assert r["decision_shots"] == 3  # the break is one of them, and is not timed here
    assert 0 < r["decision_cpu_s"] <= r["decision_cpu_s_max"]


@pytest.mark.parametrize("argv", [["nope"], [], ["speed", "--batch", "0"], ["speed", "--bogus"],
                                  ["speed", "--games", "-1"]])
def test_bad_usage_returns_2(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("termpool: ") and err.count("\n") == 1


def test_help(capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.main(["--help"]) == 0
    assert "speed" in capsys.readouterr().out


CALLGRIND = """\
fn=(1) caller
cfn=(2) ufunc_generic_vectorcall
calls=5 0
0 100
cfn=(3) array_add
calls=2 0
0 10
cfn=(4) array_tolist
calls=3 0
0 10
fn=(5) other
cfn=(2)
calls=4 0
0 10
cfn=(6) list_append
calls=9 0
0 1
fn=(7) array_subscript
0 5
fn=(5)
cfn=(7)
calls=6 0
0 5
"""


def test_numpy_calls_are_read_from_callgrind_at_numpy_s_entry_points() -> None:
    from bench import npcalls

    counts = npcalls.parse_calls(CALLGRIND)
    assert counts["ufunc_generic_vectorcall"] == 9  # summed over callers, name given once
    points = npcalls.entry_points()
    assert "array_add" not in points  # an operator: its ufunc call is the one counted
    assert {"array_tolist", "array_size_get", "array_subscript"} <= points
    assert counts["array_subscript"] == 6  # named on an fn= line, called by its id after
    assert npcalls.numpy_calls(counts, points) == 9 + 3 + 6


@pytest.mark.skipif(shutil.which("valgrind") is None, reason="valgrind is not installed")
def test_numpy_calls_counted_under_valgrind(tmp_path) -> None:
    from bench import npcalls

    runner = tmp_path / "run.py"
    runner.write_text("import sys\nimport numpy as np\na = np.ones(3)\n"
                      "for _ in range(int(sys.argv[1])):\n"
                      "    b = a + a; np.concatenate([a, b]); b[0] = a[1]; a.tolist()\n")
    points = npcalls.entry_points()
    one, three = (npcalls.numpy_calls(npcalls.callgrind(tmp_path, "run.py", k), points)
                  for k in (1, 3))
    assert three - one == 2 * 5  # a ufunc, a function, a write, a read, a method a round


def test_batch_memory_counts_what_a_batch_allocates() -> None:
    """bench/memory.py: tracemalloc sees the engine of a small batch allocate (its arrays),
    the figure is per table, and an unknown method is refused by name."""
    from bench.memory import batch_peak

    r = batch_peak(4, "tracemalloc")
    assert r["at_rest"] == 4 and r["peak_bytes"] > 4 * 5_000  # at least its state arrays
    assert r["kb_per_table"] == pytest.approx(r["peak_bytes"] / 4 / 1e3)
    with pytest.raises(ValueError, match="method"):
        batch_peak(4, "guess")
