"""Parse and validate a bringup YAML file into node specifications (no processes here)."""

from __future__ import annotations

import os
import shutil
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from shiproute_bringup.errors import BringupFileError

NODE_KEYS = {"name", "executable", "parameters", "args", "ros_args", "env", "required"}


@dataclass(frozen=True)
class NodeSpec:
    """One node to start: console script, ROS node name, parameters, extra args and env."""

    name: str
    executable: str
    parameters: dict[str, Any] = field(default_factory=dict)
    args: tuple[str, ...] = ()
    ros_args: tuple[str, ...] = ()
    env: dict[str, str] = field(default_factory=dict)
    required: bool = False

    def argv(self, params_file: Path) -> list[str]:
        """Command line: executable, args, then --ros-args with params file and node name."""
        return [self.executable, *self.args, "--ros-args", "--params-file", str(params_file),
                "-r", f"__node:={self.name}", *self.ros_args]


def _expand(value: Any, variables: dict[str, str]) -> Any:
    """Expand ``${VAR}``/``$VAR`` in strings (recursively in lists and dicts)."""
    if isinstance(value, str):
        saved = dict(os.environ)
        try:
            os.environ.update(variables)
            return os.path.expandvars(value)
        finally:
            os.environ.clear()
            os.environ.update(saved)
    if isinstance(value, list):
        return [_expand(v, variables) for v in value]
    if isinstance(value, dict):
        return {k: _expand(v, variables) for k, v in value.items()}
    return value


def resolve_executable(name: str, where: str) -> str:
    """Path of a console script: as given if it is a path, else next to this Python or on PATH."""
    if os.sep in name:
        if not Path(name).is_file():
            raise BringupFileError(f"{where}: executable '{name}' does not exist")
        return name
    candidate = Path(sys.executable).parent / name
    if candidate.is_file():
        return str(candidate)
    found = shutil.which(name)
    if found is None:
        raise BringupFileError(f"{where}: executable '{name}' is not a console script of this "
                               "venv nor on PATH (is its package installed?)")
    return found


def _node(entry: Any, index: int, path: Path, common: dict[str, Any],
          variables: dict[str, str]) -> NodeSpec:
    where = f"{path}: nodes[{index}]"
    if not isinstance(entry, dict):
        raise BringupFileError(f"{where} must be a mapping, got {type(entry).__name__}")
    unknown = set(entry) - NODE_KEYS
    if unknown:
        raise BringupFileError(f"{where}: unknown keys {sorted(unknown)} "
                               f"(allowed {sorted(NODE_KEYS)})")
    name, exe = entry.get("name"), entry.get("executable")
    if not isinstance(exe, str) or not exe:
        raise BringupFileError(f"{where}: 'executable' (console script name) is required")
    name = name or exe
    if not isinstance(name, str) or not name.replace("_", "").isalnum() or name[0].isdigit():
        raise BringupFileError(f"{where}: name {name!r} is not a valid ROS node name")
    params = entry.get("parameters") or {}
    if not isinstance(params, dict):
        raise BringupFileError(f"{where}.parameters must be a mapping")
    env = entry.get("env") or {}
    if not isinstance(env, dict):
        raise BringupFileError(f"{where}.env must be a mapping")
    env = {str(k): str(_expand(str(v), variables)) for k, v in env.items()}
    variables = {**variables, **env}  # the node's own env entries expand in its values too
    lists = {}
    for key in ("args", "ros_args"):
        value = entry.get(key) or []
        if not isinstance(value, list):
            raise BringupFileError(f"{where}.{key} must be a list of strings")
        lists[key] = tuple(str(v) for v in _expand(value, variables))
    return NodeSpec(
        name=name, executable=resolve_executable(exe, where),
        parameters=_expand({**common, **params}, variables), args=lists["args"],
        ros_args=lists["ros_args"],
        env=env,
        required=bool(entry.get("required", False)))


def load_bringup(path: Path) -> list[NodeSpec]:
    """Read a bringup YAML file; raise BringupFileError naming what is wrong."""
    try:
        doc = yaml.safe_load(Path(path).read_text())
    except OSError as exc:
        raise BringupFileError(f"cannot read bringup file {path}: {exc.strerror}") from exc
    except yaml.YAMLError as exc:
        raise BringupFileError(f"bringup file {path} is not valid YAML: {exc}") from exc
    if not isinstance(doc, dict) or not isinstance(doc.get("nodes"), list) or not doc["nodes"]:
        raise BringupFileError(f"bringup file {path} needs a non-empty 'nodes' list")
    common = doc.get("common_parameters") or {}
    if not isinstance(common, dict):
        raise BringupFileError(f"{path}: common_parameters must be a mapping")
    variables = {"SHIPROUTE_PARAMS_DIR": str(Path(path).resolve().parent)}
    nodes = [_node(e, i, Path(path), common, variables) for i, e in enumerate(doc["nodes"])]
    names = [n.name for n in nodes]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise BringupFileError(f"{path}: duplicate node names {duplicates}")
    return nodes
