"""The standard break run K times, for counting instructions with valgrind (load-independent).

Instructions per break are (count(K=3) - count(K=1)) / 2, which leaves out start-up:

    PYTHONHASHSEED=0 OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 \\
        valgrind --tool=callgrind --callgrind-out-file=/dev/null \\
        "$(python -c 'import sys; print(sys.executable)')" benchmarks/instructions.py 3

(valgrind must run the interpreter itself, not a shell shim such as pyenv's; with BLAS's
default threads their spinning is counted too, and the count moves from run to run.)
"""

from __future__ import annotations

import os
import sys

if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from termpool.physics.engine import Engine
    from termpool.scene import load_scene

    scene = load_scene(os.path.join(os.path.dirname(__file__), "..", "bench", "scenes",
                                    "break.json"))
    for _ in range(int(sys.argv[1]) if len(sys.argv) > 1 else 1):
        Engine(scene.table, scene.physics, scene.pos, scene.vel, scene.w, scene.radius,
               scene.mass).run(1 / 60)
