"""The weather package's rooms keep their rule: one-way imports between rooms, no import cycle
between modules, no private name or private module imported from another module, no module
over 400 lines, ROS only in `ros/` and `experiments/` (the package's map: ARCHITECTURE.md)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE_DIR = Path(__file__).resolve().parents[1] / "shiproute_weather"
PACKAGE = PACKAGE_DIR.name
#: each room may import only rooms listed before it
ROOM_ORDER = ("errors", "contract", "physics", "wire", "sampling", "ingest", "scenarios", "ros",
              "experiments", "cli", "__init__")
ROS_ROOMS = ("ros", "experiments")
MAX_LINES = 400


def _module_name(path: Path) -> tuple[str, bool]:
    parts = list(path.relative_to(PACKAGE_DIR.parent).with_suffix("").parts)
    is_package = parts[-1] == "__init__"
    return ".".join(parts[:-1] if is_package else parts), is_package


MODULES = {_module_name(p)[0]: p for p in sorted(PACKAGE_DIR.rglob("*.py"))}


def _imports(path: Path) -> list[tuple[str, list[str]]]:
    """(absolute module, imported names) of every import statement, also inside functions."""
    name, is_package = _module_name(path)
    out: list[tuple[str, list[str]]] = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = name.split(".") if is_package else name.split(".")[:-1]
                base = base[: len(base) - (node.level - 1)]
                module = ".".join([*base, *([node.module] if node.module else [])])
            out.append((module, [a.name for a in node.names]))
        elif isinstance(node, ast.Import):
            out.extend((a.name, []) for a in node.names)
    return out


def _room(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def _targets(module: str, names: list[str]) -> list[str]:
    """Modules of this package that an import statement loads (a name may be a submodule)."""
    found = [module] if module in MODULES else []
    found += [f"{module}.{n}" for n in names if f"{module}.{n}" in MODULES]
    return found


@pytest.mark.parametrize("module", sorted(MODULES))
def test_rooms_import_only_rooms_before_them(module: str) -> None:
    room = _room(module)
    for target, names in _imports(MODULES[module]):
        for dep in _targets(target, names):
            dep_room = _room(dep)
            assert ROOM_ORDER.index(dep_room) <= ROOM_ORDER.index(room), (
                f"{module} (room {room}) imports {dep} (room {dep_room}): rooms import only "
                f"rooms before them in {ROOM_ORDER}")


def test_no_import_cycle_between_modules() -> None:
    graph = {m: {d for t, n in _imports(p) for d in _targets(t, n) if d != m}
             for m, p in MODULES.items()}
    state: dict[str, int] = {}

    def visit(m: str, path: list[str]) -> None:
        state[m] = 1
        for d in sorted(graph[m]):
            assert state.get(d) != 1, f"import cycle: {' -> '.join([*path, m, d])}"
            if d not in state:
                visit(d, [*path, m])
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m, [])


@pytest.mark.parametrize("module", sorted(MODULES))
def test_no_private_name_from_another_module(module: str) -> None:
    for target, names in _imports(MODULES[module]):
        if target == "__future__":
            continue
        private_module = [p for p in target.split(".") if p.startswith("_") and p != "__init__"]
        assert not private_module, f"{module} imports the private module {target}"
        private = [n for n in names if n.startswith("_")]
        assert not private, f"{module} imports private {private} from {target}"


@pytest.mark.parametrize("module", sorted(MODULES))
def test_module_is_at_most_400_lines(module: str) -> None:
    n = len(MODULES[module].read_text().splitlines())
    assert n <= MAX_LINES, f"{module} has {n} lines (limit {MAX_LINES}): split it by concern"


@pytest.mark.parametrize("module", sorted(MODULES))
def test_ros_only_in_the_ros_rooms(module: str) -> None:
    if _room(module) in ROS_ROOMS:
        return
    ros = [t for t, _ in _imports(MODULES[module])
           if t.split(".")[0] in ("rclpy", "shiproute_msgs", "diagnostic_msgs")]
    assert not ros, f"{module} imports {ros}: only {ROS_ROOMS} may touch ROS"


def test_the_checks_see_the_package() -> None:
    """Guards the tests above against passing on an empty or misread tree."""
    assert len(MODULES) > 40
    assert {_room(m) for m in MODULES} == set(ROOM_ORDER)
    node_imports = {t for t, _ in _imports(MODULES[f"{PACKAGE}.ros.node"])}
    assert "rclpy" in node_imports
    assert f"{PACKAGE}.ingest.stream" in node_imports
