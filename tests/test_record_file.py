"""`termpool play --record FILE`: checked before play, saved on every way out (the end, Q mid-
shot, Ctrl-C, signals, a crash), written atomically, never replacing a file without --force,
and sent to the data directory when the target cannot take it. (The terminal's ways out are in
test_ui_e2e.py.)"""

from __future__ import annotations

import ast
import contextlib
import io
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest
from unprivileged import as_nobody

from termpool import cli, files
from termpool.ui.app import App
from termpool.ui.phases.turn import start_turn
from termpool.ui.state import Phase

ROOT = Path(__file__).resolve().parent.parent
PLAY = ("play", "--headless", "--mode", "practice")


def keys(tmp_path: Path, script: str) -> str:
    p = tmp_path / "keys.txt"
    p.write_text(script)
    return str(p)


def replays(path: Path, capsys) -> str:
    """The verdict line of `termpool replay` on the file (which must replay identically)."""
    capsys.readouterr()
    assert cli.main(["replay", str(path)]) == 0
    return capsys.readouterr().out.splitlines()[-1]


def test_quitting_while_the_balls_roll_saves_the_shot_played_out(capsys, tmp_path) -> None:
    rec = tmp_path / "x.json"
    rc = cli.main([*PLAY, "--keys", keys(tmp_path, "enter space-hold 1.0 wait 0.3 q y"),
                   "--record", str(rec)])
    err = capsys.readouterr().err
    assert rc == 0
    assert err == f"termpool: record saved to {rec} (1 shot)\n"
    assert replays(rec, capsys) == "1 shot: all identical"


def test_a_record_file_named_gz_is_written_compressed_and_replays(capsys, tmp_path) -> None:
    # Two matches (practice, one shot, M for the menu, practice again, one shot, quit).
    rec, second = tmp_path / "x.json.gz", tmp_path / "x-2.json.gz"
    one = "enter space-hold 1.0 wait 20"
    rc = cli.main(["play", "--headless", "--keys", keys(tmp_path, f"5 {one} q m 5 {one} q y"),
                   "--record", str(rec)])
    assert rc == 0
    assert capsys.readouterr().err.splitlines() == [
        f"termpool: record saved to {rec} (1 shot)", f"termpool: record saved to {second} (1 shot)"]
    for p in rec, second:
        assert p.read_bytes()[:2] == files.GZIP_MAGIC
        assert replays(p, capsys) == "1 shot: all identical"


