"""The game's screens, frame by frame, are the ones of the regression snapshot.

tests/snapshots/screens.json was written by tests/make_screens.py from the app before it was
rebuilt as state, update and view; every scenario of tests/screen_scenarios.py (the menu,
the boxes, both kinds of opponent, ball in hand, options, watching, the input modes and the
settings) must draw the same cells at the same virtual times, ring the same bells and play
the same shots."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import screen_scenarios as S

SNAPSHOT = Path(__file__).resolve().parent / "snapshots" / "screens.json"
STORED = json.loads(SNAPSHOT.read_text())
RUNS = [(name, cols, rows, colors) for name in S.SCENARIOS for cols, rows in S.SIZES
        for colors in S.DEPTHS]


def test_the_snapshot_holds_every_scenario_and_no_other() -> None:
    assert sorted(STORED) == sorted(f"{n} {c}x{r} {d}" for n, c, r, d in RUNS)


@pytest.mark.parametrize(("name", "cols", "rows", "colors"), RUNS,
                         ids=[f"{n}-{c}x{r}-{d}" for n, c, r, d in RUNS])
def test_the_screens_are_the_snapshot_s(name, cols, rows, colors) -> None:
    frames: list = []
    log = S.run(name, cols, rows, colors, frames)
    want = STORED[f"{name} {cols}x{rows} {colors}"]
    got = S.chunks(log)
    for k, (mine, theirs) in enumerate(zip(got, want["chunks"], strict=False)):
        if mine != theirs:
            part = log[k * S.CHUNK:(k + 1) * S.CHUNK]
            shown = [f for f in frames if part[0][1] <= f[0] <= part[-1][1]][:1]
            text = "\n".join("".join(r).rstrip() for r in shown[0][1][0]) if shown else ""
            pytest.fail(f"the screens differ from t={part[0][1]} on (snapshot entries "
                        f"{k * S.CHUNK}-{k * S.CHUNK + len(part) - 1}); the first frame of "
                        f"that stretch now:\n{text}")
    assert len(log) == want["entries"]
