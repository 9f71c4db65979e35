"""pooltool's side of `termpool bench speed`'s paired breaks: one process, kept alive.

    PYTHON bench/pooltool_worker.py     (started by bench/pooltool_pair.py, not by hand)

Run by an interpreter that has pooltool (often a separate environment), so it uses only the
standard library and pooltool, never termpool. It talks one JSON object a line:

    worker -> {"ok": true, "version": V}          once pooltool is imported
    {"op": "setup", "name": N, ...} -> {"ok": true, "events": E, "warm_cpu_s": [...]}
        builds break N from termpool's scene (`pooltool_break` below), then runs it `warm`
        times, outside the figures, so numba has compiled everything before the first timed run
    {"op": "break", "name": N}      -> {"ok": true, "cpu_s": C, "wall_s": W, "events": E}
        one break N from its built template to rest; C is time.process_time() around it
    end of input          -> the worker exits 0
    any failure           -> {"ok": false, "error": ONE_LINE}, and the worker exits 1
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Callable
from typing import Any, TextIO

# A break: run() simulates one break and returns what count() turns into its event count
# (counted outside the timed part).
Break = tuple[Callable[[], Any], Callable[[Any], int]]


def _say(out: TextIO, obj: dict) -> None:
    out.write(json.dumps(obj) + "\n")
    out.flush()


def _timed(brk: Break) -> dict:
    run, count = brk
    c0, w0 = time.process_time(), time.perf_counter()
    result = run()
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    return {"cpu_s": cpu, "wall_s": wall, "events": count(result)}


def serve(make_break: Callable[[dict], Break], version: str,
          stdin: TextIO = sys.stdin, stdout: TextIO = sys.stdout) -> int:
    """Answer setup and break requests until the end of input (the protocol above).
    `make_break(setup)` builds the break; a stand-in engine can be served the same way."""
    _say(stdout, {"ok": True, "version": version})
    breaks: dict[str, Break] = {}
    for line in stdin:
        try:
            req = json.loads(line)
            name = str(req.get("name", ""))
            if req["op"] == "setup":
                breaks[name] = make_break(req)
                runs = [_timed(breaks[name]) for _ in range(max(1, int(req.get("warm", 1))))]
                answer = {"ok": True, "events": runs[-1]["events"],
                          "warm_cpu_s": [r["cpu_s"] for r in runs]}
            elif req["op"] == "break" and name in breaks:
                answer = {"ok": True, **_timed(breaks[name])}
            else:
                raise ValueError(f"unexpected request {line.strip()[:80]!r}")
        except Exception as e:  # noqa: BLE001 -- every failure goes back as one line
            _say(stdout, {"ok": False, "error": f"{type(e).__name__}: {e}".splitlines()[0]})
            return 1
        _say(stdout, answer)
    return 0


def pooltool_break(setup: dict) -> Break:
    """termpool's break in pooltool: the same table size, pockets' mouths and holes, cushion
    height, balls (positions, radius, mass), starting velocities and spins, and the friction
    and restitution figures pooltool has names for. termpool's x (along the table) becomes
    pooltool's y and termpool's y becomes width - x: a rotation, so spins keep their sense.
    A moving ball starts sliding, as a ball struck without a cue's contact time does in
    termpool. Each run simulates a copy of the template to rest, as termpool's break builds
    its Engine each run."""
    import numpy as np
    import pooltool as pt

    t, ph = setup["table"], setup["physics"]
    specs = pt.objects.PocketTableSpecs(
        l=t["length"], w=t["width"], cushion_height=ph["cushion_height"],
        corner_pocket_width=t["corner_mouth"], side_pocket_width=t["side_mouth"],
        corner_pocket_radius=t["corner_hole_radius"], side_pocket_radius=t["side_hole_radius"],
    )
    table = pt.Table.from_table_specs(specs)
    width = t["width"]
    balls = {}
    for b in setup["balls"]:
        (x, y), (vx, vy), (wx, wy, wz) = b["pos"], b["vel"], b["w"]
        ball = pt.Ball.create(
            b["id"], xy=(width - y, x), R=b["radius"], m=b["mass"],
            u_s=ph["mu_slide"], u_r=ph["mu_roll"], u_sp_proportionality=ph["mu_spin"] / b["radius"],
            e_b=ph["e_ball"], e_c=ph["e_cushion"], f_c=ph["mu_cushion"], g=ph["g"],
        )
        if any((vx, vy, wx, wy, wz)):
            ball.state.rvw[1] = np.array([-vy, vx, 0.0])
            ball.state.rvw[2] = np.array([-wy, wx, wz])
            ball.state.s = pt.constants.sliding
        balls[b["id"]] = ball
    template = pt.System(table=table, balls=balls, cue=pt.Cue(cue_ball_id=setup["cue"]))

    def run() -> Any:
        return pt.simulate(template)  # simulates a copy; the template stays at the start

    def count(shot: Any) -> int:  # pooltool's own events, without its start and end markers
        return sum(1 for e in shot.events if e.event_type != pt.EventType.NONE)

    return run, count


def main() -> int:
    # Python put this file's folder (termpool's bench/) first on sys.path: take it off, so
    # nothing there can stand in for a module pooltool imports.
    del sys.path[0]
    try:
        import pooltool
    except Exception as e:  # noqa: BLE001 -- ImportError, or anything its import raises
        _say(sys.stdout, {"ok": False, "error": f"cannot import pooltool ({type(e).__name__}: "
                                                f"{e})".splitlines()[0]})
        return 1
    return serve(pooltool_break, str(getattr(pooltool, "__version__", "unknown")))


if __name__ == "__main__":
    raise SystemExit(main())
