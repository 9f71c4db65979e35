"""The files termpool reads and writes: bounded reads, guarded JSON, atomic writes.

Every file the game reads goes through `read_text` (a size limit, so `/dev/zero` is refused
instead of filling memory; UTF-8 with or without a byte order mark) and every JSON file through
`parse_json` (integers of at most `MAX_INT_DIGITS` digits, nesting at most `MAX_DEPTH` deep, no
NaN or Infinity). A gzip-compressed file is read through, to the same limit on its text (kept
matches are written so: a record's many 17-digit floats shrink about sixfold). All JSON it
writes is made by `to_json`, which refuses NaN and Infinity.
Every file it writes goes through `write_atomic`: a temporary file in the same directory,
flushed to disk, then renamed over the target, so a kill or a full disk never leaves a partial
file. Errors are `FileError`s with one line naming the file.
"""

from __future__ import annotations

import json
import os
import re
import stat
import sys
import tempfile
import time
import zlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

MiB = 1 << 20
MAX_SCENE_BYTES = 16 * MiB
MAX_REPLAY_BYTES = 128 * MiB  # a break's record is about 100 kB, a later shot about 10 kB
MAX_SCRIPT_BYTES = 1 * MiB  # headless key scripts
MAX_CONFIG_BYTES = 64 * 1024  # keys.conf
MAX_INT_DIGITS = 100  # the largest integer a file holds is a 39-digit generator state
MAX_DEPTH = 64  # the deepest file termpool writes nests 8 levels


class FileError(ValueError):
    """A file that cannot be read, parsed or written; the message is one line. `unreadable`:
    it could not be opened or read (`missing`: it does not exist)."""

    unreadable = False
    missing = False


def _size(n: int) -> str:
    return f"{n // MiB} MiB" if n >= MiB else f"{n // 1024} KiB"


def read_text(path: str | os.PathLike, limit: int, what: str = "file") -> str:
    """The text of a file ("-": standard input), at most `limit` bytes of UTF-8 (a leading
    byte order mark is dropped). Raises FileError naming the file and `what` it is for."""
    name = "stdin" if os.fspath(path) == "-" else os.fspath(path)
    too_big = f"{name}: larger than {_size(limit)}, the limit for a {what}"
    try:
        if os.fspath(path) == "-":
            data = sys.stdin.buffer.read(limit + 1)
        else:
            with open(path, "rb") as f:
                st = os.fstat(f.fileno())
                if stat.S_ISREG(st.st_mode) and st.st_size > limit:
                    raise FileError(too_big)
                data = f.read(limit + 1)
    except OSError as e:
        err = FileError(f"cannot read {what} '{name}': {e.strerror or e}")
        err.unreadable, err.missing = True, isinstance(e, FileNotFoundError)
        raise err from None
    if data[:2] == GZIP_MAGIC:
        data = _gunzip(data, limit, name)
    if len(data) > limit:
        raise FileError(too_big)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        # A name ending .gz promises gzip: say that it is not, before what else it is not.
        gz = " (nor gzip, though its name ends in .gz)" if name.endswith(".gz") else ""
        raise FileError(f"{name}: not UTF-8 text{gz}") from None


GZIP_MAGIC = b"\x1f\x8b"


def _gunzip(data: bytes, limit: int, name: str) -> bytes:
    """The text of gzip `data`, stopping one byte past `limit` (a small file may unpack to
    any size: the limit holds for what it unpacks to, and the caller refuses the excess)."""
    z = zlib.decompressobj(wbits=31)
    try:
        out = z.decompress(data, limit + 1)
    except zlib.error as e:
        raise FileError(f"{name}: a damaged gzip file ({e})") from None
    if len(out) <= limit and not z.eof:
        raise FileError(f"{name}: a damaged gzip file (it ends too soon)")
    return out


def gzipped(text: str) -> bytes:
    """`text` as a gzip file's bytes; the same text gives the same bytes (no time stamp)."""
    import gzip

    return gzip.compress(text.encode("utf-8"), compresslevel=6, mtime=0)


def _int(text: str) -> int:
    if len(text.lstrip("-")) > MAX_INT_DIGITS:
        raise FileError(f"an integer with more than {MAX_INT_DIGITS} digits")
    return int(text)


def _constant(name: str) -> float:
    raise FileError(f"{name} is not JSON (a number must be finite)")


def depth(obj: Any) -> int:
    """How deep lists and objects nest in a parsed JSON value (a scalar is 0)."""
    deepest = 0
    stack = [(obj, 1)] if isinstance(obj, (dict, list)) else []
    while stack:
        node, d = stack.pop()
        deepest = max(deepest, d)
        if deepest > MAX_DEPTH:
            break  # deep enough to refuse: no need to walk the rest
        for v in node.values() if isinstance(node, dict) else node:
            if isinstance(v, (dict, list)):
                stack.append((v, d + 1))
    return deepest


def parse_json(text: str, where: str,
               pairs_hook: Callable[[list[tuple[str, Any]]], Any] | None = None) -> Any:
    """Parse JSON text, refusing what no termpool file holds: integers longer than
    MAX_INT_DIGITS digits and nesting deeper than MAX_DEPTH. Raises FileError."""
    if not text.strip():  # (json's own words for it point at line 1 column 1)
        raise FileError(f"{where}: empty, where JSON was expected")
    try:
        data = json.loads(text, parse_int=_int, parse_constant=_constant,
                          object_pairs_hook=pairs_hook)
    except json.JSONDecodeError as e:
        raise FileError(f"{where}: invalid JSON at line {e.lineno} column {e.colno}: "
                        f"{e.msg}") from None
    except RecursionError:
        data = None
        too_deep = True
    except ValueError as e:  # from _int or the hook
        raise FileError(f"{where}: invalid JSON: {e}") from None
    else:
        too_deep = depth(data) > MAX_DEPTH
    if too_deep:
        raise FileError(f"{where}: invalid JSON: nested more than {MAX_DEPTH} levels deep")
    return data


