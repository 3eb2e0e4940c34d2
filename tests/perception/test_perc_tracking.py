"""Tracks: stable ids, identities kept while the face is away, duplicates and blips."""

from __future__ import annotations

from amiro.core.messages import Point
from amiro.perception.tracking import Measurement, PeopleTracker


def test_identity_sticks_to_the_track() -> None:
    tracker = PeopleTracker()
    (first,) = tracker.update(0.0, [Measurement(Point(1.0, 1.0, 0.8), 0.9, "maria")])
    (again,) = tracker.update(0.5, [Measurement(Point(1.1, 1.0, 0.8), 0.9, None)])
    assert again.id == first.id and again.name == "maria" and again.hits == 2
    assert again.position.x == 1.05  # smoothed halfway


def test_two_people_two_tracks_and_duplicates_merge() -> None:
    tracker = PeopleTracker()
    tracks = tracker.update(
        0.0,
        [
            Measurement(Point(1.0, 1.0, 0.8), 0.9),
            Measurement(Point(1.1, 1.05, 0.8), 0.5),  # a duplicate box on the same person
            Measurement(Point(4.0, 1.0, 0.8), 0.9),
        ],
    )
    assert len(tracks) == 2 and len({t.id for t in tracks}) == 2
    assert not any(t.confirmed for t in tracks)  # one frame: maybe false positives
    tracks = tracker.update(0.5, [Measurement(Point(1.0, 1.0, 0.8), 0.9)])
    assert [t.confirmed for t in tracks] == [True]


def test_tracks_are_forgotten() -> None:
    tracker = PeopleTracker()
    (a,) = tracker.update(0.0, [Measurement(Point(1.0, 1.0, 0.8), 0.9)])
    (b,) = tracker.update(10.0, [Measurement(Point(1.0, 1.0, 0.8), 0.9)])
    assert a.id != b.id


def test_conflicting_names_give_no_name() -> None:
    tracker = PeopleTracker()
    tracker.update(0.0, [Measurement(Point(1.0, 1.0, 0.8), 0.9, "maria")])
    (t,) = tracker.update(0.5, [Measurement(Point(1.0, 1.0, 0.8), 0.9, "ion")])
    assert t.name is None
    (t,) = tracker.update(1.0, [Measurement(Point(1.0, 1.0, 0.8), 0.9, "maria")])
    assert t.name == "maria"
