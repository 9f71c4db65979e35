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


def test_a_crash_in_the_game_still_saves_the_record(capsys, tmp_path, monkeypatch) -> None:
    rec = tmp_path / "x.json"
    tick = App.tick

    def crash_after_the_first_shot(self, t):
        if self.match.history:
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


def test_record_to_stdout_follows_the_screen(capsys, tmp_path) -> None:
    rc = cli.main([*PLAY, "--keys", keys(tmp_path, "enter space-hold 1.0 wait 1"), "--record",
                   "-"])
    out, err = capsys.readouterr()
    assert rc == 0 and err == ""
    saved = json.loads(out[out.index("\n{") + 1:])
    assert len(saved["shots"]) == 1


def test_leaving_from_the_menu_says_there_is_nothing_to_save(capsys, tmp_path) -> None:
    rec = tmp_path / "x.json"
    rc = cli.main(["play", "--headless", "--keys", keys(tmp_path, "q"), "--record", str(rec)])
    assert rc == 0 and not rec.exists()
    assert capsys.readouterr().err == "termpool: no match was played, so there is no record " \
                                      "to save\n"
