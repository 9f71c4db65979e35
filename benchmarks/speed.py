"""Speed benchmark of the physics core: same as `termpool bench speed [options]`.

python benchmarks/speed.py [--json] [--repeat N] [--batch B] [--dt S]
"""

from __future__ import annotations

import os
import sys

if __name__ == "__main__":
    # Run from a checkout without installing: make the repository's termpool importable.
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from bench import main

    raise SystemExit(main(["speed", *sys.argv[1:]]))
