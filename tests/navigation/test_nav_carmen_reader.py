"""The CARMEN reader on hand-written log snippets: each laser format, gmapping's re-anchored
odometry, and the file order as time base when the stamps cannot be trusted."""

from __future__ import annotations

import gzip
import logging
import math
from pathlib import Path

import numpy as np
import pytest

from amiro.navigation.carmen import flaser_angles, read_carmen

RANGES = "1.0 2.0 3.0"


def _flaser(x: float, y: float, th: float, stamp: str) -> str:
    pose = f"{x} {y} {th}"
    return f"FLASER 3 {RANGES} {pose} {pose} {stamp} host {stamp}"


def _odom(x: float, y: float, th: float, stamp: str) -> str:
    return f"ODOM {x} {y} {th} 0 0 0 {stamp} host {stamp}"


def _write(tmp_path: Path, lines: list[str], name: str = "a.log") -> Path:
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_gmapping_reanchoring_is_skipped_and_raw_odometry_recovered(tmp_path: Path) -> None:
    # the robot really drives 1 m straight per scan; gmapping corrects each scan 0.1 m
    # sideways and re-anchors the odometry there (the ODOM line right after the scan)
    lines = [
        _odom(0, 0, 0, "1.0"),
        _flaser(0, 0, 0, "1.0"),
        _odom(0, 0, 0, "0"),
        _odom(0.5, 0, 0, "1.5"),
        _odom(1.0, 0, 0, "2.0"),
        _flaser(1.0, 0.1, 0, "2.0"),
        _odom(1.0, 0.1, 0, "0"),
        _odom(2.0, 0.1, 0, "3.0"),
        _flaser(2.0, 0.2, 0, "3.0"),
    ]
    scans = read_carmen(_write(tmp_path, lines))
    assert [s.odom.x for s in scans] == pytest.approx([0.0, 1.0, 2.0])
    assert [s.odom.y for s in scans] == pytest.approx([0.0, 0.0, 0.0])
    assert [s.reference.y for s in scans if s.reference] == pytest.approx([0.0, 0.1, 0.2])
    assert all(s.timed for s in scans)
    assert [s.timestamp for s in scans] == [1.0, 2.0, 3.0]


def test_a_turn_is_chained_in_the_robot_frame(tmp_path: Path) -> None:
    # after a re-anchoring with a different heading the increments are rotated with it
    lines = [
        _odom(0, 0, 0, "1.0"),
        _flaser(0, 0, 0, "1.0"),
        _odom(0, 0, math.pi / 2, "0"),  # not equal to the scan: a real motion (a turn)
        _flaser(5, 5, 0, "2.0"),
        _odom(5, 5, 0, "0"),
        _odom(6, 5, 0, "3.0"),
        _flaser(6, 5, 0, "3.0"),
    ]
    scans = read_carmen(_write(tmp_path, lines))
    assert scans[1].odom.theta == pytest.approx(math.pi / 2)
    # 1 m forward after the turn goes along +y in the odometry frame
    assert (scans[2].odom.x, scans[2].odom.y) == pytest.approx((0.0, 1.0))


