"""The import graph of the shiproute packages read from their source with `ast` (nothing is
imported): which module imports which, at which line, and which names."""

from __future__ import annotations

import ast
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PACKAGES = ("shiproute_core", "shiproute_weather", "shiproute_planner", "shiproute_ais_replay",
            "shiproute_bringup", "shiproute_display")


@dataclass(frozen=True)
class ImportEdge:
    """One import statement of `importer`, resolved to the module it reads `names` from."""

    importer: str
    target: str
    names: tuple[str, ...]
    line: int


def source_modules(package: str) -> dict[str, Path]:
    """Dotted module name -> file, for every module of one package (tests excluded)."""
    root = REPO / "src" / package
    modules: dict[str, Path] = {}
    for path in sorted((root / package).rglob("*.py")):
        parts = list(path.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        modules[".".join(parts)] = path
    return modules


def _is_type_checking_block(node: ast.AST) -> bool:
    test = getattr(node, "test", None)
    return isinstance(node, ast.If) and (
        (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING")
        or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"))


def _imports(tree: ast.AST) -> list[ast.Import | ast.ImportFrom]:
    """Every import statement, skipping `if TYPE_CHECKING:` blocks (they never run)."""
    found: list[ast.Import | ast.ImportFrom] = []
    stack: list[ast.AST] = [tree]
    while stack:
        node = stack.pop()
        if _is_type_checking_block(node):
            continue
        if isinstance(node, ast.Import | ast.ImportFrom):
            found.append(node)
        stack.extend(ast.iter_child_nodes(node))
    return found


def _base(module: str, path: Path, node: ast.ImportFrom) -> str:
    """Absolute dotted name an ImportFrom reads from (relative levels resolved)."""
    if node.level == 0:
        return node.module or ""
    package_parts = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
    keep = package_parts[: len(package_parts) - (node.level - 1)]
    return ".".join(keep + ([node.module] if node.module else []))


def import_edges(modules: dict[str, Path]) -> list[ImportEdge]:
    """Edges between modules of the known set; `from pkg import sub` resolves to the submodule."""
    edges: list[ImportEdge] = []
    for module, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in _imports(tree):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name in modules:
                        edges.append(ImportEdge(module, alias.name, (), node.lineno))
                continue
            base = _base(module, path, node)
            plain: list[str] = []
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                if sub in modules:
                    edges.append(ImportEdge(module, sub, (), node.lineno))
                else:
                    plain.append(alias.name)
            if plain and base in modules:
                edges.append(ImportEdge(module, base, tuple(plain), node.lineno))
    return edges


def find_cycles(modules: dict[str, Path], edges: list[ImportEdge]) -> list[list[str]]:
    """Strongly connected groups of more than one module (Tarjan), each sorted."""
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for edge in edges:
        if edge.target != edge.importer:
            graph[edge.importer].add(edge.target)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    groups: list[list[str]] = []
    counter = 0

    def visit(start: str) -> None:
        nonlocal counter
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                group = []
                while True:
                    top = stack.pop()
                    on_stack.discard(top)
                    group.append(top)
                    if top == node:
                        break
                if len(group) > 1:
                    groups.append(sorted(group))

    for module in sorted(graph):
        if module not in index:
            visit(module)
    return groups


def is_private(name: str) -> bool:
    """A leading underscore marks a name private to its module (dunders are not private)."""
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def parent_package(module: str, modules: dict[str, Path]) -> str:
    """The package a module lives in (a package's own parent for an `__init__`)."""
    path = modules[module]
    return module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
