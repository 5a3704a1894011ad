"""The `shiproute` dispatcher, `bench` dispatch, `test` runner and `echo` subcommand."""

from __future__ import annotations

import sys
import uuid

import pytest
from shiproute_bringup.dispatch import Command, discover, dispatch
from shiproute_bringup.msgdict import message_class, plain_equal, to_plain
from shiproute_bringup.rosproc import RosProcess, random_bench_domain_id, random_domain_id

from shiproute_bringup import cli, testrun


def test_usage_errors_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    """Unknown and missing subcommands print usage to stderr and return 2."""
    assert cli.main(["nosuchcmd"]) == 2
    err = capsys.readouterr().err
    assert "unknown subcommand 'nosuchcmd'" in err and "env" in err
    assert cli.main([]) == 2
    assert "missing subcommand" in capsys.readouterr().err
    assert cli.main(["bench"]) == 2
    assert "missing benchmark" in capsys.readouterr().err


def test_help_lists_commands_with_docstring_lines(capsys: pytest.CaptureFixture[str]) -> None:
    """--help lists every registered subcommand with its module's first docstring line."""
    assert cli.main(["--help"]) == 0
    out = capsys.readouterr().out
    for name in ("env", "bringup", "echo", "test", "bench"):
        assert name in discover("shiproute.commands")
        assert f"  {name}" in out
    assert "Print the environment" in out


def test_broken_module_is_reported_not_fatal(capsys: pytest.CaptureFixture[str],
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    """A command whose module cannot be imported shows as unavailable; running it returns 1."""
    broken = Command("broken", "shiproute_no_such_module_xyz:main")
    good = Command("env", "shiproute_bringup.env:main")
    monkeypatch.setattr("shiproute_bringup.dispatch.discover",
                        lambda group: {"broken": broken, "env": good})
    assert dispatch("shiproute", "x", ["--help"]) == 0
    out = capsys.readouterr().out
    assert "broken  (unavailable: ModuleNotFoundError" in out
    assert "env     Print the environment" in out
    assert dispatch("shiproute", "x", ["broken"]) == 1
    assert "'broken' is unavailable" in capsys.readouterr().err


def test_dispatch_runs_target_with_remaining_args(monkeypatch: pytest.MonkeyPatch) -> None:
    """The command's main receives argv after the command name; its return is the exit code."""
    seen: list[list[str]] = []
    module = type(sys)("shiproute_fake_cmd")
    module.main = lambda argv: seen.append(argv) or 7  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "shiproute_fake_cmd", module)
    monkeypatch.setattr("shiproute_bringup.dispatch.discover",
                        lambda group: {"fake": Command("fake", "shiproute_fake_cmd:main")})
    assert dispatch("shiproute", "x", ["fake", "-a", "b"]) == 7
    assert seen == [["-a", "b"]]


def test_testrun_adds_timeout_unless_given() -> None:
    """`shiproute test` passes a per-test timeout to pytest unless the caller set one."""
    assert any(a.startswith("--timeout=") for a in testrun.pytest_command(["-k", "x"]))
    assert testrun.pytest_command(["--timeout=5"]).count("--timeout=5") == 1


def test_testrun_parallel_only_for_the_whole_suite() -> None:
    """The whole suite runs on xdist workers; a run naming files or setting -n stays as asked."""
    whole = testrun.pytest_command(["-q", "-k", "plan"])
    assert "-n" in whole and "loadfile" in whole
    assert "-n" not in testrun.pytest_command(["-q", "tests/test_tree_rules.py"])
    assert testrun.pytest_command(["-n", "3"]).count("-n") == 1
    assert "-n" not in testrun.pytest_command(["-p", "no:xdist"])


def test_domain_ids_of_parallel_workers_never_meet(monkeypatch: pytest.MonkeyPatch) -> None:
    """Worker i of n draws ROS domain ids = i (mod n) within 0..101, so no two workers share one."""
    monkeypatch.setenv("PYTEST_XDIST_WORKER_COUNT", "3")
    for index in range(3):
        monkeypatch.setenv("PYTEST_XDIST_WORKER", f"gw{index}")
        ids = {random_domain_id() for _ in range(300)}
        assert all(i % 3 == index and 0 <= i <= 101 for i in ids) and len(ids) > 20


def test_msgdict_nan_aware_equality() -> None:
    """plain_equal: NaN equals NaN but no number; to_plain truncates arrays on request."""
    assert plain_equal({"a": [float("nan"), 1.0]}, {"a": [float("nan"), 1.0]})
    assert not plain_equal({"a": [float("nan")]}, {"a": [0.0]})
    assert not plain_equal([1.0, 2.0], [1.0])
    assert to_plain(list(range(40)), max_array=3) == [0, 1, 2, "... (40 values)"]


def test_bench_domain_ids_never_meet_the_tests_ids(monkeypatch: pytest.MonkeyPatch) -> None:
    """Benchmarks draw ROS domain ids from 215..232, tests from 0..101 (any worker split)."""
    monkeypatch.delenv("PYTEST_XDIST_WORKER", raising=False)
    monkeypatch.delenv("PYTEST_XDIST_WORKER_COUNT", raising=False)
    bench = {random_bench_domain_id() for _ in range(500)}
    tests = {random_domain_id() for _ in range(500)}
    assert bench <= set(range(215, 233)) and len(bench) > 10
    assert tests <= set(range(0, 102)) and not bench & tests


@pytest.mark.ros
@pytest.mark.parametrize("draw", [random_domain_id, random_bench_domain_id],
                         ids=["test-domain", "bench-domain"])
def test_echo_prints_messages_from_another_process(draw) -> None:
    """`shiproute echo` discovers the type of a topic and prints N messages as YAML (on a
    tests' domain and on a benchmarks' one: both ranges work with the DDS in use)."""
    pytest.importorskip("shiproute_msgs.msg")
    assert message_class("shiproute_msgs/msg/ShipState").__name__ == "ShipState"
    dom = draw()
    topic = f"/echo_test_{uuid.uuid4().hex[:8]}"  # no other test's publisher can share it
    talker_code = (
        "import math, sys, rclpy\nfrom rclpy.node import Node\n"
        "from shiproute_msgs.msg import ShipState\n"
        "rclpy.init(); n = Node('talker'); p = n.create_publisher(ShipState, sys.argv[1], 10)\n"
        "n.create_timer(0.1, lambda: p.publish(ShipState(mmsi=440123000, sog_kn=math.nan)))\n"
        "try:\n    rclpy.spin(n)\nexcept BaseException:\n    pass\n")
    with RosProcess.python(talker_code, topic, domain_id=dom, name="talker"), \
         RosProcess.script("shiproute", "echo", topic, "--count", "2", "--timeout", "20",
                           domain_id=dom, name="echo", merge_stderr=False) as echo:
        assert echo.wait(30) == 0, echo.output
    out = echo.output
    assert out.count("mmsi: 440123000") == 2 and "sog_kn: .nan" in out
