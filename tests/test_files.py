"""Reading and writing files: size limits, guarded JSON, atomic writes, the data directory."""

from __future__ import annotations

import io
import json
import math
import os
import shutil
import stat
import sys
import tempfile
from pathlib import Path

import pytest
from unprivileged import as_nobody

from termpool import files
from termpool.files import FileError, parse_json, read_text, write_atomic, write_problem


def test_read_text_refuses_a_file_over_its_limit(tmp_path) -> None:
    p = tmp_path / "big.json"
    p.write_bytes(b" " * 1025)
    with pytest.raises(FileError, match=r"big.json: larger than 1 KiB, the limit for a scene$"):
        read_text(p, 1024, "scene")
    p.write_bytes(b" " * 1024)
    assert read_text(p, 1024) == " " * 1024


def test_read_text_stops_at_its_limit_on_an_endless_device() -> None:
    with pytest.raises(FileError, match="^/dev/zero: larger than 64 KiB"):
        read_text("/dev/zero", 64 * 1024)


def test_read_text_bounds_stdin_too(monkeypatch) -> None:
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(b"x" * 2000)))
    with pytest.raises(FileError, match="^stdin: larger than 1 KiB"):
        read_text("-", 1024)


def test_read_text_drops_a_byte_order_mark_and_refuses_other_encodings(tmp_path) -> None:
    p = tmp_path / "a.txt"
    p.write_bytes("\ufeffshoot = space".encode())
    assert read_text(p, 100) == "shoot = space"
    p.write_bytes(b"caf\xe9")
    with pytest.raises(FileError, match=r"a.txt: not UTF-8 text$"):
        read_text(p, 100)


def test_a_file_named_gz_that_is_not_gzip_says_so(tmp_path) -> None:
    p = tmp_path / "match.json.gz"
    p.write_bytes(b"\x00\xff\xfe not gzip")
    with pytest.raises(FileError, match=r"match.json.gz: not UTF-8 text \(nor gzip, though its "
                                        r"name ends in .gz\)$"):
        read_text(p, 100)
    p.write_text('{"a": 1}')  # plain text under a .gz name is still read
    assert read_text(p, 100) == '{"a": 1}'


@pytest.mark.parametrize("text", ["", "  \n\t"])
def test_empty_json_is_called_empty(text) -> None:
    with pytest.raises(FileError, match=r"^stdin: empty, where JSON was expected$"):
        parse_json(text, "stdin")


def test_read_text_reads_a_gzip_file_through(tmp_path) -> None:
    p = tmp_path / "x.json.gz"
    p.write_bytes(files.gzipped('{"a": "é"}'))
    assert files.read_text(p, 100) == '{"a": "é"}'
    assert files.gzipped("same") == files.gzipped("same")  # no time stamp: the same bytes


def test_read_text_holds_a_gzip_file_to_the_limit_of_its_text(tmp_path) -> None:
    p = tmp_path / "bomb.gz"
    p.write_bytes(files.gzipped(" " * 10_000_000))  # 10 MB of text in about 10 kB
    assert p.stat().st_size < 20_000
    with pytest.raises(FileError, match=r"bomb.gz: larger than 1 MiB, the limit for a replay"):
        files.read_text(p, 1 << 20, "replay")


def test_read_text_names_a_damaged_gzip_file(tmp_path) -> None:
    p = tmp_path / "cut.json.gz"
    p.write_bytes(files.gzipped('{"shots": []}' * 50)[:20])
    with pytest.raises(FileError, match=r"^\S*cut.json.gz: a damaged gzip file \(it ends too "
                       r"soon\)$"):
        files.read_text(p, 1000)
    p.write_bytes(files.GZIP_MAGIC + b"not deflate at all")
    with pytest.raises(FileError, match=r"^\S*cut.json.gz: a damaged gzip file \("):
        files.read_text(p, 1000)


def test_read_text_names_the_file_it_cannot_open(tmp_path) -> None:
    with pytest.raises(FileError, match=r"^cannot read replay '.*nope': No such file"):
        read_text(tmp_path / "nope", 100, "replay")
    with pytest.raises(FileError, match=r"^cannot read file '.*': Is a directory"):
        read_text(tmp_path, 100)


@pytest.mark.parametrize("digits", [files.MAX_INT_DIGITS + 1, 400, 5000, 100_000])
def test_parse_json_refuses_integers_with_too_many_digits(digits) -> None:
    for text in (f'{{"x": {"9" * digits}}}', f'[-{"1" * digits}]'):
        with pytest.raises(FileError, match=f"^f: invalid JSON: an integer with more than "
                                            f"{files.MAX_INT_DIGITS} digits$"):
            parse_json(text, "f")


def test_parse_json_keeps_integers_as_long_as_a_generator_state() -> None:
    state = 2 ** 128 - 1  # a PCG64 state and increment are 128-bit integers
    assert parse_json(f'{{"state": {state}, "small": -{"9" * files.MAX_INT_DIGITS}}}', "f") \
        == {"state": state, "small": -int("9" * files.MAX_INT_DIGITS)}


