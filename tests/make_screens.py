"""Write tests/snapshots/screens.json: the regression snapshot of the game's screens.

    python tests/make_screens.py

It plays every scenario of tests/screen_scenarios.py at each size and colour depth and stores
what the screen did, in chunks of digests (see `screen_scenarios.chunks`). The file in the
repository was made from the app as it was before it became state, update and view (commit
dd8e13d), so tests/test_ui_screens.py holds the new code to the old screens, cell for cell.
Make it again only for a change of the screens that is meant, and say so in the commit.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import screen_scenarios as S  # noqa: E402

OUT = HERE / "snapshots" / "screens.json"


def key(name: str, cols: int, rows: int, colors: str) -> str:
    return f"{name} {cols}x{rows} {colors}"


def main() -> int:
    found = {}
    for name in S.SCENARIOS:
        for cols, rows in S.SIZES:
            for colors in S.DEPTHS:
                log = S.run(name, cols, rows, colors)
                found[key(name, cols, rows, colors)] = {"entries": len(log),
                                                        "chunks": S.chunks(log)}
                print(key(name, cols, rows, colors), len(log), flush=True)
    OUT.parent.mkdir(exist_ok=True)
    lines = [f"{json.dumps(k)}: {json.dumps(found[k])}" for k in sorted(found)]
    OUT.write_text("{\n" + ",\n".join(lines) + "\n}\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