def test_a_crash_in_the_game_still_saves_the_record(capsys, tmp_path, monkeypatch) -> None:
    rec = tmp_path / "x.json"
    tick = App.tick

    def crash_after_the_first_shot(self, t):
        if self.state.match.history:
            raise RuntimeError("boom")
        tick(self, t)

    monkeypatch.setattr(App, "tick", crash_after_the_first_shot)
    with pytest.raises(RuntimeError, match="boom"):
        cli.main([*PLAY, "--keys", keys(tmp_path, "enter space-hold 1.0 wait 20 x"),
                  "--record", str(rec)])
    assert f"record saved to {rec} (1 shot)" in capsys.readouterr().err
    monkeypatch.undo()
    assert replays(rec, capsys) == "1 shot: all identical"


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_during_a_headless_game_still_saves_the_record(capsys, tmp_path, sig,
                                                                code) -> None:
    rec = tmp_path / "x.json"
    script = "enter " + " ".join(f"left*3 space-hold {0.3 + k % 5 * 0.1:.1f} wait 15"
                                 for k in range(40))  # many shots: seconds of work
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    p = subprocess.Popen([sys.executable, "-m", "termpool", *PLAY, "--keys",
                          keys(tmp_path, script), "--record", str(rec)], cwd=ROOT, env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(3.0)  # well into the game (started, not finished: that takes far longer)
    p.send_signal(sig)
    out, err = p.communicate(timeout=120)
    assert p.returncode == code, err
    assert "Traceback" not in err and err.startswith(f"termpool: record saved to {rec} (")
    assert replays(rec, capsys).endswith(": all identical")


def test_an_existing_file_is_refused_before_play_without_force(capsys, tmp_path) -> None:
    rec = tmp_path / "x.json"
    rec.write_text("an earlier match")
    argv = [*PLAY, "--keys", keys(tmp_path, "enter space-hold 1.0 wait 1"), "--record",
            str(rec)]
    assert cli.main(argv) == 2
    out, err = capsys.readouterr()
    assert out == ""  # refused before play
    assert err == f"termpool: play: --record: cannot write '{rec}': exists (pass --force to " \
                  "replace it)\n"
    assert rec.read_text() == "an earlier match"
    assert cli.main([*argv, "--force"]) == 0
    err = capsys.readouterr().err
    assert err == f"termpool: record saved to {rec} (1 shot; it replaced the file that was " \
                  "there)\n"
    assert replays(rec, capsys) == "1 shot: all identical"


@pytest.mark.parametrize("where, why", [
    ("missing/x.json", "no such directory"), (".", "is a directory"),
    ("/dev/null", "exists and is not a regular file"), ("/proc/x.json", ""),
])
def test_a_record_path_that_cannot_be_written_is_refused_before_play(capsys, tmp_path, where,
                                                                     why) -> None:
    path = where if where.startswith("/") else str(tmp_path / where)
    rc = cli.main([*PLAY, "--keys", keys(tmp_path, "enter"), "--record", path, "--force"])
    out, err = capsys.readouterr()
    assert rc == 2 and out == ""
    assert err.startswith(f"termpool: play: --record: cannot write '{path}': {why}")
    assert err.count("\n") == 1


def test_a_record_path_without_permission_is_refused_before_play(tmp_path) -> None:
    d = Path(tempfile.mkdtemp(dir="/tmp"))
    script = d / "keys.txt"
    script.write_text("enter")
    d.chmod(0o555)

    def play():
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            rc = cli.main([*PLAY, "--keys", str(script), "--record", str(d / "x.json")])
        return rc, err.getvalue()

    try:
        rc, err = ast.literal_eval(as_nobody(play))
    finally:
        d.chmod(0o700)
        shutil.rmtree(d)
    assert rc == 2 and err.endswith("cannot write '" + str(d / "x.json") + "': Permission "
                                    "denied\n")


def test_a_failed_write_at_the_end_goes_to_the_data_directory(capsys, tmp_path,
                                                              monkeypatch) -> None:
    rec = tmp_path / "x.json"
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    write = files.write_atomic

    def disk_full_for_the_target(path, text):
        if Path(path) == rec:
            raise OSError(28, "No space left on device")
        write(path, text)

    monkeypatch.setattr(files, "write_atomic", disk_full_for_the_target)
    rc = cli.main([*PLAY, "--keys", keys(tmp_path, "enter space-hold 1.0 wait 1"), "--record",
                   str(rec)])
    err = capsys.readouterr().err
    (spare,) = (tmp_path / "data" / "termpool").glob("record-*")  # beside the history
    assert rc == 1 and not rec.exists()
    assert err == f"termpool: cannot write the record to '{rec}' (No space left on device); " \
                  f"it was saved to {spare} (1 shot)\n"
    assert replays(spare, capsys) == "1 shot: all identical"


def test_a_file_size_limit_leaves_the_old_file_whole(tmp_path) -> None:
    # A record larger than the process may write: before, a truncated file replaced the old
    # one. Now neither the target nor the data directory takes a partial file.
    rec = tmp_path / "x.json"
    rec.write_text('{"an": "earlier match"}')
    data = tmp_path / "data"
    env = dict(os.environ, PYTHONPATH=str(ROOT), XDG_DATA_HOME=str(data))

    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))

    p = subprocess.run([sys.executable, "-m", "termpool", *PLAY, "--keys",
                        keys(tmp_path, "enter space-hold 1.0 wait 1"), "--record", str(rec),
                        "--force"], cwd=ROOT, env=env, capture_output=True, text=True,
                       preexec_fn=limit, timeout=120)
    assert p.returncode == 1
    assert p.stderr.startswith(f"termpool: cannot write the record to '{rec}' (File too large)")
    assert p.stderr.endswith(": it is lost\n")
    assert rec.read_text() == '{"an": "earlier match"}'
    assert sorted(os.listdir(tmp_path)) == ["data", "keys.txt", "x.json"]  # no partial files
    # nor in the data directory, where only the history of play (a short line) may be
    assert [f.name for f in data.rglob("*") if f.is_file()] in ([], ["history.jsonl"])


