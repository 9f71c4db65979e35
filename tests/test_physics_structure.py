"""The physics package's own structure: no import cycle between its modules (type-checking
imports included), no module importing another's private name, and every class's state
declared: no attribute born outside __init__, none read that the class does not have."""

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


def _declared(cls: ast.ClassDef) -> tuple[set[str], dict[str, set[str]]]:
    """A class's names (methods, properties, class attributes and annotated fields), and per
    method the attributes it assigns on self."""
    names: set[str] = set()
    assigned: dict[str, set[str]] = {}
    for node in cls.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            names.add(node.name)
            own = set()
            for sub in ast.walk(node):
                targets = []
                if isinstance(sub, ast.Assign):
                    targets = sub.targets
                elif isinstance(sub, (ast.AugAssign, ast.AnnAssign)):
                    targets = [sub.target]
                for t in targets:
                    for x in ast.walk(t):
                        if (isinstance(x, ast.Attribute) and isinstance(x.ctx, ast.Store)
                                and isinstance(x.value, ast.Name) and x.value.id == "self"):
                            own.add(x.attr)
            assigned[node.name] = own
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names |= {x.id for t in node.targets for x in ast.walk(t) if isinstance(x, ast.Name)}
    return names, assigned


def _classes():
    for path in sorted(PHYSICS.rglob("*.py")):
        if path.name == "naive.py":  # the benchmarks' baselines (template methods), not the game's
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ClassDef):
                yield path.relative_to(ROOT).as_posix(), node


def test_every_physics_class_declares_its_state_in_init():
    born, unknown = [], []
    for where, cls in _classes():
        names, assigned = _declared(cls)
        init = assigned.get("__init__", set())
        for method, attrs in assigned.items():
            if method != "__init__":
                born += [f"{where}: {cls.name}.{a} (in {method})" for a in attrs - init - names]
        bases = {b.id for b in cls.bases if isinstance(b, ast.Name)}
        if bases - {"Protocol"}:
            continue  # what a base class (an exception, an enum) holds is not written here
        for sub in ast.walk(cls):
            if (isinstance(sub, ast.Attribute) and isinstance(sub.ctx, ast.Load)
                    and isinstance(sub.value, ast.Name) and sub.value.id == "self"
                    and sub.attr not in init | names and not sub.attr.startswith("__")):
                unknown.append(f"{where}: {cls.name} reads self.{sub.attr}")
    assert born == []
    assert sorted(set(unknown)) == []


def test_the_state_check_finds_an_attribute_born_late_and_one_never_declared():
    src = ast.parse("class A:\n def __init__(self):\n  self.a = 1\n"
                    " def f(self):\n  self.b = self.c\n")
    names, assigned = _declared(src.body[0])
    assert assigned == {"__init__": {"a"}, "f": {"b"}} and names == {"__init__", "f"}
