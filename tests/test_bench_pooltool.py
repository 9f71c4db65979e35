"""`termpool bench speed` against pooltool: choosing the interpreter, the worker's protocol and
the pairing, with a stand-in worker so that none of it needs pooltool (no timing thresholds)."""

from __future__ import annotations

import importlib.util
import io
import json
import math
import os
import statistics
import sys
from pathlib import Path

import pytest

import bench
from bench import pooltool_pair, pooltool_worker, speed

# A stand-in for a pooltool interpreter: it runs the real worker's protocol loop (`serve`) with
# a break that burns a little CPU and reports the number of balls it was given as its events.
# It leaves the setup it received, and a mark once the protocol loop has ended.
FAKE = """#!{python}
import json, runpy, sys
worker = runpy.run_path(sys.argv[1])

def make_break(setup):
    with open({setup_file!r} + setup["name"], "w") as f:
        json.dump(setup, f)
    if {fail_setup!r}:
        raise ValueError("no such table")
    n = len(setup["balls"])
    return (lambda: sum(i * i for i in range(20000))), (lambda _: n)

rc = worker["serve"](make_break, "fake 1.0")
open({done_file!r}, "w").close()
raise SystemExit(rc)
"""


def _fake(tmp_path: Path, fail_setup: bool = False, body: str | None = None) -> Path:
    path = tmp_path / "fakepython"
    path.write_text(body or FAKE.format(
        python=sys.executable, setup_file=str(tmp_path / "setup-"),
        done_file=str(tmp_path / "done"), fail_setup=fail_setup))
    path.chmod(0o755)
    return path


@pytest.fixture
def no_pooltool(monkeypatch: pytest.MonkeyPatch) -> None:
    """As on a machine without pooltool: no variable, and this interpreter cannot import it."""
    monkeypatch.delenv(pooltool_pair.ENV, raising=False)
    find = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "pooltool" else find(name, *a))


def _speed_json(capsys: pytest.CaptureFixture[str], *extra: str) -> dict:
    rc = bench.main(["speed", "--json", "--repeat", "1", "--batch", "4", *extra])
    out, err = capsys.readouterr()
    assert rc == 0, err
    return json.loads(out)


# ------------------------------------------------------------------ choosing the interpreter


def test_choose_python_order(monkeypatch: pytest.MonkeyPatch, no_pooltool: None) -> None:
    assert pooltool_pair.choose_python(None, False) is None
    monkeypatch.setenv(pooltool_pair.ENV, "/env/python")
    assert pooltool_pair.choose_python(None, False) == ("/env/python", pooltool_pair.ENV)
    assert pooltool_pair.choose_python("/given/python", False) == ("/given/python", "--pooltool")
    assert pooltool_pair.choose_python("/given/python", True) is None


def test_choose_python_takes_this_interpreter_when_it_has_pooltool(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(pooltool_pair.ENV, raising=False)
    find = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: object() if name == "pooltool" else find(name, *a))
    assert pooltool_pair.choose_python(None, False) == (sys.executable, "this interpreter")


# ------------------------------------------------------------------------------ without it


def test_keys_are_null_without_pooltool(capsys: pytest.CaptureFixture[str],
                                        no_pooltool: None) -> None:
    result = _speed_json(capsys)
    assert result["pooltool"] is None
    for key in pooltool_pair.FIGURES:
        assert key in result and result[key] is None, key
    assert result["targets"][pooltool_pair.KEY] == ">= 4"
    assert result["pass"][pooltool_pair.KEY] is None
    assert math.isfinite(result["break_cpu_ms"])  # the rest is measured as before


def test_text_report_says_pooltool_was_not_measured(capsys: pytest.CaptureFixture[str],
                                                    no_pooltool: None) -> None:
    assert bench.main(["speed", "--repeat", "1", "--batch", "4"]) == 0
    assert "pooltool: not measured" in capsys.readouterr().out


# ------------------------------------------------------------------------------ bad input


