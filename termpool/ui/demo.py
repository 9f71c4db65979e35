"""Print one frame of a scene to the terminal: python -m termpool.ui.demo [scene.json] [options].

Options: --colors auto|truecolor|256|16|mono, --size COLSxROWS (default: the terminal's),
--time T (run the scene's shot for T simulated seconds first).
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
from pathlib import Path

from termpool.physics.engine import Engine
from termpool.physics.results import DT
from termpool.rules.referee import load_game_scene
from termpool.scene import SceneError
from termpool.ui.frame import render_scene_text

DEFAULT_SCENE = Path(__file__).resolve().parent.parent / "examples" / "break.json"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m termpool.ui.demo", description=__doc__)
    ap.add_argument("scene", nargs="?", default=str(DEFAULT_SCENE), help="scene file (JSON)")
    ap.add_argument("--colors", default="auto", choices=["auto", "truecolor", "256", "16", "mono"])
    ap.add_argument("--size", help="COLSxROWS instead of the terminal's size")
    ap.add_argument("--time", type=float, default=0.0, help="simulate the shot this long first")
    args = ap.parse_args(argv)

    try:
        scene = load_game_scene(args.scene)  # a game block is checked as termpool sim does
    except SceneError as e:
        print(f"demo: {e}", file=sys.stderr)
        return 2
    if args.size:
        try:
            cols, rows = (int(v) for v in args.size.lower().split("x"))
        except ValueError:
            print("demo: --size must look like 120x40", file=sys.stderr)
            return 2
        clear = ""
    else:
        cols, rows = shutil.get_terminal_size()
        rows -= 1  # keep the last line for the cursor (and the shell prompt)
        clear = "\x1b[H\x1b[2J"
    pos, state = scene.pos, None
    if args.time > 0:
        eng = Engine(scene.table, scene.physics, scene.pos, scene.vel, scene.w, scene.radius,
                     scene.mass, record=False)
        eng.run(DT, duration=args.time)
        pos, state = eng.pos[0], eng.state[0]
    title = "termpool  " + os.path.basename(args.scene)
    text = render_scene_text(scene.table, scene.ids, pos, state, cols, rows, args.colors,
                             radius=scene.radius, title=title)
    sys.stdout.write(clear + text + (f"\x1b[{rows + 1};1H" if clear else "\n"))
    sys.stdout.flush()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
