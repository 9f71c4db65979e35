"""The house rules of the imports: the import contract of pyproject.toml ([tool.importlinter],
run by import-linter: each layer imports only those below it, the benchmarks only the physics,
the scenes and the rules, no cycles inside a package), and no module importing another
module's private (`_name`) name.

A contract still broken is marked xfail(strict) naming the edges that break it: when they are
cut the test fails as XPASS, and the mark must go."""

from __future__ import annotations

import ast
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = ROOT / "pyproject.toml"
CONTRACTS = [c["id"] for c in
             tomllib.loads(PYPROJECT.read_text())["tool"]["importlinter"]["contracts"]]

# contract id -> the imports that still break it
STILL_BROKEN = {
}
# module (path from the root) -> the private names of other modules it still imports
STILL_PRIVATE = {
}

LINT = ("import sys; from importlinter.cli import lint_imports; "
        "sys.exit(lint_imports(config_filename=sys.argv[1], limit_to_contracts=(sys.argv[2],), "
        "no_cache=True))")


def lint(config: Path, contract: str, cwd: Path) -> subprocess.CompletedProcess:
    """import-linter on one contract of `config`, over the packages importable from `cwd`."""
    return subprocess.run([sys.executable, "-c", LINT, str(config), contract], cwd=cwd,
                          capture_output=True, text=True, timeout=300)


def _marked(ids, broken: dict[str, str]) -> list:
    return [pytest.param(i, marks=pytest.mark.xfail(strict=True, raises=AssertionError,
                                                    reason=f"still broken: {broken[i]}"))
            if i in broken else i for i in ids]


def test_every_contract_has_an_id_and_every_xfail_names_a_contract() -> None:
    assert len(set(CONTRACTS)) == len(CONTRACTS) >= 4
    assert set(STILL_BROKEN) <= set(CONTRACTS)


@pytest.mark.parametrize("contract", _marked(CONTRACTS, STILL_BROKEN))
def test_import_contract_holds(contract: str) -> None:
    p = lint(PYPROJECT, contract, ROOT)
    if p.returncode != 0 and "BROKEN" not in p.stdout:  # not a verdict: never an xfail
        raise RuntimeError(f"import-linter could not check '{contract}': {p.stderr[-2000:]}")
    assert p.returncode == 0, p.stdout[-3000:]


def test_a_broken_contract_fails_the_check(tmp_path: Path) -> None:
    """The check itself: a lower layer importing a higher one fails it, and the same package
    without that import passes."""
    pkg = tmp_path / "house"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "high.py").write_text("from house import low\n")
    (pkg / "low.py").write_text("from house import high\n")
    config = tmp_path / "contract.toml"
    config.write_text('[tool.importlinter]\nroot_packages = ["house"]\n\n'
                      '[[tool.importlinter.contracts]]\nid = "stairs"\nname = "one way"\n'
                      'type = "layers"\nlayers = ["house.high", "house.low"]\n')
    p = lint(config, "stairs", tmp_path)
    assert p.returncode == 1 and "house.low -> house.high" in p.stdout, p.stdout + p.stderr
    (pkg / "low.py").write_text("")
    p = lint(config, "stairs", tmp_path)
    assert p.returncode == 0, p.stdout + p.stderr


# ------------------------------------------------------------------------ private names


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _module_names() -> dict[str, Path]:
    out = {}
    for top in ("termpool", "bench"):
        for f in (ROOT / top).rglob("*.py"):
            parts = list(f.relative_to(ROOT).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            out[".".join(parts)] = f
    return out


MODULES = _module_names()


def private_imports(source: str, name: str, modules=MODULES) -> list[str]:
    """`module._name` for every private name of another of `modules` that the code `source`
    of the module called `name` imports (from X import _name) or reads off an imported module
    (X._name, alias._name)."""
    me = name.removesuffix(".__init__")
    package = name.split(".")[:-1]  # what a relative import starts from
    tree = ast.parse(source)
    found, aliases = [], {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.asname:
                    aliases[a.asname] = a.name
                else:
                    aliases[a.name.split(".")[0]] = a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            origin = ".".join([*base, *([node.module] if node.module else [])])
            for a in node.names:
                full = f"{origin}.{a.name}"
                if full in modules:
                    aliases[a.asname or a.name] = full
                if _private(a.name) and origin in modules and origin != me:
                    found.append(full)
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and _private(node.attr):
            chain, value = [], node.value
            while isinstance(value, ast.Attribute):
                chain.append(value.attr)
                value = value.value
            if isinstance(value, ast.Name) and value.id in aliases:
                owner = ".".join([aliases[value.id], *reversed(chain)])
                if owner in modules and owner != me:
                    found.append(f"{owner}.{node.attr}")
    return sorted(set(found))


def test_the_private_name_check_finds_each_form() -> None:
    code = ("from termpool import cli\nimport termpool.scene\nimport termpool.files as f\n"
            "from termpool.physics.vec import _cross\nfrom .results import _samples\n"
            "from . import engine\nfrom .cushion import simple\n"
            "cli._fail('x'); termpool.scene._fmt(1); f._size(1); engine._TRANSITION_NAMES\n"
            "simple.x._y; cli.__doc__; _own(); self._mine\n"
            "from termpool.physics.state import norm as _norm\n"
            "from .probe import _own\n")
    assert private_imports(code, "termpool.physics.probe") == [
        "termpool.cli._fail", "termpool.files._size",
        "termpool.physics.engine._TRANSITION_NAMES", "termpool.physics.results._samples",
        "termpool.physics.vec._cross", "termpool.scene._fmt"]
    # a package's __init__ is its package: relative imports start there
    assert private_imports("from .common import _x\nfrom . import _y\n",
                           "bench.__init__") == ["bench.common._x"]


def _rel_name(path: Path) -> str:
    return ".".join(path.relative_to(ROOT).with_suffix("").parts)


@pytest.mark.parametrize("rel", _marked(sorted(str(p.relative_to(ROOT)) for p in
                                               MODULES.values()), STILL_PRIVATE))
def test_no_module_imports_another_modules_private_name(rel: str) -> None:
    path = ROOT / rel
    assert private_imports(path.read_text(encoding="utf-8"), _rel_name(path)) == []
