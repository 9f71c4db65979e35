"""Stiff and extreme cases of the physics core: same as `termpool bench stability [options]`.

python benchmarks/stability.py [--json] [--quick] [--case TEXT ...]
"""

from __future__ import annotations

import os
import sys

if __name__ == "__main__":
    # Run from a checkout without installing: make the repository's termpool importable.
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from bench import main

    raise SystemExit(main(["stability", *sys.argv[1:]]))
