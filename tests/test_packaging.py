"""What `pip install .` installs: every package of the game (setuptools finds a package only by
its __init__.py) and its data, and not the benchmarks, which live beside it in the checkout."""

from __future__ import annotations

import tomllib
from pathlib import Path

from setuptools import find_packages

ROOT = Path(__file__).resolve().parent.parent


def test_the_wheel_holds_every_game_package_and_no_benchmarks() -> None:
    find = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"][
        "packages"]["find"]
    shipped = set(find_packages(where=str(ROOT), **find))
    code = {".".join(d.relative_to(ROOT).parts) for d in (ROOT / "termpool").rglob("*")
            if d.is_dir() and any(d.glob("*.py"))} | {"termpool"}
    assert shipped == code
    assert not any(p == "bench" or p.startswith("bench.") for p in shipped)
    assert (ROOT / "bench" / "__init__.py").exists()
