"""The planner's rooms keep their one-way dependencies: read from the source (AST), not run.

ros/ is the only room that imports ROS; nothing imports ros/; the optimiser ga/ knows nothing of
routes; the data layers geo/ and the ship model ship/ know nothing of the route-finding, the
optimiser or the experiments; no module reaches for another module's private names; no import
cycle between modules; no module over 400 lines.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1] / "shiproute_planner"
PKG = "shiproute_planner"
ROS_PACKAGES = ("rclpy", "shiproute_msgs", "nav_msgs", "geometry_msgs", "builtin_interfaces",
                "diagnostic_msgs", "rcl_interfaces", "std_msgs", "foxglove_msgs")
MAX_LINES = 400
#: room -> rooms (first component under the package) it must not import
FORBIDDEN = {
    "ga": ("route", "geo", "ship", "ros", "baselines", "experiments", "cli", "fleet"),
    "geo": ("route", "ga", "ship", "ros", "baselines", "experiments", "cli", "fleet"),
    "ship": ("route", "ga", "geo", "ros", "baselines", "experiments", "cli", "fleet"),
    "route": ("ga", "ros", "baselines", "experiments", "cli", "fleet"),
}


def _modules() -> dict[str, Path]:
    out = {}
    for path in ROOT.rglob("*.py"):
        parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _imports(name: str) -> list[tuple[str, str]]:
    """(imported module, imported name or '') of every import in module `name`, lazy ones too."""
    path = MODULES[name]
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    out = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out += [(a.name, "") for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            module = ".".join([*base, node.module] if node.module else base)
            for a in node.names:
                full = f"{module}.{a.name}"
                out.append((full, "") if full in MODULES else (module, a.name))
    return out


def _room(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 2 or (len(parts) == 2 and (ROOT / parts[1]).is_dir()) else ""


def test_only_the_ros_room_imports_ros() -> None:
    offenders = [(m, t) for m in MODULES if _room(m) != "ros" for t, _ in _imports(m)
                 if t.split(".")[0] in ROS_PACKAGES]
    assert offenders == []


def test_nothing_outside_ros_imports_the_ros_room() -> None:
    offenders = [(m, t) for m in MODULES if _room(m) != "ros" for t, _ in _imports(m)
                 if t.startswith(f"{PKG}.ros")]
    assert offenders == []


def test_the_product_does_not_import_the_experiments() -> None:
    offenders = [(m, t) for m in MODULES if _room(m) not in ("experiments", "cli")
                 for t, _ in _imports(m) if t.startswith(f"{PKG}.experiments")]
    assert offenders == []


@pytest.mark.parametrize("room", sorted(FORBIDDEN))
def test_rooms_depend_one_way(room: str) -> None:
    offenders = [(m, t) for m in MODULES if _room(m) == room for t, _ in _imports(m)
                 if t.startswith(f"{PKG}.") and _room(t) in FORBIDDEN[room]]
    assert offenders == []


def test_no_private_name_from_another_module() -> None:
    offenders = [(m, t, n) for m in MODULES for t, n in _imports(m)
                 if t != "__future__" and n.startswith("_") and not n.startswith("__")]
    assert offenders == []


def test_no_import_cycle_between_modules() -> None:
    graph = {m: {t for t, _ in _imports(m) if t in MODULES and t != m} for m in MODULES}
    # importing a.b.c runs a/__init__ and a/b/__init__ first: a cycle through them counts too
    for m, targets in graph.items():
        for t in list(targets):
            parts = t.split(".")
            for i in range(2, len(parts)):
                parent = ".".join(parts[:i])
                if parent in MODULES and parent != m and not m.startswith(parent + "."):
                    targets.add(parent)
    state: dict[str, int] = {}
    cycle: list[str] = []

    def visit(m: str, stack: list[str]) -> bool:
        state[m] = 1
        for t in graph[m]:
            if state.get(t) == 1:
                cycle.extend([*stack[stack.index(t):], m, t] if t in stack else [m, t])
                return True
            if t not in state and visit(t, [*stack, m]):
                return True
        state[m] = 2
        return False

    assert not any(visit(m, []) for m in sorted(MODULES) if m not in state), cycle


def test_no_module_over_400_lines() -> None:
    long = {m: n for m, p in MODULES.items() if (n := len(p.read_text().splitlines())) > MAX_LINES}
    assert long == {}
