"""Rules of the source tree that keep it readable: no import cycles, no reaching into another
module's private names, small modules, names and flags defined once."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest
from tree_imports import (
    PACKAGES,
    REPO,
    find_cycles,
    import_edges,
    is_private,
    parent_package,
    source_modules,
)

MAX_MODULE_LINES = 400
# module (path under src/) -> why it may be longer than MAX_MODULE_LINES
LONG_MODULE_EXCEPTIONS: dict[str, str] = {}


def _all_modules() -> dict[str, Path]:
    modules: dict[str, Path] = {}
    for package in PACKAGES:
        modules.update(source_modules(package))
    return modules


MODULES = _all_modules()
EDGES = import_edges(MODULES)


def test_the_graph_reader_sees_every_package_and_their_imports() -> None:
    # guards the rules below against passing vacuously on an empty graph
    assert {m.split(".")[0] for m in MODULES} == set(PACKAGES)
    assert len(MODULES) > 200 and len(EDGES) > 500


def test_reader_finds_a_cycle_and_a_private_import(tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from .b import _hidden\n")
    (pkg / "b.py").write_text("from . import a\n_hidden = 1\n")
    modules = {"pkg": pkg / "__init__.py", "pkg.a": pkg / "a.py", "pkg.b": pkg / "b.py"}
    edges = import_edges(modules)
    assert find_cycles(modules, edges) == [["pkg.a", "pkg.b"]]
    assert [e.names for e in edges if e.importer == "pkg.a"] == [("_hidden",)]


def test_no_import_cycles() -> None:
    cycles = find_cycles(MODULES, EDGES)
    assert not cycles, "import cycles (each group imports itself round):\n" + "\n".join(
        " <-> ".join(group) for group in cycles)


def test_no_private_names_imported_from_another_module() -> None:
    bad = [f"{e.importer}:{e.line} imports {name} from {e.target}"
           for e in EDGES for name in e.names if is_private(name)]
    assert not bad, "\n".join(bad)


def test_private_modules_are_used_only_inside_their_own_package() -> None:
    bad = []
    for edge in EDGES:
        if not is_private(edge.target.rsplit(".", 1)[-1]):
            continue
        home = edge.target.rsplit(".", 1)[0]
        importer_home = parent_package(edge.importer, MODULES)
        if not (importer_home == home or importer_home.startswith(home + ".")):
            bad.append(f"{edge.importer}:{edge.line} imports private module {edge.target}")
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("package", PACKAGES)
def test_modules_stay_small(package: str) -> None:
    too_long = []
    for path in source_modules(package).values():
        name = str(path.relative_to(REPO / "src"))
        lines = len(path.read_text(encoding="utf-8").splitlines())
        if lines > MAX_MODULE_LINES and name not in LONG_MODULE_EXCEPTIONS:
            too_long.append(f"{name}: {lines} lines")
    assert not too_long, f"modules over {MAX_MODULE_LINES} lines:\n" + "\n".join(too_long)


def test_long_module_exceptions_are_still_needed() -> None:
    for name in LONG_MODULE_EXCEPTIONS:
        path = REPO / "src" / name
        assert path.exists() and len(path.read_text().splitlines()) > MAX_MODULE_LINES, name


_TOPIC = re.compile(r"^/shiproute/")
_NM_LITERALS = {1852.0, 0.514444, 1852.0 / 3600.0}


def _constants(path: Path) -> list[ast.Constant]:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    return [n for n in ast.walk(tree) if isinstance(n, ast.Constant)]


def test_topic_names_are_written_only_in_core_topics() -> None:
    home = REPO / "src/shiproute_core/shiproute_core/topics.py"
    bad = [f"{path.relative_to(REPO)}:{c.lineno} {c.value!r}"
           for path in MODULES.values() if path != home
           for c in _constants(path) if isinstance(c.value, str) and _TOPIC.match(c.value)]
    assert not bad, "topic names to import from shiproute_core.topics:\n" + "\n".join(bad)


def test_nautical_mile_and_knot_are_written_only_in_core_units() -> None:
    home = REPO / "src/shiproute_core/shiproute_core/units.py"
    bad = [f"{path.relative_to(REPO)}:{c.lineno} {c.value!r}"
           for path in MODULES.values() if path != home
           for c in _constants(path)
           if isinstance(c.value, float) and any(abs(c.value - v) < 1e-9 for v in _NM_LITERALS)]
    assert not bad, "use shiproute_core.units (M_PER_NM, M_S_PER_KNOT):\n" + "\n".join(bad)
