"""The physics package's own import structure: no cycle between its modules (type-checking
imports included), and no module importing another's private name."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PHYSICS = ROOT / "termpool" / "physics"


def _module(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports() -> dict[str, list[tuple[str, list[str]]]]:
    """Each physics module's imports of physics modules: (module, names imported from it)."""
    mods = {_module(p): p for p in PHYSICS.rglob("*.py")}
    out: dict[str, list[tuple[str, list[str]]]] = {}
    for name, path in mods.items():
        found = []
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module:
                names = [a.name for a in node.names]
                if node.module in mods:
                    found.append((node.module, names))
                found += [(f"{node.module}.{n}", []) for n in names
                          if f"{node.module}.{n}" in mods]
            elif isinstance(node, ast.Import):
                found += [(a.name, []) for a in node.names if a.name in mods]
        out[name] = found
    return out


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of the graph, or None."""
    state: dict[str, int] = {}
    path: list[str] = []

    def visit(n: str) -> list[str] | None:
        state[n] = 1
        path.append(n)
        for m in sorted(graph.get(n, ())):
            if state.get(m) == 1:
                return path[path.index(m):] + [m]
            if m not in state and (found := visit(m)):
                return found
        path.pop()
        state[n] = 2
        return None

    for n in sorted(graph):
        if n not in state and (found := visit(n)):
            return found
    return None


def test_the_physics_modules_import_each_other_without_a_cycle():
    graph = {m: {dep for dep, _ in deps if dep != m} for m, deps in _imports().items()}
    # A package imports its own modules to list them; a module importing its package's
    # __init__ back would be the cycle.
    assert _cycle(graph) is None, " -> ".join(_cycle(graph) or [])


def test_no_physics_module_imports_another_modules_private_name():
    private = [(m, dep, n) for m, deps in _imports().items() for dep, names in deps
               for n in names if n.startswith("_") and n != "__future__"]
    assert private == []


def test_the_cycle_finder_finds_a_cycle():
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
