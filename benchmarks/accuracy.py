"""Accuracy benchmark of the stepping schemes: same as `termpool bench accuracy [options]`.

python benchmarks/accuracy.py [--json] [--scenes DIR] [--closed NAMES] [--dts S ...]
                              [--schemes A,B] [--png PATH]
"""

from __future__ import annotations

import os
import sys

if __name__ == "__main__":
    # Run from a checkout without installing: make the repository's termpool importable.
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from bench import main

    raise SystemExit(main(["accuracy", *sys.argv[1:]]))