@pytest.mark.parametrize("how", ["option", "env"])
def test_bad_interpreter_path_is_one_line_and_exit_2(
        how: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    missing = str(tmp_path / "no-such-python")
    argv = ["speed", "--json", "--repeat", "1", "--batch", "4"]
    if how == "option":
        argv += ["--pooltool", missing]
    else:
        monkeypatch.setenv(pooltool_pair.ENV, missing)
    assert bench.main(argv) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("termpool: bench speed: ")
    assert ("--pooltool" if how == "option" else pooltool_pair.ENV) in err
    assert missing in err


def test_a_directory_is_not_an_interpreter(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.main(["speed", "--pooltool", str(tmp_path)]) == 2
    assert capsys.readouterr().err.count("\n") == 1


@pytest.mark.skipif(importlib.util.find_spec("pooltool") is not None,
                    reason="this interpreter has pooltool")
def test_interpreter_without_pooltool_is_one_line_and_exit_2(
        capsys: pytest.CaptureFixture[str]) -> None:
    # The real worker, in an interpreter that cannot import pooltool.
    assert bench.main(["speed", "--json", "--pooltool", sys.executable]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1 and "cannot import pooltool" in err


def test_a_program_that_is_not_the_worker_is_one_line_and_exit_2(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    fake = _fake(tmp_path, body=f"#!{sys.executable}\nprint('Python 3.11.7')\n")
    assert bench.main(["speed", "--pooltool", str(fake)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "not a worker's answer" in err


def test_a_worker_that_dies_names_its_last_error_line(tmp_path: Path) -> None:
    fake = _fake(tmp_path, body=f"#!{sys.executable}\nraise SystemExit('numba: out of luck')\n")
    with pytest.raises(pooltool_pair.WorkerError) as e:
        pooltool_pair.Worker(str(fake), "--pooltool")
    assert "stopped" in str(e.value) and "numba: out of luck" in str(e.value)
    assert "\n" not in str(e.value)


def test_a_failing_setup_is_one_line(tmp_path: Path) -> None:
    with pooltool_pair.Worker(str(_fake(tmp_path, fail_setup=True)), "--pooltool") as w:
        with pytest.raises(pooltool_pair.WorkerError) as e:
            w.setup(speed.break_scene())
    assert "ValueError: no such table" in str(e.value) and "\n" not in str(e.value)


# ------------------------------------------------------------------- with a stand-in worker


def test_paired_figures_with_a_stand_in_worker(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    fake = _fake(tmp_path)
    r = _speed_json(capsys, "--pooltool", str(fake), "--pairs", "3")
    d = r["pooltool"]
    assert r["pooltool_version"] == "fake 1.0"
    assert d["from"] == "--pooltool" and d["pairs"] == 3 and d["python"] == str(fake)
    scene = speed.break_scene()
    assert set(pooltool_pair.BREAKS) <= set(d)
    for name, (infix, gap) in pooltool_pair.BREAKS.items():
        b = d[name]
        assert b["rack_gap"] == gap
        assert len(b["warm_cpu_s"]) == pooltool_pair.WARM_BREAKS
        term, pool = b["termpool_cpu_ms"], b["pooltool_cpu_ms"]
        assert len(term) == len(pool) == len(b["pooltool_wall_ms"]) == len(b["events"]) == 3
        assert all(t > 0 for t in term) and all(p > 0 for p in pool)
        assert r[f"pooltool{infix}_break_cpu_ms"] == statistics.median(pool)
        assert r[f"pooltool{infix}_pair_termpool_cpu_ms"] == statistics.median(term)
        ratio = statistics.median(p / t for t, p in zip(term, pool, strict=True))
        assert r[f"vs_pooltool{infix}_cpu"] == pytest.approx(ratio, rel=1e-12)
        assert b["termpool_events"] > 0
        # The worker was sent termpool's own break scene: every ball, the cue ball at 8 m/s.
        setup = json.loads((tmp_path / f"setup-{name}").read_text())
        assert r[f"pooltool{infix}_events"] == len(scene.ids) == len(setup["balls"])
        assert [b["id"] for b in setup["balls"]] == scene.ids
        cue = setup["balls"][scene.index("cue")]
        assert cue["pos"] == scene.pos[scene.index("cue")].tolist()
        assert math.hypot(*cue["vel"]) == speed.BREAK_SPEED
        assert setup["table"]["length"] == scene.table.length
        assert setup["warm"] == pooltool_pair.WARM_BREAKS
    assert r["pass"]["vs_pooltool_cpu"] is (r["vs_pooltool_cpu"] >= 4)
    frozen = json.loads((tmp_path / "setup-frozen").read_text())["balls"]
    assert [b["pos"] for b in frozen] == scene.pos.tolist()
    assert (tmp_path / "done").exists()  # the worker saw the end of its input and exited


def test_the_variable_names_the_interpreter(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setenv(pooltool_pair.ENV, str(_fake(tmp_path)))
    assert bench.main(["speed", "--repeat", "1", "--batch", "4", "--pairs", "1"]) == 0
    out = capsys.readouterr().out
    assert "against pooltool fake 1.0" in out and "1 paired runs" in out
    assert "frozen rack" in out and "open rack" in out
    assert (tmp_path / "done").exists()


def test_no_pooltool_skips_a_named_interpreter(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    r = _speed_json(capsys, "--pooltool", str(_fake(tmp_path)), "--no-pooltool")
    assert r["pooltool"] is None and r["vs_pooltool_cpu"] is None
    assert not list(tmp_path.glob("setup-*"))


# ------------------------------------------------------------------------------ the parts


def test_pairs_alternate_which_side_goes_first() -> None:
    log: list[str] = []

    def side(name: str, values: list[float]):
        def run() -> float:
            log.append(name)
            return values[sum(1 for x in log if x == name) - 1]
        return run

    pairs = pooltool_pair.alternate(side("t", [1.0, 2.0, 3.0, 4.0]),
                                    side("p", [10.0, 20.0, 30.0, 40.0]), 4)
    assert log == ["t", "p", "p", "t", "t", "p", "p", "t"]
    assert pairs == [(1.0, 10.0), (2.0, 20.0), (3.0, 30.0), (4.0, 40.0)]


def test_summary_takes_the_median_of_the_pairs_ratios() -> None:
    # Ratios 4, 3 and 6: their median is 4, while the ratio of the medians would be 3.
    s = pooltool_pair.summary([(1.0, 4.0), (2.0, 6.0), (3.0, 18.0)], [5, 7, 7], "_open")
    assert s == {"vs_pooltool_open_cpu": 4.0, "pooltool_open_break_cpu_ms": 6000.0,
                 "pooltool_open_pair_termpool_cpu_ms": 2000.0, "pooltool_open_events": 7}
    assert set(s) <= set(pooltool_pair.FIGURES)


def test_open_rack_keeps_the_cue_ball_and_spreads_the_rack_evenly() -> None:
    scene = speed.break_scene()
    gap = 1e-3
    pos = pooltool_pair.open_rack(scene, gap)
    cue, apex = scene.index("cue"), scene.index(speed.APEX_ID)
    assert (pos[cue] == scene.pos[cue]).all()
    assert pos[apex] == pytest.approx(scene.pos[apex], abs=1e-12)  # on the foot spot
    # Neighbours that touched are 2R (1 + gap) apart; none comes closer than that.
    d = [math.dist(pos[i], pos[j]) for i in range(len(pos)) for j in range(i)
         if cue not in (i, j)]
    touching = 2 * float(scene.radius[0])
    assert min(d) == pytest.approx(touching * (1 + gap), rel=1e-9)
    closest = sum(1 for x in d if x < touching * (1 + 2 * gap))
    assert closest == 30  # a 15-ball triangle: 10 contacts within rows, 20 between them


def test_judge_marks_the_target() -> None:
    for value, verdict in ((4.0, True), (3.99, False), (None, None)):
        out: dict = {"targets": {}, "pass": {}, "vs_pooltool_cpu": value}
        pooltool_pair.judge(out)
        assert out["targets"]["vs_pooltool_cpu"] == ">= 4"
        assert out["pass"]["vs_pooltool_cpu"] is verdict


def _serve(lines: list[str]) -> tuple[int, list[dict]]:
    out = io.StringIO()
    brk = (lambda: "done", lambda result: len(result))
    rc = pooltool_worker.serve(lambda setup: brk, "v", io.StringIO("".join(lines)), out)
    return rc, [json.loads(x) for x in out.getvalue().splitlines()]


def test_worker_protocol() -> None:
    rc, answers = _serve(['{"op": "setup", "warm": 3}\n', '{"op": "break"}\n'])
    assert rc == 0
    assert answers[0] == {"ok": True, "version": "v"}
    assert answers[1]["ok"] and answers[1]["events"] == 4 and len(answers[1]["warm_cpu_s"]) == 3
    assert answers[2]["ok"] and answers[2]["events"] == 4
    assert answers[2]["cpu_s"] >= 0 and answers[2]["wall_s"] >= 0


@pytest.mark.parametrize("line", ['{"op": "break"}\n', '{"op": "jump"}\n', "not json\n"])
def test_worker_refuses_in_one_line_and_stops(line: str) -> None:
    rc, answers = _serve([line, '{"op": "setup"}\n'])
    assert rc == 1
    assert len(answers) == 2 and answers[1]["ok"] is False
    assert answers[1]["error"] and "\n" not in answers[1]["error"]


def test_worker_imports_nothing_of_termpool() -> None:
    # It runs in pooltool's environment, where termpool is not installed.
    text = Path(pooltool_worker.__file__).read_text()
    assert "termpool" not in "".join(
        line for line in text.splitlines() if line.lstrip().startswith(("import", "from")))
    assert os.access(pooltool_pair.WORKER, os.R_OK)
