"""Shot records and `termpool replay`: a saved match replays bit for bit, tampering is found
and named, and malformed files give one clear line and exit status 2."""

from __future__ import annotations

import copy
import json
import math
import sys
from dataclasses import replace
from pathlib import Path

import pytest

from termpool import cli
from termpool.game import Match, Shot
from termpool.game.record import first_difference, replay
from termpool.scene import load_scene


def play_match() -> dict:
    """A short 9-ball match: a break, then a few shots (whatever they do), with any option
    answered, saved through JSON."""
    m = Match("9ball", seed=1, players=("Ann", "Bob"))
    m.begin(Shot(8.0, 0.0)).finish()
    for angle in (30.0, -120.0, 75.0):
        if m.option:
            m.choose(m.option.split("_or_")[0])
        if m.frame_over:
            break
        m.begin(Shot(2.5, angle, top=0.2)).finish()
    return json.loads(json.dumps(m.to_json()))


@pytest.fixture(scope="module")
def saved() -> dict:
    return play_match()


def write(tmp_path: Path, data, name: str = "match.json") -> str:
    p = tmp_path / name
    p.write_text(data if isinstance(data, str) else json.dumps(data))
    return str(p)


def run_cli(capsys, *argv: str) -> tuple[int, str, str]:
    rc = cli.main(["replay", *argv])
    out, err = capsys.readouterr()
    return rc, out, err


# --------------------------------------------------------------------------------- records


def test_record_holds_what_the_brief_asks(saved) -> None:
    rec = saved["shots"][0]
    assert set(rec) == {"n", "frame", "player", "scene", "shot", "dt", "time", "steps",
                        "events", "final", "outcome"}
    assert rec["shot"] == {"speed": 8.0, "angle": 0.0, "side": 0.0, "top": 0.0,
                           "called": None, "push_out": False}
    assert rec["scene"]["game"]["break"] is True and rec["dt"] == 1 / 60
    # The scene loads as a scene, balls at rest on the racked table.
    scene = load_scene(rec["scene"])
    assert scene.ids == ["cue", *(str(n) for n in range(1, 10))]
    assert not scene.vel.any() and not scene.w.any()
    ev = rec["events"][0]
    assert {"t", "type", "ids", "balls"} <= set(ev)
    assert rec["outcome"]["reason"]


def test_records_chain_from_shot_to_shot(saved) -> None:
    """The scene of each shot is the table the previous one left (pocketed balls gone)."""
    shots = saved["shots"]
    assert len(shots) >= 3
    for a, b in zip(shots, shots[1:], strict=False):
        left = {f["id"]: (f["x"], f["y"]) for f in a["final"] if f["state"] != "pocketed"}
        now = {s["id"]: (s["x"], s["y"]) for s in b["scene"]["balls"]}
        respot = set(a["outcome"]["respot"]) | ({"cue"} if "cue" not in left else set())
        assert set(now) == set(left) | respot
        assert all(now[k] == left[k] for k in left if k not in respot)


