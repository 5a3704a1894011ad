"""The display's Fast DDS profile: a keep-all slice reader holding at most SLICE_WINDOW slices."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET

import pytest
from shiproute_core.fastdds import USER_SETTINGS, forget_profile
from shiproute_display.ros.dds_profile import SLICE_WINDOW, use_windowed_slice_reader

from shiproute_core import topics

NS = "{http://www.eprosima.com}"


@pytest.fixture
def clean_env(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in USER_SETTINGS:
        monkeypatch.delenv(name, raising=False)


def _readers(text: str) -> dict[str, ET.Element]:
    root = ET.fromstring(text.encode())  # Fast DDS rejects the whole file when malformed
    return {r.get("profile_name", ""): r for r in root.iter(f"{NS}data_reader")}


def test_display_profile_windows_the_slice_reader(clean_env: None) -> None:
    path = use_windowed_slice_reader(topics.FORECAST_SLICES)
    assert path is not None and os.environ["FASTDDS_DEFAULT_PROFILES_FILE"] == str(path)
    readers = _readers(path.read_text())
    forget_profile(path)
    assert not path.exists() and "FASTDDS_DEFAULT_PROFILES_FILE" not in os.environ
    slice_reader = readers[topics.FORECAST_SLICES]
    assert slice_reader.find(f"{NS}topic/{NS}historyQos/{NS}kind").text == "KEEP_ALL"
    limits = slice_reader.find(f"{NS}topic/{NS}resourceLimitsQos")
    assert int(limits.find(f"{NS}max_samples").text) == SLICE_WINDOW
    assert slice_reader.find(f"{NS}historyMemoryPolicy").text == "DYNAMIC"
    default = readers["shiproute display readers"]
    assert default.get("is_default_profile") == "true"
    assert default.find(f"{NS}historyMemoryPolicy").text == "PREALLOCATED_WITH_REALLOC"
