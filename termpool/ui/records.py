"""Every match played is kept, each in a file of its own: by default in the data directory's
`records/` (`files.records_dir`), or where `--record FILE` says.

By default a match goes to `records/<date>-<time>-<mode>.json.gz` (the time it was first
written; gzip, as every FILE whose name ends in .gz); the newest `files.KEEP_RECORDS` such
files are kept and older ones removed. The setting `records` (`--no-record`) turns this off.
With `--record FILE` the first match with a shot goes to FILE, the second to FILE-2 (`m.json`
-> `m-2.json`), the third to FILE-3, and so on, and nothing goes to `records/`. A match is
written after every shot, when it ends or is left (a new game, the menu) and once more on the
way out if it changed, atomically each time, so a session killed later still has it. A --record
file that was there before play is replaced only with --force (the first one is checked before
play); a file this session wrote is its own to rewrite. A file that cannot be written sends its
match to the data directory instead (`files.write_fallback`).
Nothing is printed while the game holds the terminal: the lines saying where each match went
are kept for the end (`lines`). With FILE "-" the matches go to standard output at the end
as JSON Lines: each match one JSON object on a line of its own, in the order played (one line
is a replay file: `termpool replay -` reads it from stdin). A player back in an online match
after their connection dropped goes on in the file their dropped session kept (`adopt`).
"""

from __future__ import annotations

import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from termpool import files
from termpool.ui.term import signals_held


def slot_path(path: str, k: int) -> str:
    """Where the k-th match (from 1) of a session goes: FILE, then FILE-2, FILE-3 ...
    (`m.json` -> `m-2.json`, `m.json.gz` -> `m-2.json.gz`)."""
    if k == 1:
        return path
    p = Path(path)
    gz = p.suffix == ".gz" and p.stem != Path(p.stem).stem
    base = Path(p.stem) if gz else p
    return str(p.with_name(f"{base.stem}-{k}{base.suffix}{'.gz' if gz else ''}"))


@dataclass
class _Kept:
    match: object
    shots: int = 0  # as last written ...
    winner: int | None = None  # ... (a match given up changes no shot, only its winner)
    last: object = None  # ... its last shot (a take-back and a new shot keep the count)
    choices: int = 0  # ... and the options answered
    where: str | None = None  # the file it is in (None: lost)
    why: str | None = None  # why it is not in its own file
    target: str | None = None  # its own file in the records folder (chosen when first kept)
    floor: int = 0  # shots its file holds already (adopted): not written again with fewer


def _written(kept: _Kept) -> None:
    """Note the match as it was just written."""
    m = kept.match
    kept.shots, kept.winner, kept.choices = len(m.history), m.winner, len(m.choices)
    kept.last = m.history[-1] if m.history else None


def _as_written(kept: _Kept) -> bool:
    """The match is as it was last written: the same shots (the last one the very record
    written, not a shot played again after a take-back), winner and answers."""
    m = kept.match
    return ((kept.shots, kept.winner, kept.choices) == (len(m.history), m.winner, len(m.choices))
            and kept.last is (m.history[-1] if m.history else None))