def test_record_to_stdout_is_all_stdout_has_and_the_screen_goes_to_stderr(capsys,
                                                                          tmp_path) -> None:
    rc = cli.main([*PLAY, "--keys", keys(tmp_path, "enter space-hold 1.0 wait 1"), "--record",
                   "-"])
    out, err = capsys.readouterr()
    assert rc == 0
    saved = json.loads(out)  # a pipe gets the match and nothing else
    assert len(saved["shots"]) == 1
    assert "You to shoot" in err  # the final screen, as it is shown without --record -


def test_leaving_from_the_menu_says_there_is_nothing_to_save(capsys, tmp_path) -> None:
    rec = tmp_path / "x.json"
    rc = cli.main(["play", "--headless", "--keys", keys(tmp_path, "q"), "--record", str(rec)])
    assert rc == 0 and not rec.exists()
    assert capsys.readouterr().err == "termpool: no match was played, so there is no record " \
                                      "to save\n"


def test_a_record_holding_a_nan_is_not_written_as_bad_json(capsys, tmp_path,
                                                           monkeypatch) -> None:
    """JSON has no NaN: should a match ever hold one, the record says so in one line and no
    file with a NaN token is left for a replay to choke on."""
    from termpool.game import Match

    real = Match.to_json

    def with_nan(self):
        d = real(self)
        d["current"]["balls"][0]["x"] = float("nan")
        return d

    monkeypatch.setattr(Match, "to_json", with_nan)
    rec = tmp_path / "x.json"
    rc = cli.main([*PLAY, "--keys", keys(tmp_path, "enter space-hold 1.0 wait 1"), "--record",
                   str(rec)])
    err = capsys.readouterr().err
    assert rc == 1 and not rec.exists()
    assert err == ("termpool: cannot write the record: current.balls[0].x is nan, not a finite "
                   "number (JSON has no NaN or Infinity): it is lost\n")


# ------------------------------------------------------------- every match of a session

def nine_alone(app: App) -> None:
    """The match in play comes down to the 9 alone in front of the cue ball, on the aim."""
    app.state = nine_alone_in(app.state)


def nine_alone_in(s):
    m = s.match
    m.ball_in_hand = None
    for k, b in enumerate(m.ids):
        m.on_table[k] = b in ("cue", "9")
    m.state = m.state.__class__(mode="9ball", shooter=0, pocketed=tuple("12345678"))
    m.pos[m.index("9")] = (m.table.length - 0.3, m.table.width - 0.3)
    m.pos[m.index("cue")] = (m.table.length - 0.8, m.table.width - 0.8)
    return start_turn(s)


def session(tmp_path: Path, force: bool = False):
    from termpool.ui.app import Options
    from termpool.ui.records import Records

    return App(Options(mode="9ball", opponent="human", colors="mono", seed=0),
               records=Records(str(tmp_path / "m.json"), force))


def win(app: App, t: float) -> float:
    from termpool.ui.headless import play as play_keys
    from termpool.ui.keys import parse_script

    nine_alone(app)
    play_keys(app, parse_script("down*4 space-hold 0.5 wait 20"), 100, 32)
    assert app.state.phase is Phase.OVER and app.state.match.winner == 0
    return t + 30.0


def leave(app: App, capsys, tmp_path: Path) -> list[str]:
    import argparse

    from termpool.ui.play import _leave

    capsys.readouterr()
    assert _leave(app, argparse.Namespace(record=str(tmp_path / "m.json"), force=False)) == 0
    return capsys.readouterr().err.splitlines()


def test_a_match_won_is_saved_at_once_and_kept_after_the_menu(capsys, tmp_path) -> None:
    from termpool.ui.keys import Key

    app = session(tmp_path)
    t = win(app, 0.0)
    rec = tmp_path / "m.json"
    assert replays(rec, capsys) == "1 shot: all identical"  # on disk before anything else
    app.key(Key("m"), t)
    app.key(Key("q"), t + 1)  # the menu's Q quits
    assert app.done and app.state.match is None
    assert leave(app, capsys, tmp_path) == [f"termpool: record saved to {rec} (1 shot)"]
    assert replays(rec, capsys) == "1 shot: all identical"


