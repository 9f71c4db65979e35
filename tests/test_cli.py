"""The `termpool` command: sim output, errors, determinism, sampling, bench dispatch."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import types
from pathlib import Path

import pytest

from termpool import cli

ROOT = Path(__file__).resolve().parent.parent
EX = ROOT / "examples"
EXAMPLES = sorted(EX.glob("*.json"))
TOP_KEYS = {"time", "steps", "wall_time", "method", "dt", "balls", "events"}
BALL_KEYS = {"id", "x", "y", "vx", "vy", "w", "state"}
STATES = {"stationary", "spinning", "sliding", "rolling", "pocketed"}
EVENT_TYPES = {
    "ball_ball",
    "cushion",
    "pocket",
    "slide_to_roll",
    "slide_to_spin",
    "slide_to_stop",
    "roll_to_stop",
    "roll_to_spin",
    "spin_to_stop",
}
POCKETS = {"head_left", "head_right", "side_left", "side_right", "foot_left", "foot_right"}


def run(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    return subprocess.run(
        [sys.executable, "-m", "termpool", *args],
        cwd=ROOT,
        env=env,
        input=stdin,
        capture_output=True,
        text=True,
        timeout=300,
    )


def sim(*args: str) -> dict:
    p = run("sim", *args)
    assert p.returncode == 0, p.stderr
    assert p.stderr == ""
    return json.loads(p.stdout)


def check_output(out: dict, method: str = "fixed") -> None:
    assert TOP_KEYS <= set(out)
    assert out["method"] == method
    assert isinstance(out["steps"], int) and out["steps"] >= 0
    assert out["time"] >= 0 and out["wall_time"] >= 0
    ids = [b["id"] for b in out["balls"]]
    assert len(set(ids)) == len(ids)
    for b in out["balls"]:
        assert BALL_KEYS <= set(b) and len(b["w"]) == 3 and b["state"] in STATES
        assert ("pocket" in b) == (b["state"] == "pocketed")
        if "pocket" in b:
            assert b["pocket"] in POCKETS
    ts = [e["t"] for e in out["events"]]
    assert ts == sorted(ts)
    for e in out["events"]:
        assert {"t", "type", "ids", "balls"} <= set(e) and e["type"] in EVENT_TYPES
        assert set(e["ids"]) <= set(ids)
        assert [b["id"] for b in e["balls"]] == e["ids"]
        for b in e["balls"]:
            assert BALL_KEYS <= set(b)
        if e["type"] == "pocket":
            assert e["pocket"] in POCKETS
        if e["type"] == "cushion":
            assert e["feature"] in ("rail", "jaw", "tip")


def without_wall(out: dict) -> dict:
    return {k: v for k, v in out.items() if k != "wall_time"}


# ------------------------------------------------------------------------------- success


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_sim_examples(path: Path) -> None:
    out = sim(str(path.relative_to(ROOT)))
    check_output(out)
    assert out["dt"] == pytest.approx(1 / 60)
    assert "samples" not in out
    assert out["events"], "every example shot produces events"
    # Without --duration the run ends with every ball at rest.
    assert all(b["state"] in ("stationary", "pocketed") for b in out["balls"])


def test_no_arguments_without_a_terminal_points_to_sim() -> None:
    # `termpool` alone plays in the terminal; with no tty it must say so in one line, not hang.
    p = run(stdin="")
    assert p.returncode == 2
    assert p.stdout == ""
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "terminal" in lines[0] and "termpool sim" in lines[0]


def test_help_mentions_default_break() -> None:
    p = run("--help")
    assert p.returncode == 0 and "break.json" in p.stdout and "sim" in p.stdout
    p = run("sim", "--help")
    assert p.returncode == 0 and "--sample-hz" in p.stdout


def test_deterministic_output() -> None:
    a = run("sim", "examples/break.json")
    b = run("sim", "examples/break.json")
    assert a.returncode == b.returncode == 0
    assert without_wall(json.loads(a.stdout)) == without_wall(json.loads(b.stdout))
    # Byte-identical apart from the wall_time line.
    strip = [ln for ln in a.stdout.splitlines() if '"wall_time"' not in ln]
    assert strip == [ln for ln in b.stdout.splitlines() if '"wall_time"' not in ln]


def test_method_event() -> None:
    out = sim("examples/stun.json", "--method", "event")
    check_output(out, "event")
    assert out["dt"] is None
    fixed = sim("examples/stun.json")
    # Both drivers are exact between events: same events, same final positions.
    assert [e["type"] for e in out["events"]] == [e["type"] for e in fixed["events"]]
    for be, bf in zip(out["balls"], fixed["balls"], strict=True):
        assert be["x"] == pytest.approx(bf["x"], abs=1e-6)
        assert be["y"] == pytest.approx(bf["y"], abs=1e-6)


@pytest.mark.parametrize("method", ["fixed", "event"])
def test_sample_hz(method: str) -> None:
    hz = 20
    out = sim("examples/cut.json", "--sample-hz", str(hz), "--method", method)
    check_output(out, method)
    samples = out["samples"]
    assert len(samples) >= 2
    for k, s in enumerate(samples):
        assert s["t"] == pytest.approx(k / hz, abs=1e-9)
        assert s["t"] <= out["time"] + 1e-9
    assert samples[0]["pos"]["cue"] == [0.635, 0.635]
    pocketed = {e["ids"][0]: e["t"] for e in out["events"] if e["type"] == "pocket"}
    assert pocketed, "the cut example pots the 1"
    for s in samples:
        for bid, t in pocketed.items():
            assert (bid in s["pos"]) == (s["t"] < t)
        for x, y in s["pos"].values():
            assert math.isfinite(x) and math.isfinite(y)


def test_duration_stops_early() -> None:
    out = sim("examples/break.json", "--duration", "0.25", "--dt", "0.01")
    check_output(out)
    assert out["time"] == pytest.approx(0.25)
    assert out["dt"] == 0.01
    assert any(b["state"] not in ("stationary", "pocketed") for b in out["balls"])
    assert all(e["t"] <= 0.25 + 1e-9 for e in out["events"])


def test_scene_from_stdin() -> None:
    p = run("sim", "-", stdin=(EX / "draw.json").read_text())
    assert p.returncode == 0, p.stderr
    assert without_wall(json.loads(p.stdout)) == without_wall(sim("examples/draw.json"))


def test_examples_behave_as_described() -> None:
    stun = sim("examples/stun.json")
    first = stun["events"][0]
    assert first["type"] == "ball_ball" and first["ids"] == ["cue", "1"]
    cue, obj = first["balls"]
    assert math.hypot(cue["vx"], cue["vy"]) < 0.01  # stops dead
    assert obj["vx"] == pytest.approx(1.8, abs=0.01)
    cut = {b["id"]: b for b in sim("examples/cut.json")["balls"]}
    assert cut["1"].get("pocket") == "foot_left" and "pocket" not in cut["cue"]
    draw = sim("examples/draw.json")
    hit = next(e for e in draw["events"] if e["type"] == "ball_ball")
    assert draw["balls"][0]["x"] < hit["balls"][0]["x"] - 0.05  # the cue ball came back
    bank = sim("examples/bank.json")
    assert any(e["type"] == "cushion" for e in bank["events"])
    assert not any(e["type"] == "pocket" for e in bank["events"])


# -------------------------------------------------------------------------------- errors


def bad_scenes(tmp_path: Path) -> dict[str, Path]:
    files = {
        "json": '{"balls": "8ball",,}',
        "overlap": json.dumps({"balls": [{"x": 1, "y": 0.5}, {"x": 1.01, "y": 0.5}]}),
        "unknown": json.dumps({"table": {"lenght": 2}}),
        "physics": json.dumps({"physics": {"mu_slide": -1}}),
        "miscue": json.dumps({"shot": {"speed": 3, "top": 0.9}}),
        "empty": "",
    }
    out = {}
    for name, text in files.items():
        p = tmp_path / f"{name}.json"
        p.write_text(text)
        out[name] = p
    return out


def assert_usage_error(p: subprocess.CompletedProcess, *fragments: str) -> None:
    assert p.returncode == 2
    assert p.stdout == ""
    assert "Traceback" not in p.stderr
    lines = p.stderr.splitlines()
    assert len(lines) == 1, p.stderr
    assert lines[0].startswith("termpool: ")
    for f in fragments:
        assert f in lines[0]


def test_bad_scenes_exit_2(tmp_path: Path) -> None:
    scenes = bad_scenes(tmp_path)
    expect = {
        "json": "invalid JSON at line 1 column",
        "overlap": "balls[1] (id '1'): overlaps ball 'cue'",
        "unknown": "table: unknown key 'lenght'",
        "physics": "physics.mu_slide: must not be negative",
        "miscue": "miscue",
        "empty": "empty, where JSON was expected",
    }
    for name, path in scenes.items():
        assert_usage_error(run("sim", str(path)), expect[name])


@pytest.mark.parametrize(
    "args, fragment",
    [
        (["sim", "no/such/scene.json"], "cannot read scene 'no/such/scene.json'"),
        (["sim", "examples/break.json", "--dt", "0"], "--dt"),
        (["sim", "examples/break.json", "--dt", "-0.01"], "--dt"),
        (["sim", "examples/break.json", "--dt", "fast"], "not a number"),
        (["sim", "examples/break.json", "--dt", "inf"], "--dt"),
        (["sim", "examples/break.json", "--duration", "-1"], "--duration"),
        (["sim", "examples/break.json", "--sample-hz", "0"], "--sample-hz"),
        (["sim", "examples/break.json", "--dt", "1e-300"], "--dt: must be from 0.0001 to 1"),
        # (a range from 0 says 0 is out: "0" is refused as not positive)
        (["sim", "examples/break.json", "--duration", "1e9"], "--duration: must be above 0 and "
                                                               "at most 3600"),
        (["sim", "examples/break.json", "--sample-hz", "1e300"], "--sample-hz: must be above 0"),
        (["records", "--last", "x"], "--last: must be a whole number from 1 up, not 'x'"),
        (["records", "--last", "0"], "--last: must be a whole number from 1 up"),
        (["sim", "examples/break.json", "--method", "rk4"], "--method"),
        (["sim", "examples/break.json", "--bogus"], "--bogus"),
        (["sim"], "SCENE"),
        (["play"], "play"),
    ],
)
def test_bad_options_exit_2(args: list[str], fragment: str) -> None:
    assert_usage_error(run(*args), fragment)


def test_bad_scene_in_process(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    p = tmp_path / "s.json"
    p.write_text(json.dumps({"balls": [{"id": "cue", "x": 9, "y": 0.5}]}))
    assert cli.main(["sim", str(p)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("termpool: balls[0] (id 'cue'): off the table") and err.count("\n") == 1


# ---------------------------------------------------------------------------------- misc


def test_bench_dispatch(monkeypatch: pytest.MonkeyPatch) -> None:
    seen = []
    fake = types.ModuleType("bench")
    fake.main = lambda args: seen.append(list(args)) or 3
    monkeypatch.setitem(sys.modules, "bench", fake)
    assert cli.main(["bench", "--quick", "-n", "5"]) == 3
    assert seen == [["--quick", "-n", "5"]]


def test_bench_runs_from_a_checkout_outside_it(tmp_path: Path) -> None:
    """The benchmarks sit beside the package in the checkout: `termpool bench` finds them
    from any directory, as an editable install runs it."""
    p = subprocess.run([sys.executable, "-m", "termpool", "bench", "--help"], cwd=tmp_path,
                       capture_output=True, text=True,
                       env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert p.returncode == 0, p.stderr
    assert "speed" in p.stdout and "stability" in p.stdout


def test_bench_without_the_benchmarks_is_one_line_and_status_2(tmp_path: Path) -> None:
    """An installed game has the package and no `bench` beside it (as `pip install .` puts
    it in site-packages): one line saying so, exit status 2, and the game itself still runs."""
    import shutil

    site = tmp_path / "site"
    shutil.copytree(ROOT / "termpool", site / "termpool",
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = {**os.environ, "PYTHONPATH": str(site)}
    p = subprocess.run([sys.executable, "-m", "termpool", "bench", "speed"], cwd=tmp_path,
                       capture_output=True, text=True, env=env)
    assert p.returncode == 2
    assert p.stdout == "" and p.stderr.count("\n") == 1
    assert p.stderr.startswith("termpool: bench: the benchmarks are not installed")
    p = subprocess.run([sys.executable, "-m", "termpool", "sim",
                        str(site / "termpool" / "examples" / "cut.json")], cwd=tmp_path,
                       capture_output=True, text=True, env=env)
    assert p.returncode == 0 and json.loads(p.stdout)["balls"], p.stderr


def test_cli_import_is_light() -> None:
    code = "import sys, termpool.cli; print('numpy' in sys.modules)"
    p = subprocess.run(
        [sys.executable, "-c", code],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert p.stdout.strip() == "False", p.stderr


def test_dump_json_is_valid_and_stable() -> None:
    result = {"time": 1.5, "dt": None, "balls": [{"id": "1", "w": [0.0, 1.0, 2.0]}], "events": []}
    text = cli.dump_json(result)
    assert json.loads(text) == result
    assert text == cli.dump_json(json.loads(text))


def test_scene_that_never_rests_needs_a_duration(tmp_path: Path) -> None:
    scene = {
        "table": {"length": 2.54, "width": 1.27, "pockets": "none"},
        "physics": {"mu_roll": 0},
        "balls": [{"id": "cue", "x": 0.5, "y": 0.5, "vx": 1.0, "vy": 0.3}],
    }
    path = tmp_path / "endless.json"
    path.write_text(json.dumps(scene))
    assert_usage_error(run("sim", str(path)), "physics.mu_roll", "--duration")
    out = sim(str(path), "--duration", "2")
    assert out["time"] == pytest.approx(2.0)
    assert out["balls"][0]["state"] in ("sliding", "rolling")


def test_the_top_help_speaks_to_players_and_names_watching_a_match() -> None:
    p = run("--help")
    assert p.returncode == 0
    out = " ".join(p.stdout.split())
    assert "8-ball, 9-ball and practice" in out
    assert "--record match.json" in out and "replay FILE --watch" in out
    assert "termpool records" in out
    assert "batched" not in out and "physics core" not in out


# What `termpool sim` imports: the physics and the scene, the rules only for a scene with a
# game block, never the game, the computer or the UI (its start-up is most of a short run's
# time; docs/performance.md).
_MODULES = (
    "import atexit, runpy, sys\n"
    "atexit.register(lambda: sys.stderr.write('\\nMODULES ' + ' '.join(sorted(sys.modules))))\n"
    "sys.argv = ['termpool', *sys.argv[1:]]\n"
    "runpy.run_module('termpool', run_name='__main__', alter_sys=True)\n"
)


def sim_modules(scene: str) -> set[str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    p = subprocess.run([sys.executable, "-c", _MODULES, "sim", scene], env=env,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert json.loads(p.stdout)["balls"]
    return set(p.stderr.rsplit("MODULES ", 1)[1].split())


def _under(modules: set[str], *packages: str) -> list[str]:
    return sorted(m for m in modules if any(m == p or m.startswith(p + ".") for p in packages))


def test_sim_imports_neither_the_ui_nor_the_game(tmp_path):
    one = tmp_path / "one.json"
    one.write_text(json.dumps({"table": "9ft", "balls": [{"id": "cue", "x": 0.6, "y": 0.6}],
                               "shot": {"speed": 2.0, "angle": 10}}))
    modules = sim_modules(str(one))
    assert "termpool.physics.engine" in modules and "termpool.scene" in modules
    assert _under(modules, "blessed", "termpool.ui", "termpool.game", "termpool.ai",
                  "termpool.selfplay", "termpool.rules") == []
    # A scene with a game block brings the referee, and still not the UI.
    modules = sim_modules(str(EX / "referee_pot.json"))
    assert "termpool.rules.referee" in modules
    assert _under(modules, "blessed", "termpool.ui", "termpool.game", "termpool.ai",
                  "termpool.selfplay") == []