class Records:
    def __init__(self, path: str | None, force: bool = False,
                 folder: str | os.PathLike | None = None,
                 most: int = files.KEEP_RECORDS) -> None:
        """`path`: --record FILE (it wins); else `folder`: every match in a file of its own
        there, the newest `most` kept; neither: nothing is kept."""
        self.path, self.force = path, force
        self.folder = None if path else folder
        self.most = most
        self._kept: list[_Kept] = []  # in the order the matches were first kept
        self._ours: set[str] = set()  # files this session wrote
        self._replaced: set[str] = set()  # ... of which were there before

    def keep(self, match, empty: bool = False, on: bool = True) -> None:
        """Save `match` (not one without shots unless `empty`; again only if it has more
        shots since). `on`: the setting that keeps matches in the records folder (--record
        FILE keeps them whatever it says)."""
        if match is None or match.running is not None:
            return
        if not (self.path or (self.folder is not None and on)):
            return
        if not (match.history or empty):
            return
        kept = next((x for x in self._kept if x.match is match), None)
        if kept is None:
            kept = _Kept(match)
            self._kept.append(kept)
        elif _as_written(kept) and kept.where is not None:
            return
        if len(match.history) < kept.floor:  # an adopted file is not cut short meanwhile
            return
        if self.path != "-":
            self._write(self._kept.index(kept) + 1, kept)
        else:
            _written(kept)

    def adopt(self, match, look: int = 20) -> None:
        """`match` is one this player's earlier session kept a part of (an online match they
        are back in after their connection dropped): of the newest `look` files in the
        records folder, the one of the same match (its settings, players and seed, which a
        challenge draws at random) is the file it goes on in, rather than a second one."""
        if self.folder is None or any(x.match is match for x in self._kept):
            return
        want = files.parse_json(files.to_json(match.to_json()["match"]), "match")
        for path in reversed(files.kept_records(self.folder)[-look:]):
            try:
                old = files.parse_json(files.read_text(path, files.MAX_REPLAY_BYTES,
                                                       "record"), str(path))
            except (OSError, files.FileError):
                continue
            if isinstance(old, dict) and old.get("match") == want:
                shots = old.get("shots")
                self._kept.append(_Kept(match, target=str(path),
                                        floor=len(shots) if isinstance(shots, list) else 0))
                self._ours.add(str(path))  # this player's own record of it, to go on
                return

    def kept_at(self, match) -> str | None:
        """The file `match` was last written to (None: not kept, or lost)."""
        kept = next((x for x in self._kept if x.match is match), None)
        return None if kept is None else kept.where

    def _name(self, kept: _Kept) -> str:
        """A new file in the records folder for `kept` (the folder is made if need be; if it
        cannot be, writing the file says why)."""
        try:
            os.makedirs(self.folder, exist_ok=True)
        except OSError:
            pass
        stamp = time.strftime("%Y%m%d-%H%M%S")
        mode = kept.match.mode
        n = 1
        while True:
            name = f"{stamp}{'' if n == 1 else f'-{n}'}-{mode}{files.KEPT_SUFFIX}"
            target = os.path.join(self.folder, name)
            if target not in self._ours and not os.path.lexists(target):
                return target
            n += 1

    def _prune(self) -> None:
        """Remove the oldest kept matches beyond the newest `most` (never this session's)."""
        old = files.kept_records(self.folder)
        for p in old[:max(0, len(old) - self.most)]:
            if str(p) not in self._ours:
                try:
                    p.unlink()
                except OSError:
                    pass

    def _write(self, k: int, kept: _Kept) -> None:
        if self.path:
            target = slot_path(self.path, k)
        else:
            if kept.target is None:
                kept.target = self._name(kept)
            target = kept.target
        fresh = target not in self._ours
        try:
            text = files.to_json(kept.match.to_json(), indent=1) + "\n"
            data = files.gzipped(text) if target.endswith(".gz") else text
        except ValueError as e:  # JSON has no NaN: no file could hold it
            kept.where, kept.why = None, f"cannot write the record: {e}"
            return
        with signals_held():
            ours = target in self._ours
            why = files.write_problem(target, force=self.force or ours)
            if why is None:
                try:
                    existed = os.path.exists(target) and not ours
                    files.write_atomic(target, data)
                    self._ours.add(target)
                    if existed:
                        self._replaced.add(target)
                    kept.where, kept.why = target, None
                    _written(kept)
                    if self.folder is not None and fresh:
                        self._prune()
                    return
                except OSError as e:
                    why = e.strerror or str(e)
            kept.why = f"cannot write the record to '{target}' ({why})"
            if self.folder is not None:  # the data directory is where it failed: no spare
                if kept.where is not None:  # its file keeps the match as it was
                    kept.why = f"cannot update the record '{target}' ({why})"
                return
            try:
                if kept.where in self._ours and kept.where != target:
                    files.write_atomic(kept.where, text)  # its spare from before
                else:
                    kept.where = str(files.write_fallback(text, "record"))
                    self._ours.add(kept.where)
                _written(kept)
            except OSError as e:
                kept.where = None
                kept.why += f" nor to the data directory ({e.strerror or e})"

    def finish(self, current=None) -> tuple[list[str], int]:
        """After play: the lines to say, one per match in order (with "-", standard output
        gets the matches themselves, a JSON line each), and the status: 0, or 1 if a match
        did not go where asked. A session whose only match (`current`) has no shot yet still
        saves it: its rack and settings are a record too."""
        if not self.path:
            return self._said(), 0  # the records folder's trouble is a warning, no more
        if not self._kept and current is not None:
            self.keep(current, empty=True)
        if not self._kept:
            return ["no match was played, so there is no record to save"], 0
        if self.path == "-":
            lines = []
            for x in self._kept:
                try:
                    sys.stdout.write(files.to_json(x.match.to_json()) + "\n")  # a line
                except ValueError as e:
                    lines.append(f"cannot write the record: {e}: it is lost")
            sys.stdout.flush()
            return lines, int(bool(lines))
        return self._said(), int(any(x.why for x in self._kept))

    def _said(self) -> list[str]:
        """One line per match kept: where it went, or why it did not."""
        lines = []
        for x in self._kept:
            what = f"{x.shots} {'shot' if x.shots == 1 else 'shots'}"
            if x.where is None:
                lines.append(f"{x.why}: it is lost")
            elif x.why:
                lines.append(f"{x.why}; it was saved to {x.where} ({what})")
            else:
                replaced = "; it replaced the file that was there" \
                    if x.where in self._replaced else ""
                lines.append(f"record saved to {x.where} ({what}{replaced})")
        return lines
