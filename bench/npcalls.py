"""How many times the engine calls into numpy per event, on one table, counted by valgrind.

numpy's per-call cost (half a microsecond and more) was once most of a break's time, so the
engine's one-table path works in plain floats where it can; this counts what is left. A
Python-level profiler sees neither ufuncs nor operators on arrays, so the count is taken at
numpy's own C entry points, under callgrind (valgrind), which counts every call exactly:

- ufunc calls, operators on arrays included (`ufunc_generic_vectorcall`);
- numpy functions (`dispatcher_vectorcall`, the array-function dispatch);
- indexing, reads and writes (`array_subscript`, `array_assign_subscript`);
- ndarray methods and attributes read from Python (`array_<name>`, `array_<name>_get`;
  the operator slots are left out, as their ufunc call is counted).

The break is run K = 1 and K = 3 times; per break is the difference over 2, which leaves
start-up out, and per event divides by the break's events.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

ENTRY = ("ufunc_generic_vectorcall", "dispatcher_vectorcall", "array_subscript",
         "array_assign_subscript")
RUNNER = "benchmarks/instructions.py"  # the standard break, K times


def entry_points() -> set[str]:
    """numpy's C functions counted as a call from Python (see the module's docstring)."""
    import numpy as np

    ufuncs = {f"array_{n}" for n in dir(np) if isinstance(getattr(np, n, None), np.ufunc)}
    names = [n for n in dir(np.ndarray) if not n.startswith("__")]
    methods = {f"array_{n}" for n in names} | {f"array_{n}_get" for n in names}
    return set(ENTRY) | (methods - ufuncs)


def parse_calls(text: str) -> Counter:
    """Calls to each function in a callgrind output file (summed over callers)."""
    calls: Counter = Counter()
    names: dict[str, str] = {}
    current = None
    for line in text.splitlines():
        # Function names are compressed: "(id) name" the first time, "(id)" after, in one
        # namespace shared by fn= (the caller) and cfn= (the called) lines.
        m = re.match(r"(c?)fn=\((\d+)\)(?: (.*))?", line)
        if m:
            if m.group(3):
                names[m.group(2)] = m.group(3)
            current = names.get(m.group(2)) if m.group(1) else None
            continue
        m = re.match(r"calls=(\d+)", line)
        if m and current:
            calls[current] += int(m.group(1))
    return calls


def numpy_calls(counts: Counter, points: set[str]) -> int:
    return sum(v for k, v in counts.items() if k in points)


def callgrind(root: Path, runner: str, k: int) -> Counter:
    """Calls per function of `python runner k` under callgrind, with `root` on the path."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cg.out")
        env = dict(os.environ, PYTHONHASHSEED="0", OPENBLAS_NUM_THREADS="1",
                   OMP_NUM_THREADS="1", PYTHONPATH=str(root))
        # valgrind must run the interpreter itself, not a shell shim.
        exe = os.path.realpath(sys.executable)
        p = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                            exe, str(root / runner), str(k)],
                           env=env, capture_output=True, text=True, timeout=3600)
        if p.returncode != 0:
            last = (p.stderr.strip().splitlines() or ["no output"])[-1]
            raise RuntimeError(f"valgrind failed: {last}")
        return parse_calls(Path(out).read_text())


def calls_per_event(events: int) -> dict:
    """numpy calls per break and per event of the standard break, or None where valgrind is
    not installed."""
    if shutil.which("valgrind") is None:
        return {"numpy_calls_per_break": None, "numpy_calls_per_event": None}
    import termpool

    root = Path(termpool.__file__).resolve().parent.parent
    points = entry_points()
    one, three = (numpy_calls(callgrind(root, RUNNER, k), points) for k in (1, 3))
    per_break = (three - one) / 2
    return {"numpy_calls_per_break": per_break, "numpy_calls_per_event": per_break / events}