def test_unsorted_stamps_fall_back_to_file_order_with_one_warning(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    lines = [
        _odom(0, 0, 0, "5.0"),
        _flaser(0, 0, 0, "5.0"),
        _odom(1, 0, 0, "2.0"),  # clock went backwards: a sorted search would pick odom 0
        _flaser(1, 0, 0, "2.0"),
        _odom(2, 0, 0, "9.0"),
        _flaser(2, 0, 0, "1.0"),
    ]
    with caplog.at_level(logging.WARNING):
        scans = read_carmen(_write(tmp_path, lines))
    assert [s.odom.x for s in scans] == pytest.approx([0.0, 1.0, 2.0])
    assert [s.timestamp for s in scans] == [0.0, 1.0, 2.0]
    assert not any(s.timed for s in scans)
    assert len([r for r in caplog.records if "file order" in r.message]) == 1


def test_coarse_printed_stamps_are_not_trusted(tmp_path: Path) -> None:
    # %g stamps: every scan of these ten seconds prints as 1.13486e+09
    lines = []
    for k in range(3):
        lines += [_odom(k, 0, 0, "1.13486e+09"), _flaser(k, 0, 0, "1.13486e+09")]
    scans = read_carmen(_write(tmp_path, lines))
    assert [s.odom.x for s in scans] == pytest.approx([0.0, 1.0, 2.0])
    assert not scans[0].timed


def test_odometry_is_interpolated_at_the_scan_stamp(tmp_path: Path) -> None:
    lines = [
        _odom(0, 0, 0, "10.0"),
        _flaser(0, 0, 0, "10.0"),
        _odom(1, 0, 0, "11.0"),
        _flaser(9, 9, 0, "11.5"),  # halfway to the next ODOM
        _odom(2, 0, 0, "12.0"),
    ]
    scans = read_carmen(_write(tmp_path, lines))
    assert scans[1].odom.x == pytest.approx(1.5)


def test_rawlaser_and_robotlaser_carry_their_beam_geometry(tmp_path: Path) -> None:
    raw = f"RAWLASER1 0 -1.5 3.0 1.5 8.0 0.01 0 3 {RANGES} 0 7.0 host 7.0"
    robot = (
        f"ROBOTLASER1 0 -1.0 2.0 1.0 8.0 0.01 0 3 {RANGES} 2 0.5 0.5 "
        "0.1 0 0 0.3 0.4 0.5 0 0 0 0 0 8.0 host 8.0"
    )
    lines = [_odom(0, 0, 0, "6.5"), raw, _odom(1, 0, 0, "7.5"), robot]
    scans = read_carmen(_write(tmp_path, lines))
    assert scans[0].reference is None and scans[0].odom.x == pytest.approx(0.5)
    assert list(scans[0].angles()) == pytest.approx([-1.5, 0.0, 1.5])
    assert list(scans[1].angles()) == pytest.approx([-1.0, 0.0, 1.0])
    assert scans[1].reference is not None
    assert (scans[1].reference.x, scans[1].reference.theta) == pytest.approx((0.3, 0.5))
    assert list(scans[1].ranges) == [1.0, 2.0, 3.0]


def test_without_odom_lines_the_laser_odom_fields_are_used(tmp_path: Path) -> None:
    line = f"FLASER 3 {RANGES} 1 2 0.3 4 5 0.6 1.0 host 1.0"
    path = tmp_path / "b.log.gz"
    with gzip.open(path, "wt", encoding="utf-8") as fh:
        fh.write(line + "\n")
    (scan,) = read_carmen(path)
    assert (scan.odom.x, scan.odom.y, scan.odom.theta) == pytest.approx((4, 5, 0.6))
    assert scan.reference is not None and scan.reference.x == 1.0
    assert list(scan.angles()) == pytest.approx([-math.pi / 2, 0.0, math.pi / 2])


def test_flaser_beams_follow_carmens_geometry_for_the_beam_count() -> None:
    # a SICK's 180 or 360 beams start at -90 degrees and stop one step short of +90
    for n, step in ((180, 1.0), (181, 1.0), (360, 0.5), (361, 0.5)):
        angles = np.degrees(flaser_angles(n))
        assert angles[0] == pytest.approx(-90.0)
        assert np.diff(angles) == pytest.approx(np.full(n - 1, step))
    assert np.degrees(flaser_angles(5)) == pytest.approx([-90, -45, 0, 45, 90])


def test_a_log_of_reanchoring_lines_only_carries_no_odometry(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    # Orebro: each scan followed only by gmapping's re-anchoring to its own pose
    lines = [_odom(0, 0, 0, "0.5")]
    for k in range(12):
        lines += [_flaser(0.5 * k, 0, 0, f"{k + 1}.0"), _odom(0.5 * k, 0, 0, f"{k + 1}.0")]
    with caplog.at_level(logging.WARNING):
        scans = read_carmen(_write(tmp_path, lines))
    assert not any(s.odometry for s in scans)
    assert any("no odometry" in r.message for r in caplog.records)
    # one real increment per scan is odometry
    moving = [_odom(0, 0, 0, "0.5")]
    for k in range(12):
        moving += [_odom(0.5 * k, 0, 0, f"{k + 0.9}"), _flaser(0.5 * k, 0, 0, f"{k + 1}.0")]
    assert all(s.odometry for s in read_carmen(_write(tmp_path, moving, "b.log")))
