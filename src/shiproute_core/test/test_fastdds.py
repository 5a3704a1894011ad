"""The shared Fast DDS profile writer: a well-formed document with rmw_fastrtps' defaults for
every other endpoint and the given settings for one reader; the integrator's XML respected."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET

import pytest
from shiproute_core.fastdds import USER_SETTINGS, forget_profile, use_topic_reader_profile

from shiproute_core import topics

NS = "{http://www.eprosima.com}"


@pytest.fixture
def clean_env(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in USER_SETTINGS:
        monkeypatch.delenv(name, raising=False)


def _readers(text: str) -> dict[str, ET.Element]:
    root = ET.fromstring(text.encode())  # Fast DDS rejects the whole file when malformed
    return {r.get("profile_name", ""): r for r in root.iter(f"{NS}data_reader")}


def test_generic_profile_keeps_defaults_and_sets_the_topic_reader(clean_env: None) -> None:
    settings = "      <historyMemoryPolicy>DYNAMIC</historyMemoryPolicy>\n"
    path = use_topic_reader_profile("planner", topics.FORECAST_SLICES, settings)
    assert path is not None and os.environ["RMW_FASTRTPS_USE_QOS_FROM_XML"] == "1"
    readers = _readers(path.read_text())
    forget_profile(path)
    assert not path.exists() and "RMW_FASTRTPS_USE_QOS_FROM_XML" not in os.environ
    assert readers[topics.FORECAST_SLICES].find(f"{NS}historyMemoryPolicy").text == "DYNAMIC"
    assert set(readers) == {topics.FORECAST_SLICES, "shiproute planner readers"}


def test_integrator_xml_is_left_alone(monkeypatch: pytest.MonkeyPatch, tmp_path) -> None:
    own = tmp_path / "own.xml"
    for name in USER_SETTINGS:
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("FASTRTPS_DEFAULT_PROFILES_FILE", str(own))
    assert use_topic_reader_profile("x", "/t", "") is None
    assert "FASTDDS_DEFAULT_PROFILES_FILE" not in os.environ
