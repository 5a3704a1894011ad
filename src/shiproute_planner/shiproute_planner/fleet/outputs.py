"""Per-voyage output folders, published atomically: a voyage's files are written into a
temporary folder and renamed to `voyages/<id>--<key>` in one step, so a re-run task (a lost
worker's voyage planned again) can never leave two outputs or half of one; the first complete
one wins and a later duplicate is discarded."""

from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import uuid
from collections.abc import Callable
from pathlib import Path
from typing import Any

RESULT_FILE = "result.json"  # written last inside the folder: the voyage's fleet record
VOYAGES_DIR = "voyages"


def safe_name(voyage_id: str) -> str:
    """A voyage id as a file-name part."""
    return re.sub(r"[^A-Za-z0-9@._-]+", "_", voyage_id).strip("_") or "voyage"


def voyage_dir(out_root: str | Path, voyage_id: str, key: str) -> Path:
    """Where the outputs of voyage `voyage_id` planned from inputs `key` live."""
    return Path(out_root) / VOYAGES_DIR / f"{safe_name(voyage_id)}--{key}"


def existing_result(out_root: str | Path, voyage_id: str, key: str) -> dict[str, Any] | None:
    """The stored record of a voyage already planned from the same inputs, else None."""
    path = voyage_dir(out_root, voyage_id, key) / RESULT_FILE
    try:
        rec = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return rec if isinstance(rec, dict) and rec.get("key") == key else None


def publish(out_root: str | Path, voyage_id: str, key: str,
            write: Callable[[Path], dict[str, Any]]) -> tuple[dict[str, Any], bool]:
    """Run `write(tmp_dir) -> record`, store the record and rename the folder into place.

    Returns (record, True) when this call published the outputs, or (stored record, False)
    when another run of the same voyage had already published them."""
    final = voyage_dir(out_root, voyage_id, key)
    final.parent.mkdir(parents=True, exist_ok=True)
    tmp = final.parent / f".tmp-{final.name}-{uuid.uuid4().hex[:8]}"
    tmp.mkdir()
    try:
        record = write(tmp)
        record = {**record, "key": key, "out_dir": str(final)}
        (tmp / RESULT_FILE).write_text(json.dumps(record, indent=1, default=str))
        try:
            os.rename(tmp, final)  # atomic; fails when the folder exists and is not empty
        except OSError:
            stored = existing_result(out_root, voyage_id, key)
            if stored is None:
                raise
            return stored, False
        return record, True
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)


def remove_stale(out_root: str | Path, voyage_id: str, key: str) -> list[Path]:
    """Delete outputs of `voyage_id` made from other inputs (and abandoned temp folders), so
    each voyage keeps exactly one output folder."""
    root = Path(out_root) / VOYAGES_DIR
    name = safe_name(voyage_id)
    keep = voyage_dir(out_root, voyage_id, key).name
    gone: list[Path] = []
    if not root.is_dir():
        return gone
    for p in root.iterdir():
        base = p.name[len(".tmp-"):] if p.name.startswith(".tmp-") else p.name
        if base.rsplit("--", 1)[0] == name and p.name != keep:
            with contextlib.suppress(OSError):
                shutil.rmtree(p)
                gone.append(p)
    return gone
