"""What a run of the engine gives back, as JSON, and the fixed step runs are driven with.

`sim_result` is the one definition of the printed form: `termpool sim` prints it, and a shot
record (game/record.py) keeps its time, steps, events and final balls, so a replay compares
exactly what sim would print. Kept light (numpy is imported inside the functions), so the
command line can import it at start.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

DT = 1 / 60  # s: the game's fixed step (every shot is recorded with it); sim's and bench's default
DT_RANGE = (1e-4, 1.0)  # s: a fixed step sim, a match or a replay accepts


def _f(x: Any) -> float:
    return float(x)


def _ball_state(d: dict) -> dict:
    out = {k: _f(d[k]) for k in ("x", "y", "vx", "vy") if k in d}
    if "w" in d:
        out["w"] = [_f(v) for v in d["w"]]
    if "state" in d:
        out["state"] = str(d["state"])
    for k, v in d.items():  # anything else the engine reports, passed through
        if k not in out and k != "id":
            out[k] = v
    return out


def sim_result(ids: Sequence[str], hole_names: Sequence[str], eng: Any, samples: list | None,
               method: str, dt: float | None, wall_time: float) -> dict:
    """The JSON-able result of a finished run of `eng` (an Engine of one table), its balls
    named by `ids` and its pockets by `hole_names` (the table's).

    `samples` is what the run returned, or None to leave the "samples" key out.
    """
    import numpy as np

    from termpool.physics.state import STATE_NAMES

    n = len(ids)
    pos = np.asarray(eng.pos, float).reshape(-1, n, 2)[0]
    vel = np.asarray(eng.vel, float).reshape(-1, n, 2)[0]
    w = np.asarray(eng.w, float).reshape(-1, n, 3)[0]
    state = np.asarray(eng.state).reshape(-1, n)[0]
    pocket = np.asarray(eng.pocket).reshape(-1, n)[0]
    pocketed = STATE_NAMES.index("pocketed")
    balls = []
    for i, bid in enumerate(ids):
        b = {
            "id": bid,
            "x": _f(pos[i, 0]),
            "y": _f(pos[i, 1]),
            "vx": _f(vel[i, 0]),
            "vy": _f(vel[i, 1]),
            "w": [_f(v) for v in w[i]],
            "state": STATE_NAMES[int(state[i])],
        }
        if int(pocket[i]) >= 0:
            b["pocket"] = hole_names[int(pocket[i])]
        balls.append(b)

    log = eng.events[0] if eng.events and isinstance(eng.events[0], list) else eng.events
    events = []
    for ev in sorted(log, key=lambda e: e["t"]):
        idx = [int(i) for i in ev["i"]]
        out = {"t": _f(ev["t"]), "type": ev["type"], "ids": [ids[i] for i in idx]}
        out["balls"] = [
            {"id": ids[i], **_ball_state(b)} for i, b in zip(idx, ev.get("balls", []), strict=False)
        ]
        for k in ("pocket", "feature"):
            if ev.get(k) is not None:
                out[k] = ev[k]
        events.append(out)

    result: dict[str, Any] = {
        "time": _f(eng.time),
        "steps": int(eng.steps),
        "wall_time": wall_time,
        "method": method,
        "dt": dt,
        "balls": balls,
        "events": events,
    }
    if samples is not None:
        result["samples"] = _samples(samples, ids, pocketed)
    return result


def _samples(samples: list, ids: Sequence[str], pocketed: int) -> list[dict]:
    import numpy as np

    n = len(ids)
    out = []
    for t, pos, state in samples:
        p = np.asarray(pos, float).reshape(-1, n, 2)[0]
        s = np.asarray(state).reshape(-1, n)[0]
        out.append(
            {
                "t": _f(t),
                "pos": {
                    bid: [_f(p[i, 0]), _f(p[i, 1])]
                    for i, bid in enumerate(ids)
                    if int(s[i]) != pocketed
                },
            }
        )
    return out