def test_a_new_game_after_a_win_keeps_both_matches(capsys, tmp_path) -> None:
    from termpool.ui.keys import Key

    app = session(tmp_path)
    t = win(app, 0.0)
    app.key(Key("n"), t)
    from termpool.ui.headless import play as play_keys
    from termpool.ui.keys import parse_script

    play_keys(app, parse_script("enter space-hold 1.0 wait 20 q y"), 100, 32)
    first, second = tmp_path / "m.json", tmp_path / "m-2.json"
    assert leave(app, capsys, tmp_path) == [f"termpool: record saved to {first} (1 shot)",
                                            f"termpool: record saved to {second} (1 shot)"]
    assert json.loads(first.read_text())["shots"][0]["outcome"]["winner"] == 0
    assert replays(second, capsys) == "1 shot: all identical"


def test_a_new_game_left_without_a_shot_keeps_the_match_won(capsys, tmp_path) -> None:
    from termpool.ui.keys import Key

    app = session(tmp_path)
    t = win(app, 0.0)
    app.key(Key("n"), t)
    app.key(Key("q"), t + 1)
    app.key(Key("y"), t + 2)
    assert app.done
    rec = tmp_path / "m.json"
    assert leave(app, capsys, tmp_path) == [f"termpool: record saved to {rec} (1 shot)"]
    assert replays(rec, capsys) == "1 shot: all identical"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.json"]


def test_q_on_the_game_over_box_keeps_the_match(capsys, tmp_path) -> None:
    from termpool.ui.keys import Key

    app = session(tmp_path)
    t = win(app, 0.0)
    app.key(Key("q"), t)
    assert app.done
    rec = tmp_path / "m.json"
    assert leave(app, capsys, tmp_path) == [f"termpool: record saved to {rec} (1 shot)"]
    assert replays(rec, capsys) == "1 shot: all identical"


def test_a_later_match_never_replaces_a_file_without_force(capsys, tmp_path,
                                                           monkeypatch) -> None:
    from termpool.ui.keys import Key

    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    (tmp_path / "m-2.json").write_text("an earlier match")
    app = session(tmp_path)
    t = win(app, 0.0)
    app.key(Key("n"), t)
    t = win(app, t)
    app.key(Key("q"), t)
    capsys.readouterr()
    import argparse

    from termpool.ui.play import _leave

    assert _leave(app, argparse.Namespace(record=str(tmp_path / "m.json"), force=False)) == 1
    err = capsys.readouterr().err.splitlines()
    (spare,) = (tmp_path / "data" / "termpool").glob("record-*")
    assert err == [f"termpool: record saved to {tmp_path / 'm.json'} (1 shot)",
                   f"termpool: cannot write the record to '{tmp_path / 'm-2.json'}' (exists "
                   f"(pass --force to replace it)); it was saved to {spare} (1 shot)"]
    assert (tmp_path / "m-2.json").read_text() == "an earlier match"
    assert replays(spare, capsys) == "1 shot: all identical"


def test_a_signal_after_two_matches_keeps_both(capsys, tmp_path, monkeypatch) -> None:
    from termpool.ui.phases import answer, turn

    new_match, tick = turn.new_match, App.tick
    ended = []

    def comes_down_to_the_9(s, mode, opponent):
        return nine_alone_in(new_match(s, mode, opponent))

    def term_after_two_wins(self, t):
        tick(self, t)
        if self.state.phase is Phase.OVER and self.state.match not in ended:
            ended.append(self.state.match)
            if len(ended) == 2:
                os.kill(os.getpid(), signal.SIGTERM)

    monkeypatch.setattr(turn, "new_match", comes_down_to_the_9)  # the first match's
    monkeypatch.setattr(answer, "new_match", comes_down_to_the_9)  # N on the game-over box
    monkeypatch.setattr(App, "tick", term_after_two_wins)
    rec = tmp_path / "m.json"
    script = "down*4 space-hold 0.5 wait 20 n down*4 space-hold 0.5 wait 20 wait 20"
    rc = cli.main(["play", "--headless", "--mode", "9ball", "--opponent", "human", "--keys",
                   keys(tmp_path, script), "--record", str(rec)])
    err = capsys.readouterr().err
    monkeypatch.undo()
    assert rc == 128 + signal.SIGTERM and len(ended) == 2
    assert err == (f"termpool: record saved to {rec} (1 shot)\n"
                   f"termpool: record saved to {tmp_path / 'm-2.json'} (1 shot)\n")
    assert replays(rec, capsys) == "1 shot: all identical"
    assert replays(tmp_path / "m-2.json", capsys) == "1 shot: all identical"


