"""`bench world --lanes`: the bundled hold-out set is disjoint from the public lanes, and a bad
lane file is a user's mistake (exit 2, the file named), not a traceback."""

from __future__ import annotations

import pytest
from shiproute_planner.experiments.bench import world


def test_holdout_set_shares_no_voyage_with_the_public_lanes():
    public = {(r["from"], r["to"]) for r in world._lanes("world")}
    holdout = world._lanes("holdout")
    assert len(world._lanes("world")) == 20  # the public set of shared/benchmarks
    assert holdout and not public & {(r["from"], r["to"]) for r in holdout}


@pytest.mark.parametrize("content", [None, "a,b\n1,2\n", ""])
def test_bad_lane_file_exits_2_naming_it(tmp_path, capsys, content):
    path = tmp_path / "lanes.csv"
    if content is not None:
        path.write_text(content)
    with pytest.raises(SystemExit) as exc:
        world.main(["--lanes", str(path)])
    assert exc.value.code == 2
    assert str(path) in capsys.readouterr().err
