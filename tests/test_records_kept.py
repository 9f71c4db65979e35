"""Every match is kept by default, in the data directory's records/: written after every shot,
atomically, on every way out (the end, Q, a signal, a crash), replayable, listed by `termpool
records`, bounded to the newest KEEP_RECORDS, and turned off by the setting or --no-record.
(--record FILE, which sends them elsewhere, is in test_record_file.py.)"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from termpool import cli, files
from termpool.ui.app import App, Options
from termpool.ui.headless import play as play_keys
from termpool.ui.headless import screen_text
from termpool.ui.keys import parse_script
from termpool.ui.records import Records

ROOT = Path(__file__).resolve().parent.parent
PLAY = ("play", "--headless", "--mode", "practice")
ONE_SHOT = "enter space-hold 1.0 wait 20"


def keys(tmp_path: Path, script: str) -> str:
    p = tmp_path / "keys.txt"
    p.write_text(script)
    return str(p)


def kept() -> list[Path]:
    return files.kept_records(files.records_dir())


def shots(rec: Path) -> int:
    """The number of shot records in a kept match (read as the game reads it, gzip or not)."""
    return len(json.loads(files.read_text(rec, files.MAX_REPLAY_BYTES))["shots"])


def replays(path: Path, capsys) -> str:
    """The last line of `termpool replay` on the file (which must replay identically)."""
    capsys.readouterr()
    assert cli.main(["replay", str(path)]) == 0
    return capsys.readouterr().out.splitlines()[-1]


def test_a_match_played_without_record_is_kept_and_replays(capsys, tmp_path) -> None:
    rc = cli.main([*PLAY, "--keys", keys(tmp_path, ONE_SHOT + " q y")])
    err = capsys.readouterr().err
    (rec,) = kept()
    assert rc == 0 and rec.parent == files.data_dir() / "records"
    assert rec.name.endswith("-practice.json.gz")
    assert err == f"termpool: record saved to {rec} (1 shot)\n"
    assert replays(rec, capsys) == "1 shot: all identical"
    assert shots(rec) == 1
    assert rec.read_bytes()[:2] == files.GZIP_MAGIC


def test_a_match_from_the_menu_is_kept(capsys, tmp_path) -> None:
    # The menu's Practice (5), one shot, Q and Y: no flag at all.
    rc = cli.main(["play", "--headless", "--keys", keys(tmp_path, "5 " + ONE_SHOT + " q y")])
    (rec,) = kept()
    assert rc == 0 and f"record saved to {rec} (1 shot)" in capsys.readouterr().err
    assert replays(rec, capsys) == "1 shot: all identical"


@pytest.mark.parametrize("off", [["--no-record"], ["--no-records"]])
def test_no_record_keeps_nothing(capsys, tmp_path, off) -> None:
    rc = cli.main([*PLAY, *off, "--keys", keys(tmp_path, ONE_SHOT + " q y")])
    assert rc == 0 and kept() == [] and capsys.readouterr().err == ""


def test_the_setting_off_keeps_nothing(capsys, tmp_path) -> None:
    from termpool.ui.settings import settings_path

    conf = settings_path()
    conf.parent.mkdir(parents=True)
    conf.write_text("records = off\n")
    assert cli.main([*PLAY, "--keys", keys(tmp_path, ONE_SHOT + " q y")]) == 0
    assert kept() == []
    # ... and the flag turns it back on for one run
    assert cli.main([*PLAY, "--records", "--keys", keys(tmp_path, ONE_SHOT + " q y")]) == 0
    assert len(kept()) == 1


def test_each_shot_is_on_disk_before_the_game_is_left(capsys, tmp_path) -> None:
    folder = tmp_path / "records"
    app = App(Options(mode="practice", colors="mono", seed=3), records=Records(None,
                                                                               folder=folder))
    play_keys(app, parse_script(ONE_SHOT), 100, 32)
    (rec,) = files.kept_records(folder)
    assert shots(rec) == 1  # not left yet: written at the shot
    play_keys(app, parse_script("space-hold 0.6 wait 20"), 100, 32)
    assert shots(rec) == 2  # the same file, rewritten
    assert files.kept_records(folder) == [rec]
    assert replays(rec, capsys) == "2 shots: all identical"


def test_a_shot_played_again_after_a_take_back_is_the_one_kept(capsys, tmp_path) -> None:
    """Practice: U, then another shot, leaves as many shots as before; the file must hold the
    new shot, not the one taken back (and the same again with the game left at once)."""
    folder = tmp_path / "records"
    app = App(Options(mode="practice", colors="mono", seed=3), records=Records(None,
                                                                               folder=folder))
    play_keys(app, parse_script(ONE_SHOT + " space-hold 0.6 wait 20"), 100, 32)
    (rec,) = files.kept_records(folder)
    taken_back = json.loads(files.read_text(rec, files.MAX_REPLAY_BYTES))["shots"][1]
    play_keys(app, parse_script("u wait 1 right*9 space-hold 0.3 wait 20"), 100, 32)
    shots_now = json.loads(files.read_text(rec, files.MAX_REPLAY_BYTES))["shots"]
    assert len(shots_now) == 2 and shots_now[1]["shot"] != taken_back["shot"]
    assert shots_now[1]["shot"] == app.state.match.history[1]["shot"]
    assert replays(rec, capsys) == "2 shots: all identical"


def test_a_failed_write_leaves_the_last_whole_record_and_no_temporary_file(
        capsys, tmp_path, monkeypatch) -> None:
    folder = tmp_path / "records"
    app = App(Options(mode="practice", colors="mono", seed=3), records=Records(None,
                                                                               folder=folder))
    play_keys(app, parse_script(ONE_SHOT), 100, 32)
    (rec,) = files.kept_records(folder)
    before = rec.read_bytes()

    def disk_full(fd):  # the new text is written but cannot reach the disk
        raise OSError(28, "No space left on device")

    fsync = os.fsync
    monkeypatch.setattr(os, "fsync", disk_full)
    play_keys(app, parse_script("space-hold 0.6 wait 20"), 100, 32)
    monkeypatch.setattr(os, "fsync", fsync)
    assert rec.read_bytes() == before  # the one-shot record, whole
    assert sorted(p.name for p in folder.iterdir()) == [rec.name]
    assert replays(rec, capsys) == "1 shot: all identical"


def test_the_newest_are_kept_and_only_records_are_removed(capsys, tmp_path) -> None:
    folder = files.records_dir()
    folder.mkdir(parents=True)
    now = time.time()
    for k in range(files.KEEP_RECORDS + 3):  # older matches, the first the oldest; the even
        # ones plain JSON, as they were written before kept matches were compressed
        p = folder / f"20200101-{k:06d}-8ball.json{'.gz' if k % 2 else ''}"
        p.write_text("{}")
        os.utime(p, (now - 1000 + k, now - 1000 + k))
    (folder / "notes.txt").write_text("mine")
    assert cli.main([*PLAY, "--keys", keys(tmp_path, ONE_SHOT + " q y")]) == 0
    left = kept()
    assert len(left) == files.KEEP_RECORDS
    assert left[-1].name.endswith("-practice.json.gz")  # this match, the newest
    assert left[0].name == "20200101-000004-8ball.json"  # the four oldest went
    assert (folder / "notes.txt").read_text() == "mine"


def test_two_matches_in_a_session_are_two_files(capsys, tmp_path) -> None:
    # Practice, one shot, to the menu (Q, M), practice again, one shot, quit.
    script = f"5 {ONE_SHOT} q m 5 {ONE_SHOT} q y"
    assert cli.main(["play", "--headless", "--keys", keys(tmp_path, script)]) == 0
    a, b = kept()
    assert a != b
    err = capsys.readouterr().err
    assert f"record saved to {a} (1 shot)" in err and f"record saved to {b} (1 shot)" in err


def test_a_crash_keeps_the_match(capsys, tmp_path, monkeypatch) -> None:
    tick = App.tick

    def crash_after_the_first_shot(self, t):
        if self.state.match.history:
            raise RuntimeError("boom")
        tick(self, t)

    monkeypatch.setattr(App, "tick", crash_after_the_first_shot)
    with pytest.raises(RuntimeError, match="boom"):
        cli.main([*PLAY, "--keys", keys(tmp_path, "enter space-hold 1.0 wait 20 x")])
    monkeypatch.setattr(App, "tick", tick)  # (not undo: that would drop the data directory)
    (rec,) = kept()
    assert f"record saved to {rec} (1 shot)" in capsys.readouterr().err
    assert replays(rec, capsys) == "1 shot: all identical"


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143),
                                       (signal.SIGHUP, 129)])
def test_a_signal_keeps_the_match(capsys, tmp_path, sig, code) -> None:
    script = "enter " + " ".join(f"left*3 space-hold {0.3 + k % 5 * 0.1:.1f} wait 15"
                                 for k in range(40))  # many shots: seconds of work
    env = dict(os.environ, PYTHONPATH=str(ROOT))  # the test's own data directory
    p = subprocess.Popen([sys.executable, "-m", "termpool", *PLAY, "--keys",
                          keys(tmp_path, script)], cwd=ROOT, env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(3.0)  # well into the game (started, not finished: that takes far longer)
    p.send_signal(sig)
    out, err = p.communicate(timeout=120)
    assert p.returncode == code, err
    (rec,) = kept()
    assert "Traceback" not in err and err.startswith(f"termpool: record saved to {rec} (")
    assert replays(rec, capsys).endswith(": all identical")


def test_the_game_over_box_says_where_the_match_is_kept(tmp_path) -> None:
    import test_record_file as R

    folder = tmp_path / "records"
    app = App(Options(mode="9ball", opponent="human", colors="mono", seed=0),
              records=Records(None, folder=folder))
    R.win(app, 0.0)
    (rec,) = files.kept_records(folder)
    assert f"kept as records/{rec.name}" in screen_text(app.cells(100, 32)[0])


def test_termpool_records_lists_them_newest_first(capsys, tmp_path) -> None:
    assert cli.main(["records"]) == 0
    assert capsys.readouterr().out == f"no match is kept in {files.records_dir()} yet\n"
    for _ in range(2):
        assert cli.main([*PLAY, "--keys", keys(tmp_path, ONE_SHOT + " q y")]) == 0
    old, new = kept()
    capsys.readouterr()
    assert cli.main(["records"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == f"2 matches kept in {files.records_dir()} (newest first):"
    assert lines[1].endswith(str(new)) and lines[2].endswith(str(old))
    assert lines[1].split()[2] == "practice" and " You · 1 shot " in lines[1]
    assert lines[-1].startswith("watch one with: termpool replay")
    assert cli.main(["records", "--last", "1"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == 3


def test_an_unwritable_data_directory_costs_one_line_and_the_game_goes_on(
        capsys, tmp_path, monkeypatch) -> None:
    data = tmp_path / "data"
    data.write_text("not a directory")
    monkeypatch.setenv("XDG_DATA_HOME", str(data))
    rc = cli.main([*PLAY, "--keys",
                   keys(tmp_path, ONE_SHOT + " q y")])
    lines = [x for x in capsys.readouterr().err.splitlines() if "record" in x]
    assert rc == 0  # the player asked for nothing: a warning, not a failure
    assert len(lines) == 1 and lines[0].startswith("termpool: cannot write the record to ")
    assert lines[0].endswith("is not a directory): it is lost")


def test_a_later_write_that_fails_leaves_the_earlier_record_and_says_so(
        capsys, tmp_path, monkeypatch) -> None:
    folder = tmp_path / "records"
    records = Records(None, folder=folder)
    app = App(Options(mode="practice", colors="mono", seed=3), records=records)
    play_keys(app, parse_script(ONE_SHOT), 100, 32)
    (rec,) = files.kept_records(folder)
    write = files.write_atomic

    def disk_full(path, text):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(files, "write_atomic", disk_full)
    play_keys(app, parse_script("space-hold 0.6 wait 20"), 100, 32)
    monkeypatch.setattr(files, "write_atomic", write)
    lines, status = records.finish(app.state.match)
    assert status == 0
    assert lines == [f"cannot update the record '{rec}' (No space left on device); it was "
                     f"saved to {rec} (1 shot)"]
    assert replays(rec, capsys) == "1 shot: all identical"


def test_termpool_records_says_who_played_and_how_it_stands(capsys, tmp_path) -> None:
    from termpool.ui.phases.turn import log_match

    folder = files.records_dir()
    app = App(Options(mode="8ball", opponent="human", player1="Ann", player2="Bob",
                      colors="mono", seed=3), records=Records(None, folder=folder))
    play_keys(app, parse_script("enter space-hold 1.0 wait 20"), 100, 32)
    app.state.match.concede(1)  # Bob gives it up: Ann has won
    log_match(app.state)
    bad = folder / "20200101-000000-9ball.json.gz"
    bad.write_bytes(b"not gzip")
    os.utime(bad, (0, 0))  # the older
    assert cli.main(["records"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "Ann v Bob · Ann won 0-0" in lines[1]
    assert "(cannot be read)" in lines[2]


def test_termpool_records_lists_them_by_when_they_began(capsys, tmp_path) -> None:
    """A match begun first but written last (left open, finished later) is listed after
    the one begun since: the list shows when each began."""
    folder = files.records_dir()
    folder.mkdir(parents=True, exist_ok=True)
    names = ["20261208-010000-8ball.json", "20261208-020000-9ball.json",
             "20261208-020000-2-9ball.json", "20261208-020000-10-9ball.json"]
    written = [1050, 1001, 1002, 1003]  # the first begun, written last
    for name, t in zip(names, written, strict=True):
        (folder / name).write_text("{}")
        os.utime(folder / name, (t, t))
    assert cli.main(["records"]) == 0
    listed = [line.split()[-1] for line in capsys.readouterr().out.splitlines()[1:-1]]
    assert [os.path.basename(x) for x in listed] == [names[3], names[2], names[1], names[0]]