def test_sim_on_a_record_scene_gives_the_recorded_shot(saved, capsys, tmp_path) -> None:
    """`termpool sim` on a record's scene plus its shot prints the same events and outcome."""
    rec = saved["shots"][1]
    scene = {**rec["scene"], "shot": {"ball": "cue", **{k: rec["shot"][k] for k in
                                                          ("speed", "angle", "side", "top")}}}
    assert cli.main(["sim", write(tmp_path, scene)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["events"] == rec["events"] and out["balls"] == rec["final"]
    assert out["outcome"] == rec["outcome"]


# -------------------------------------------------------------------------------- replaying


def test_round_trip_replays_identically(saved, capsys, tmp_path) -> None:
    rc, out, err = run_cli(capsys, write(tmp_path, saved))
    assert rc == 0 and err == ""
    lines = out.splitlines()
    assert len(lines) == len(saved["shots"]) + 1
    assert all("identical" in line for line in lines)
    assert lines[-1] == f"{len(saved['shots'])} shots: all identical"


def test_at_a_terminal_the_check_says_how_to_watch_the_match(saved, capsys, tmp_path,
                                                              monkeypatch) -> None:
    """Someone typing `termpool replay FILE` may have meant to watch it: at a terminal the
    check ends by saying how; a script reading the output (no terminal) gets the checks
    alone, and so does --json."""
    path = write(tmp_path, saved)
    monkeypatch.setattr(sys.stdout, "isatty", lambda: True)
    rc, out, _ = run_cli(capsys, path)
    assert rc == 0
    assert out.splitlines()[-2:] == [f"{len(saved['shots'])} shots: all identical",
                                     f"to watch it: termpool replay {path} --watch"]
    rc, out, _ = run_cli(capsys, path, "--json")
    assert "--watch" not in out and json.loads(out)["identical"] is True
    monkeypatch.setattr(sys.stdout, "isatty", lambda: False)
    rc, out, _ = run_cli(capsys, path)
    assert "watch" not in out


def test_round_trip_json(saved, capsys, tmp_path) -> None:
    rc, out, _ = run_cli(capsys, write(tmp_path, saved), "--json")
    res = json.loads(out)
    assert rc == 0 and res["identical"] is True
    assert [s["n"] for s in res["shots"]] == [r["n"] for r in saved["shots"]]
    assert all(s["ok"] and s["differences"] == [] for s in res["shots"])
    assert [s["events"] for s in res["shots"]] == [len(r["events"]) for r in saved["shots"]]


def test_loaded_match_replays_and_saves_the_same(saved) -> None:
    m = Match.from_json(copy.deepcopy(saved))
    again = json.loads(json.dumps(m.to_json()))
    assert again == saved
    assert all(r["ok"] for r in replay(again))


def nudge(x: float) -> float:
    return math.nextafter(x, math.inf)


@pytest.mark.parametrize(
    "change, where",
    [
        (lambda s: s["events"][3].update(t=nudge(s["events"][3]["t"])), "events[3].t"),
        (lambda s: s["events"][5]["balls"][0].update(x=nudge(s["events"][5]["balls"][0]["x"])),
         "events[5].balls[0].x"),
        (lambda s: s["events"].pop(), "events: "),
        (lambda s: s["final"][1].update(y=nudge(s["final"][1]["y"])), "final[1].y"),
        (lambda s: s["final"][2].update(state="rolling"), "final[2].state"),
        (lambda s: s["outcome"].update(reason="a fluke"), "outcome.reason"),
        (lambda s: s["shot"].update(angle=nudge(s["shot"]["angle"])), "events"),
        (lambda s: s["scene"]["balls"][0].update(x=nudge(s["scene"]["balls"][0]["x"])),
         "events"),
        (lambda s: s.update(steps=s["steps"] + 1), "steps"),
        (lambda s: s["final"][0].update(vx=-0.0), "final[0].vx"),  # bit for bit: -0.0 != 0.0
    ],
)
def test_tampered_replay_is_caught(saved, capsys, tmp_path, change, where) -> None:
    data = copy.deepcopy(saved)
    change(data["shots"][1])
    rc, out, _ = run_cli(capsys, write(tmp_path, data))
    assert rc == 1
    bad = [line for line in out.splitlines() if "DIFFERS" in line]
    assert len(bad) == 1 and bad[0].startswith("shot 2 ") and where in bad[0]
    assert out.splitlines()[-1].endswith("1 differ")


def test_a_moved_ball_the_shot_leaves_alone_is_caught(saved, capsys, tmp_path) -> None:
    """A ball no event names ends where the (tampered) scene puts it: its final place differs."""
    data = copy.deepcopy(saved)
    rec = data["shots"][1]
    named = {b for ev in rec["events"] for b in ev["ids"]}
    k, ball = next((k, b) for k, b in enumerate(rec["scene"]["balls"]) if b["id"] not in named)
    ball["x"] = nudge(ball["x"])
    rc, out, _ = run_cli(capsys, write(tmp_path, data))
    assert rc == 1 and f"DIFFERS: final[{k}].x: recorded " in out.splitlines()[1]


def test_first_difference() -> None:
    assert first_difference({"a": [1.0, 2]}, {"a": [1.0, 2.0]}) is None
    assert first_difference([0.0], [-0.0]) == "[0]: recorded 0.0, replayed -0.0"
    assert first_difference({"a": 1}, {"b": 1}) == "a: only in the recorded shot"
    assert first_difference({"a": True}, {"a": 1}) == "a: recorded true, replayed 1"
    assert first_difference({"a": [1]}, {"a": [1, 2]}) == "a: 1 recorded, 2 replayed"


# ----------------------------------------------------------------------- malformed files


def shot0(d: dict) -> dict:
    return d["shots"][0]


MALFORMED = [
    ("{", "invalid JSON at line 1"),
    ("[1, 2]", "must be a JSON object"),
    ({"format": "termpool-replay"}, "missing key 'shots'"),
    ({"shots": {}}, "shots: must be a list"),
    ({"shots": [3]}, "shots[0]: must be an object"),
    (lambda d: shot0(d).pop("dt"), "shots[0]: missing key 'dt'"),
    (lambda d: shot0(d).pop("events"), "shots[0]: missing key 'events'"),
    (lambda d: shot0(d).update(dt=-0.1), "shots[0].dt: must be a positive number"),
    (lambda d: shot0(d).update(dt="1/60"), "shots[0].dt: must be a positive number"),
    (lambda d: shot0(d).update(dt=1e-300), "shots[0].dt: must be from 0.0001 to 1 seconds, "
                                           "not 1e-300"),
    (lambda d: shot0(d).update(dt=5.0), "shots[0].dt: must be from 0.0001 to 1 seconds"),
    (lambda d: d.update(match={"players": [1, 2]}), "match.players: must be a list of two"),
    (lambda d: d["match"].update(players=["a", None]), "match.players: must be a list of two"),
    (lambda d: d["match"].update(players="ab"), "match.players: must be a list of two"),
    (lambda d: d.update(match=[]), "match: must be an object"),
    (lambda d: shot0(d)["scene"]["balls"][0].update(radius=1e-200),
     "shots[0].scene: balls[0].radius: must be at least 0.001 m"),
    (lambda d: shot0(d)["shot"].update(speed=1e308), "shots[0].scene: shot.speed: must be at "
                                                     "most 25 m/s"),
    (lambda d: shot0(d).update(n=1.5), "shots[0].n: must be a whole number"),
    (lambda d: shot0(d).update(time=None), "shots[0].time: must be a finite number"),
    (lambda d: shot0(d).update(events={}), "shots[0].events: must be a list"),
    (lambda d: shot0(d).update(final="x"), "shots[0].final: must be a list"),
    (lambda d: shot0(d).update(outcome=[]), "shots[0].outcome: must be an object"),
    (lambda d: shot0(d).update(scene=[]), "shots[0].scene: must be an object"),
    (lambda d: shot0(d)["shot"].pop("speed"), "shots[0].shot: missing key 'speed'"),
    (lambda d: shot0(d)["shot"].update(angle="up"), "shots[0].shot.angle: must be a finite"),
    (lambda d: shot0(d)["shot"].update(speed=-2.0), "shots[0].scene: shot.speed: must not be"),
    (lambda d: shot0(d)["shot"].update(side=0.6), "miscue"),
    (lambda d: shot0(d)["shot"].update(called="8"), "shots[0].shot.called"),
    (lambda d: shot0(d)["shot"].update(push_out=1), "shots[0].shot.push_out"),
    (lambda d: shot0(d)["scene"]["balls"][1].update(x=shot0(d)["scene"]["balls"][2]["x"],
                                                    y=shot0(d)["scene"]["balls"][2]["y"]),
     "shots[0].scene: balls[2] (id '2'): overlaps ball '1'"),
    (lambda d: shot0(d)["scene"]["balls"][0].pop("x"), "shots[0].scene: balls[0] (id 'cue'): "
                                                       "missing key 'x'"),
    (lambda d: shot0(d)["scene"]["physics"].update(mu_roll=0.0),
     "shots[0].scene.physics.mu_roll: must be positive"),
    (lambda d: shot0(d)["scene"].update(shot={"speed": 1.0}), "must not hold a 'shot'"),
    (lambda d: d["shots"][2].pop("scene"), "shots[2]: missing key 'scene'"),
]


@pytest.mark.parametrize("change, words", MALFORMED)
def test_malformed_replay_exits_2_with_one_line(saved, capsys, tmp_path, change,
                                                words) -> None:
    if callable(change):
        data = copy.deepcopy(saved)
        change(data)
    else:
        data = change
    rc, out, err = run_cli(capsys, write(tmp_path, data))
    assert rc == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("termpool: ") and words in err
    assert "Traceback" not in err
    if "shots[" in words:  # a shot is also counted as the screens count it, from 1
        k = int(words.split("shots[")[1].split("]")[0])
        assert err.startswith(f"termpool: shot {k + 1}: shots[{k}]"), err


def test_missing_file_exits_2(capsys, tmp_path) -> None:
    rc, out, err = run_cli(capsys, str(tmp_path / "nope.json"))
    assert rc == 2 and "cannot read" in err and "nope.json" in err


def test_not_utf8_exits_2(capsys, tmp_path) -> None:
    p = tmp_path / "bin.json"
    p.write_bytes(b"\xff\xfe\x00")
    rc, _, err = run_cli(capsys, str(p))
    assert rc == 2 and "not UTF-8 text" in err


def test_replay_from_stdin(saved, capsys, monkeypatch) -> None:
    import io

    text = json.dumps({"shots": saved["shots"][:1]})
    monkeypatch.setattr("sys.stdin", io.TextIOWrapper(io.BytesIO(text.encode())))
    rc, out, _ = run_cli(capsys, "-")
    assert rc == 0 and out.splitlines()[-1] == "1 shot: all identical"


def test_a_practice_match_with_take_backs_replays(capsys, tmp_path) -> None:
    m = Match("practice", seed=5)
    m.begin(Shot(8.0, 0.0)).finish()
    m.begin(Shot(3.0, 45.0)).finish()
    m.take_back()
    m.begin(Shot(3.0, -45.0)).finish()
    m.rerack()
    m.begin(replace(Shot(6.0, 2.0), side=0.2)).finish()
    rc, out, _ = run_cli(capsys, write(tmp_path, m.to_json()))
    assert rc == 0 and out.splitlines()[-1] == "3 shots: all identical"


def test_summary_names_the_players(saved, capsys, tmp_path) -> None:
    rc, out, _ = run_cli(capsys, write(tmp_path, saved))
    first = out.splitlines()[0]
    assert rc == 0 and first.startswith("shot 1 (frame 1, Ann): identical, ")
    reason = saved["shots"][0]["outcome"]["reason"]
    assert "player 1" in reason  # the referee's words ...
    assert first.endswith(reason.replace("player 1", "Bob"))  # ... with the players' names