@pytest.mark.parametrize("levels", [files.MAX_DEPTH + 1, 497, 1000, 200_000])
def test_parse_json_refuses_deep_nesting(levels) -> None:
    for text in ("[" * levels + "]" * levels, '{"a":' * levels + "1" + "}" * levels):
        with pytest.raises(FileError, match=f"nested more than {files.MAX_DEPTH} levels"):
            parse_json(text, "f")


def test_parse_json_accepts_nesting_up_to_the_limit() -> None:
    n = files.MAX_DEPTH
    assert files.depth(parse_json("[" * n + "]" * n, "f")) == n
    assert files.depth(parse_json('{"a": [1, {"b": []}], "c": "[[[[["}', "f")) == 4
    assert files.depth(7) == 0


@pytest.mark.parametrize("token", ["NaN", "Infinity", "-Infinity"])
def test_parse_json_refuses_nan_and_infinity(token) -> None:
    with pytest.raises(FileError, match=f"^f: invalid JSON: {token} is not JSON"):
        parse_json(f'{{"balls": [{{"x": {token}}}]}}', "f")


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_to_json_refuses_what_json_cannot_hold_and_names_its_place(bad) -> None:
    value = {"time": 1.0, "balls": [{"x": 0.5, "w": [0.0, 1.0]}, {"x": 0.5, "w": [0.0, bad]}]}
    with pytest.raises(ValueError, match=rf"^balls\[1\]\.w\[1\] is {bad!r}, not a finite"):
        files.to_json(value)
    assert files.to_json({"x": [1.5, -0.0]}, indent=1) == json.dumps({"x": [1.5, -0.0]},
                                                                      indent=1)
    safe = files.json_safe(value)  # for reports: the undefined figure as text
    assert safe["balls"][1]["w"][1] == str(bad) and json.loads(files.to_json(safe))


def test_write_atomic_writes_and_replaces_keeping_the_mode(tmp_path) -> None:
    p = tmp_path / "rec.json"
    write_atomic(p, "one")
    assert p.read_text() == "one"
    os.chmod(p, 0o640)
    write_atomic(p, "two")
    assert p.read_text() == "two"
    assert stat.S_IMODE(p.stat().st_mode) == 0o640
    assert sorted(os.listdir(tmp_path)) == ["rec.json"]  # no temporary file left
    write_atomic(p, b"\x89PNG\x00\xff")  # bytes as they are
    assert p.read_bytes() == b"\x89PNG\x00\xff"


def test_write_atomic_leaves_the_old_file_whole_when_the_write_fails(tmp_path,
                                                                      monkeypatch) -> None:
    p = tmp_path / "rec.json"
    p.write_text("the old record")

    def full_disk(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", full_disk)
    with pytest.raises(OSError, match="No space left"):
        write_atomic(p, "x" * 10_000)
    assert p.read_text() == "the old record"
    assert os.listdir(tmp_path) == ["rec.json"]


def test_write_problem_names_what_is_wrong(tmp_path) -> None:
    assert write_problem(tmp_path / "new.json") is None
    assert write_problem(tmp_path) == "is a directory"
    assert write_problem(tmp_path / "no" / "x.json") == f"no such directory '{tmp_path / 'no'}'"
    (tmp_path / "f").write_text("")
    assert write_problem(tmp_path / "f" / "x.json") == f"'{tmp_path / 'f'}' is not a directory"
    assert write_problem(tmp_path / "f") == "exists (pass --force to replace it)"
    assert write_problem(tmp_path / "f", force=True) is None
    # A device is never replaced, not even with --force (root could rename over /dev/null).
    assert write_problem("/dev/null", force=True) == "exists and is not a regular file"
    assert write_problem("/proc/x.json") is not None  # nobody creates files there
    assert os.listdir(tmp_path) == ["f"]


def test_write_problem_without_permission() -> None:
    d = Path(tempfile.mkdtemp(dir="/tmp"))  # reachable by anyone
    sub = d / "sub"
    sub.mkdir()
    try:
        sub.chmod(0o000)  # not even to be entered
        d.chmod(0o555)  # read-only
        assert as_nobody(lambda: write_problem(d / "x.json")) == repr("Permission denied")
        assert as_nobody(lambda: write_problem(sub / "x.json")) == repr("Permission denied")
    finally:
        d.chmod(0o700)
        sub.chmod(0o700)
        shutil.rmtree(d)


def test_write_fallback_goes_to_the_data_directory(tmp_path) -> None:
    env = {"XDG_DATA_HOME": str(tmp_path / "data")}
    p = files.write_fallback("{}", "record", env)
    assert p.parent == tmp_path / "data" / "termpool" and p.name.startswith("record-")
    assert p.read_text() == "{}"
    assert files.data_dir({"HOME": "/home/x"}) == Path("/home/x/.local/share/termpool")
