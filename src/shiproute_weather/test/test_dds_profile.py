"""The weather process's Fast DDS profile: the slice writer's history DYNAMIC (payloads sized
per sample), rmw_fastrtps' defaults for every other endpoint, forgotten once read, and an
integrator's own XML left alone."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET

import pytest
from shiproute_core.fastdds import USER_SETTINGS
from shiproute_weather.ros.dds_profile import forget_profile, use_dynamic_slice_writer

from shiproute_core import topics

NS = "{http://www.eprosima.com}"


@pytest.fixture()
def clean_env(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in USER_SETTINGS:
        monkeypatch.delenv(name, raising=False)


def test_slice_writer_is_dynamic_and_the_rest_default(clean_env: None) -> None:
    path = use_dynamic_slice_writer(topics.FORECAST_SLICES)
    assert path is not None and os.environ["FASTDDS_DEFAULT_PROFILES_FILE"] == str(path)
    try:
        root = ET.parse(path).getroot()
        writers = {w.get("profile_name"): w for w in root.iter(f"{NS}data_writer")}
        slices = writers[topics.FORECAST_SLICES]
        assert slices.find(f"{NS}historyMemoryPolicy").text == "DYNAMIC"
        defaults = [w for w in writers.values() if w.get("is_default_profile") == "true"]
        assert len(defaults) == 1
        assert defaults[0].find(f"{NS}historyMemoryPolicy").text == "PREALLOCATED_WITH_REALLOC"
        # no QoS of the slice writer in XML: depth, reliability, durability come from code
        assert slices.find(f"{NS}qos/{NS}durability") is None
        assert slices.find(f"{NS}topic") is None
    finally:
        forget_profile(path)
    assert not path.exists() and "FASTDDS_DEFAULT_PROFILES_FILE" not in os.environ


def test_an_integrators_xml_is_left_alone(clean_env: None,
                                          monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("FASTDDS_DEFAULT_PROFILES_FILE", "/etc/ship/fastdds.xml")
    assert use_dynamic_slice_writer(topics.FORECAST_SLICES) is None
    assert os.environ["FASTDDS_DEFAULT_PROFILES_FILE"] == "/etc/ship/fastdds.xml"
