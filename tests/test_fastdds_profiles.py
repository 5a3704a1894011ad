"""The Fast DDS profiles the planner and display processes write (through
`shiproute_core.fastdds`): a well-formed document that Fast DDS is pointed at and forgets, with
rmw_fastrtps' defaults for every other reader and the process's settings for the slice reader;
an integrator's own XML is left alone."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path

import pytest
from shiproute_core.fastdds import USER_SETTINGS, forget_profile
from shiproute_display.ros.dds_profile import SLICE_WINDOW, use_windowed_slice_reader
from shiproute_planner.ros.dds_profile import use_dynamic_slice_buffers

from shiproute_core import topics

NS = "{http://www.eprosima.com}"
#: process -> its profile writer
WRITERS: dict[str, Callable[[str], Path | None]] = {
    "planner": use_dynamic_slice_buffers, "display": use_windowed_slice_reader}


@pytest.fixture(params=sorted(WRITERS))
def readers(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch
            ) -> tuple[str, dict[str, ET.Element]]:
    """(process, reader profiles by name) of the profile the process writes, checked to be
    pointed at while it exists and forgotten with its file."""
    for name in USER_SETTINGS:
        monkeypatch.delenv(name, raising=False)
    path = WRITERS[request.param](topics.FORECAST_SLICES)
    assert path is not None and os.environ["FASTDDS_DEFAULT_PROFILES_FILE"] == str(path)
    assert os.environ["RMW_FASTRTPS_USE_QOS_FROM_XML"] == "1"
    root = ET.fromstring(path.read_text().encode())  # Fast DDS rejects a malformed file whole
    forget_profile(path)
    assert not path.exists()
    assert not {"FASTDDS_DEFAULT_PROFILES_FILE", "RMW_FASTRTPS_USE_QOS_FROM_XML"} & set(os.environ)
    return request.param, {r.get("profile_name", ""): r for r in root.iter(f"{NS}data_reader")}


def _text(element: ET.Element, path: str) -> str:
    """Text of the element at `path` below `element` (the test fails when it is missing)."""
    found = element.find("/".join(f"{NS}{part}" for part in path.split("/")))
    assert found is not None and found.text is not None, path
    return found.text


def test_profile_frees_slices_and_keeps_defaults_elsewhere(
        readers: tuple[str, dict[str, ET.Element]]) -> None:
    process, profiles = readers
    default_name = f"shiproute {process} readers"
    assert set(profiles) == {topics.FORECAST_SLICES, default_name}
    slices = profiles[topics.FORECAST_SLICES]
    assert _text(slices, "historyMemoryPolicy") == "DYNAMIC"
    default = profiles[default_name]
    assert default.get("is_default_profile") == "true"
    assert _text(default, "historyMemoryPolicy") == "PREALLOCATED_WITH_REALLOC"
    if process == "display":  # a keep-all reader holding at most SLICE_WINDOW slices
        assert _text(slices, "topic/historyQos/kind") == "KEEP_ALL"
        assert int(_text(slices, "topic/resourceLimitsQos/max_samples")) == SLICE_WINDOW


@pytest.mark.parametrize("process", sorted(WRITERS))
@pytest.mark.parametrize("setting", ["FASTDDS_DEFAULT_PROFILES_FILE",
                                     "FASTRTPS_DEFAULT_PROFILES_FILE"])
def test_integrator_xml_is_left_alone(process: str, setting: str, tmp_path: Path,
                                      monkeypatch: pytest.MonkeyPatch) -> None:
    for name in USER_SETTINGS:
        monkeypatch.delenv(name, raising=False)
    own = tmp_path / "own.xml"
    monkeypatch.setenv(setting, str(own))
    assert WRITERS[process](topics.FORECAST_SLICES) is None
    assert os.environ[setting] == str(own)
    other = ({"FASTDDS_DEFAULT_PROFILES_FILE", "FASTRTPS_DEFAULT_PROFILES_FILE"} - {setting}).pop()
    assert other not in os.environ
