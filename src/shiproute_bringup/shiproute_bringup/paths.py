"""Where the repository and workspace are, seen from the (editable) installed package."""

from __future__ import annotations

import os
from pathlib import Path


def repo_root() -> Path:
    """The repository root: $SHIPROUTE_REPO, else the first parent holding ros2_ws/ and src/."""
    env = os.environ.get("SHIPROUTE_REPO")
    if env:
        return Path(env).resolve()
    for parent in Path(__file__).resolve().parents:
        if (parent / "ros2_ws").is_dir() and (parent / "src").is_dir():
            return parent
    raise FileNotFoundError(f"no repository root (ros2_ws/ and src/) above {__file__}; "
                            "set SHIPROUTE_REPO")


def default_params_file() -> Path:
    """The bundled bringup file ``ros2_ws/params/demo.yaml``."""
    return repo_root() / "ros2_ws" / "params" / "demo.yaml"