def test_m_in_the_quit_question_goes_to_the_menu_and_keeps_the_match(capsys,
                                                                       tmp_path) -> None:
    from termpool.ui.app import Options
    from termpool.ui.headless import play as play_keys
    from termpool.ui.headless import screen_text
    from termpool.ui.keys import Key, parse_script
    from termpool.ui.records import Records

    app = App(Options(mode="practice", opponent="human", colors="mono", seed=0),
              records=Records(str(tmp_path / "m.json")))
    play_keys(app, parse_script("enter space-hold 1.0 wait 20 q"), 80, 24)
    assert "M: menu" in screen_text(app.cells(80, 24)[0])
    app.key(Key("m"), 100.0)
    assert app.state.phase is Phase.MENU and app.state.match is None and not app.done
    rec = tmp_path / "m.json"
    assert replays(rec, capsys) == "1 shot: all identical"  # saved on the way to the menu
    app.key(Key("q"), 101.0)
    assert app.done
    assert leave(app, capsys, tmp_path) == [f"termpool: record saved to {rec} (1 shot)"]


def test_record_to_stdout_is_json_lines_a_replay_reads_line_by_line(capsys, tmp_path) -> None:
    two = "enter space-hold 1.0 wait 1 q m down*4 enter enter space-hold 0.5 wait 1"
    rc = cli.main([*PLAY, "--keys", keys(tmp_path, two), "--record", "-"])
    out, err = capsys.readouterr()
    assert rc == 0 and err.count("\n") == 32  # the final screen
    lines = out.splitlines()
    matches = [json.loads(x) for x in lines]  # each line one whole JSON object, nothing else
    assert len(matches) == 2 and all(len(m["shots"]) == 1 for m in matches)
    assert matches[0]["shots"][0]["shot"] != matches[1]["shots"][0]["shot"]
    for line in lines:  # `termpool replay -` reads a line of it from stdin
        p = subprocess.run([sys.executable, "-m", "termpool", "replay", "-"], input=line + "\n",
                           capture_output=True, text=True, timeout=120)
        assert p.returncode == 0, p.stderr
        assert "all identical" in p.stdout
    # ... and the whole stream replays, match by match
    p = subprocess.run([sys.executable, "-m", "termpool", "replay", "-"], input=out,
                       capture_output=True, text=True, timeout=120)
    said = p.stdout.splitlines()
    assert p.returncode == 0, p.stderr
    assert said[0] == "match 1 of 2 (practice):" and "match 2 of 2 (practice):" in said
    assert said[-1] == "2 matches, 2 shots: all identical"
    p = subprocess.run([sys.executable, "-m", "termpool", "replay", "-", "--json"], input=out,
                       capture_output=True, text=True, timeout=120)
    assert [m["identical"] for m in json.loads(p.stdout)["matches"]] == [True, True]
    # One that differs is found, in its match, and the status says so.
    bad = json.loads(lines[1])
    bad["shots"][0]["final"][0]["x"] += 1e-9
    p = subprocess.run([sys.executable, "-m", "termpool", "replay", "-"],
                       input=lines[0] + "\n" + json.dumps(bad) + "\n",
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 1 and p.stdout.splitlines()[-1] == "2 matches, 2 shots: 1 differ"
    # Watching shows one match: a stream of two is refused in one line.
    f = tmp_path / "two.jsonl"
    f.write_text(out)
    assert cli.main(["replay", str(f), "--watch", "--headless", "--keys",
                     keys(tmp_path, "q")]) == 2
    assert capsys.readouterr().err == (f"termpool: replay: {f}: holds 2 matches (JSON Lines); "
                                       "give one, e.g. the second with `sed -n 2p`\n")