# -------------------------------------------------------------------------------- writing


def _nonfinite(value: Any, path: str = "") -> tuple[str, float] | None:
    """The place and value of the first NaN or infinity in a JSON-able value, if any."""
    if isinstance(value, float) and not (value == value and abs(value) != float("inf")):
        return path or "the value", value
    if isinstance(value, dict):
        items = ((f"{path}.{k}" if path else str(k), v) for k, v in value.items())
    elif isinstance(value, (list, tuple)):
        items = ((f"{path}[{k}]", v) for k, v in enumerate(value))
    else:
        return None
    for where, v in items:
        found = _nonfinite(v, where)
        if found:
            return found
    return None


def to_json(value: Any, where: str = "", **options: Any) -> str:
    """JSON text of `value` (with json.dumps's options) for every file and output termpool
    writes. NaN and the infinities are refused (json.dumps would write bare NaN and Infinity,
    which are not JSON): ValueError naming the first one's place, e.g. `balls[0].x is nan`
    (`where`: the place of `value` itself, when it is part of something larger)."""
    try:
        return json.dumps(value, allow_nan=False, **options)
    except ValueError:
        found = _nonfinite(value, where)
        if found is None:
            raise
        raise ValueError(f"{found[0]} is {found[1]!r}, not a finite number (JSON has no "
                         "NaN or Infinity)") from None


def json_safe(value: Any) -> Any:
    """`value` with NaN and the infinities as strings ("nan", "inf"), for reports whose
    figures may be undefined (benchmarks): strict JSON through to_json."""
    if isinstance(value, float):
        return value if value == value and abs(value) != float("inf") else str(value)
    if isinstance(value, dict):
        return {k: json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    return value


def write_problem(path: str | os.PathLike, force: bool = False) -> str | None:
    """Why `path` cannot be written (None: it can), checked by creating and removing a
    temporary file beside it. An existing file is refused unless `force`; anything but a
    regular file (a directory, a device) always is."""
    p = Path(path)
    try:
        try:
            mode = os.stat(p).st_mode
        except FileNotFoundError:
            mode = None
        if mode is not None and stat.S_ISDIR(mode):
            return "is a directory"
        if mode is not None and not stat.S_ISREG(mode):
            return "exists and is not a regular file"
        if mode is not None and not force:
            return "exists (pass --force to replace it)"
        try:
            os.stat(p.parent)
        except FileNotFoundError:
            return f"no such directory '{p.parent}'"
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent)
        os.close(fd)
        os.unlink(tmp)
    except NotADirectoryError:
        return f"'{p.parent}' is not a directory"
    except OSError as e:
        return e.strerror or str(e)
    return None


def _mode(path: Path) -> int:
    try:
        return stat.S_IMODE(os.stat(path).st_mode)  # replacing a file keeps its permissions
    except OSError:
        mask = os.umask(0)
        os.umask(mask)
        return 0o666 & ~mask


def write_atomic(path: str | os.PathLike, data: str | bytes) -> None:
    """Write `data` (text as UTF-8, or bytes) to `path` through a temporary file beside it,
    flushed to disk and then renamed over the target: readers see the old file or the whole
    new one, never a part. Raises OSError (the temporary file is removed)."""
    p = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode("utf-8") if isinstance(data, str) else data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, _mode(p))
        os.replace(tmp, p)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


RECORDS = "records"  # the data directory's folder of kept matches
KEEP_RECORDS = 100  # kept matches: the oldest beyond this many are removed


def data_dir(env: dict | None = None) -> Path:
    """Where termpool keeps files of its own: $XDG_DATA_HOME/termpool, else
    ~/.local/share/termpool."""
    env = os.environ if env is None else env
    base = env.get("XDG_DATA_HOME") or str(Path(env.get("HOME", "~")).expanduser()
                                           / ".local" / "share")
    return Path(base) / "termpool"


def records_dir(env: dict | None = None) -> Path:
    """Where every match is kept (unless turned off): `records/` in the data directory."""
    return data_dir(env) / RECORDS


# A kept match's name in the records folder: the date and time, a number when two started in
# the same second, the mode. Only files so named are ever removed.
KEPT_NAME = re.compile(r"\d{8}-\d{6}(-\d+)?-[a-z0-9]+\.json(\.gz)?")
KEPT_SUFFIX = ".json.gz"  # how they are written now (older ones, plain .json, still count)


def kept_records(folder: str | os.PathLike) -> list[Path]:
    """The matches kept in `folder`, oldest first (by when each was last written)."""
    try:
        entries = [e for e in os.scandir(folder) if KEPT_NAME.fullmatch(e.name)]
        dated = [(e.stat().st_mtime, e.name, Path(e.path)) for e in entries if e.is_file()]
    except OSError:
        return []
    return [p for _, _, p in sorted(dated)]


def write_fallback(text: str, stem: str, env: dict | None = None) -> Path:
    """Write `text` to a new file in the data directory (created if needed), named from
    `stem`, the time and the process id; returns its path. Raises OSError."""
    d = data_dir(env)
    d.mkdir(parents=True, exist_ok=True)
    path = d / f"{stem}-{time.strftime('%Y%m%d-%H%M%S')}-{os.getpid()}.json"
    write_atomic(path, text)
    return path
