"""Commands within the profile: base type, speed and acceleration limits, head range."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import pytest

from amiro.core.config import ConfigError
from amiro.core.messages import Twist
from amiro.robot.limits import Planar, VelocityLimiter, clamp_head
from amiro.robot.profile import load_profile, shipped_profiles


def test_shipped_profiles_load_with_their_base_types() -> None:
    assert set(shipped_profiles()) >= {"pepper", "generic_diff", "generic_omni"}
    assert load_profile("pepper").base == "omnidirectional"
    assert load_profile("pepper").topics.scan == "/laser"
    assert load_profile("generic_diff").base == "differential"


def test_unknown_or_bad_profiles_are_one_line_errors(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="unknown robot profile 'nao'"):
        load_profile("nao")
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\nbase: tracked\nlimits: {max_linear: 1}\n", encoding="utf-8")
    with pytest.raises(ConfigError, match=r"bad\.yaml: base"):
        load_profile(bad)


def test_a_differential_base_never_gets_a_lateral_velocity() -> None:
    limiter = VelocityLimiter("differential", load_profile("generic_diff").limits)
    target = limiter.target(Twist.planar(0.1, 0.3, 0.2))
    assert target == Planar(0.1, 0.0, 0.2)
    assert limiter.clamped == 1


def test_speeds_are_clamped_on_the_norm_for_an_omni_base() -> None:
    limits = load_profile("pepper").limits
    limiter = VelocityLimiter("omnidirectional", limits)
    target = limiter.target(Twist.planar(3.0, 4.0, -5.0))
    assert math.hypot(target.vx, target.vy) == pytest.approx(limits.max_linear)
    assert target.vx / target.vy == pytest.approx(0.75)  # direction kept
    assert target.wz == -limits.max_angular
    assert limiter.target(Twist.planar(float("nan"), 0.1, float("inf"))) == Planar(0.0, 0.1, 0.0)


def test_commands_ramp_within_the_accelerations() -> None:
    limits = load_profile("pepper").limits
    limiter = VelocityLimiter("omnidirectional", limits)
    target = limiter.target(Twist.planar(0.35, 0.0, 1.0))
    steps = [limiter.step(target, 0.1) for _ in range(20)]
    assert steps[0].vx == pytest.approx(limits.max_linear_accel * 0.1)
    assert steps[0].wz == pytest.approx(limits.max_angular_accel * 0.1)
    deltas = [b.vx - a.vx for a, b in itertools.pairwise(steps)]
    assert max(deltas) <= limits.max_linear_accel * 0.1 + 1e-12
    assert steps[-1] == target  # reached once the ramp is over


def test_head_targets_stay_within_the_joint_ranges() -> None:
    head = load_profile("pepper").head
    assert head is not None
    got = clamp_head(head, {"HeadYaw": 3.0, "HeadPitch": -2.0, "LElbowRoll": 0.3})
    assert got == {"HeadYaw": head.yaw_limits[1], "HeadPitch": head.pitch_limits[0]}
    assert clamp_head(head, {"HeadPitch": float("nan")}) == {}
