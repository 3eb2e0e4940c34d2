"""Household objects: furniture from the home, cups and bottles placed on it, found by the
simulator's detector and placed in the map."""

from __future__ import annotations

import math
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from amiro.core.config import ConfigError
from amiro.core.messages import BoundingBox2D, Point
from amiro.core.runtime import Runtime
from amiro.perception.config import PerceptionConfig
from amiro.perception.ports import Frame
from amiro.perception.sim_detector import SimDetector
from amiro.perception.sim_objects import ObjectObservation, household_objects
from amiro.sim.config import SimConfig
from amiro.sim.object_finder import SimObjectFinder
from amiro.sim.simulator import Simulation, build_sim


def living_room_view() -> Simulation:
    """The robot in the living room, looking at the couch, the coffee table and the desk."""
    cfg = SimConfig.model_validate({"start": {"x": 4.5, "y": 1.4, "theta": -0.2}})
    return build_sim(Runtime(seed=1), cfg)


def test_the_home_furniture_and_the_placed_objects() -> None:
    objects = household_objects(living_room_view().world)
    labels = Counter(o.label for o in objects)
    assert labels == {"dining table": 3, "couch": 1, "chair": 1, "bed": 1, "cup": 3, "bottle": 3}
    cup = next(o for o in objects if o.label == "cup")  # on the coffee table (0.45 m high)
    assert cup.lo[2] == pytest.approx(0.45) and cup.hi[2] == pytest.approx(0.55)
    assert cup.centre.x == pytest.approx(7.25) and cup.centre.y == pytest.approx(1.75)


def test_finder_sees_and_places_the_objects_in_view() -> None:
    sim = living_room_view()
    finder = SimObjectFinder(sim, np.random.default_rng(0), PerceptionConfig())
    seen = [s for _ in range(40) for s in finder.look()]
    labels = Counter(s.label for s in seen)
    assert set(labels) == {"cup", "bottle", "couch", "chair", "dining table"}
    assert labels["bed"] == 0  # in the bedroom, behind walls
    truths = {"bottle": Point(6.75, 1.85, 0.575), "chair": Point(8.95, 2.25, 0.45)}
    for s in seen:
        if s.label in truths:
            t = truths[s.label]
            assert math.hypot(s.position.x - t.x, s.position.y - t.y) < 0.25
            assert 0.0 < s.confidence <= 1.0


def observed(label: str, depth: float, size: float = 40.0) -> ObjectObservation:
    return ObjectObservation(label, BoundingBox2D(320, 240, size, size), depth, Point())


def found_share(obj: ObjectObservation, n: int = 1000) -> float:
    det = SimDetector(np.random.default_rng(0))
    frame = Frame(objects=[obj])
    return sum(d.label == obj.label for _ in range(n) for d in det.detect(frame)) / n


def test_recall_by_label_falls_with_distance_and_size() -> None:
    assert found_share(observed("couch", 2.0)) > found_share(observed("cup", 2.0)) + 0.2
    assert found_share(observed("cup", 2.0)) > found_share(observed("cup", 5.0)) + 0.2
    assert found_share(observed("cup", 2.0, size=5.0)) == 0.0
    assert found_share(observed("toaster", 2.0)) == 0.0


def test_bad_objects_files_are_one_line_errors(tmp_path: Path) -> None:
    world = living_room_view().world
    bad = tmp_path / "objects.yaml"
    bad.write_text("homes:\n  apartment:\n    - {label: cup, furniture: piano}\n")
    with pytest.raises(ConfigError, match="cup on unknown furniture 'piano'"):
        household_objects(world, bad)
    bad.write_text("homes:\n  apartment:\n    - {label: vase, furniture: desk}\n")
    with pytest.raises(ConfigError, match=r"homes\.apartment\.0\.label"):
        household_objects(world, bad)
    other = tmp_path / "other.yaml"
    other.write_text("homes:\n  cottage:\n    - {label: cup, furniture: piano}\n")
    assert {o.label for o in household_objects(world, other)} == {
        "dining table",
        "couch",
        "chair",
        "bed",
    }
