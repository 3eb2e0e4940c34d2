from pathlib import Path

import numpy as np
import pytest

from amiro.activity.ntu import (
    Body,
    SkeletonSequence,
    action_id,
    format_skeleton,
    parse_skeleton,
    read_skeleton_file,
    write_skeleton_file,
)
from amiro.activity.skeleton import NUM_JOINTS
from amiro.core.config import ConfigError


def _sequence() -> SkeletonSequence:
    rng = np.random.default_rng(0)
    a = rng.normal(size=(4, NUM_JOINTS, 3))
    b = rng.normal(size=(4, NUM_JOINTS, 3))
    b_present = np.array([False, True, True, False])
    b[~b_present] = np.nan
    a[2, 5] = np.nan
    return SkeletonSequence(
        4, [Body("72057594037931101", a, np.ones(4, bool)), Body("7", b, b_present)]
    )


def test_write_then_read_round_trips(tmp_path: Path) -> None:
    seq = _sequence()
    path = tmp_path / "S001C002P003R002A001.skeleton"
    write_skeleton_file(path, seq)
    back = read_skeleton_file(path)
    assert back.summary() == {
        "frames": 4,
        "bodies": [{"id": "72057594037931101", "frames": 4}, {"id": "7", "frames": 2}],
        "joints": 25,
    }
    np.testing.assert_allclose(back.bodies[1].joints[1], seq.bodies[1].joints[1], atol=1e-6)
    assert back.main_body().id == "72057594037931101"
    assert action_id(path) == 1


def test_reads_the_documented_text_layout() -> None:
    joint = "0.1 0.2 3.0 250 200 1000 500 0.9 0 0.4 0 2"
    text = "1\n1\n123 0 1 1 1 1 0 0.1 0.2 2\n25\n" + "\n".join([joint] * 25) + "\n"
    seq = parse_skeleton(text)
    assert seq.frames == 1 and seq.bodies[0].id == "123"
    np.testing.assert_allclose(seq.bodies[0].joints[0, 24], [0.1, 0.2, 3.0])


@pytest.mark.parametrize(
    "text", ["", "2\n1\n1 0 0 0 0 0 0 0 0 2\n25\n", "1\n1\n1 0\n24\n", "x\n", "1\n1\n1\n25\n1 2\n"]
)
def test_malformed_files_raise_one_line_errors(text: str) -> None:
    with pytest.raises(ConfigError) as err:
        parse_skeleton(text, "bad.skeleton")
    assert "\n" not in str(err.value) and "bad.skeleton" in str(err.value)


def test_formatted_text_marks_unseen_joints_untracked() -> None:
    lines = format_skeleton(_sequence()).splitlines()
    joint_lines = [line for line in lines if len(line.split()) == 12]
    assert sum(line.endswith(" 0") for line in joint_lines) == 1
