"""People on ROS4HRI (REP-155): what amiro's perception tracks, as HRI stacks expect it.

:class:`HriPublisher` turns each :class:`~amiro.core.messages.People` on the bus (the
tracker's confirmed tracks, map frame) into ``/humans/bodies/tracked`` and
``/humans/persons/tracked`` (``hri_msgs/IdsList``), per person ``/humans/persons/<id>/``
``face_id``, ``body_id``, ``location_confidence`` and ``name`` (the recognised name; not in
REP-155, an amiro addition), and the TF frames ``person_<id>`` and ``body_<id>`` under
``map``.  A person's id is her recognised name when there is one (amiro knows its household
by name), else the track's id, which is also the body's and the face's id.

:class:`HriListener` is the other way: ROS4HRI from another HRI stack back to People on
the bus (a person's position from her ``person_<id>`` frame), so amiro can use it.
"""

from __future__ import annotations

import re
from typing import Any

from amiro.core import names
from amiro.core.messages import Header, People, Person, Point
from amiro.core.node import Node
from amiro.ros2.context import RosContext
from amiro.ros2.convert import ros_time, seconds

IDS = "hri_msgs/msg/IdsList"
TF = "tf2_msgs/msg/TFMessage"
BODIES_TRACKED = "/humans/bodies/tracked"
PERSONS_TRACKED = "/humans/persons/tracked"
PERSON_TOPIC = "/humans/persons/{id}/{field}"
FIELDS = {
    "face_id": "std_msgs/msg/String",
    "body_id": "std_msgs/msg/String",
    "name": "std_msgs/msg/String",
    "location_confidence": "std_msgs/msg/Float32",
}


def hri_id(text: str) -> str:
    """An id usable in topic and frame names (REP-155 ids are such tokens)."""
    return re.sub(r"[^a-z0-9_]", "_", text.lower()) or "unknown"


def person_id(person: Person) -> str:
    return hri_id(person.name or person.id)


class HriPublisher(Node):
    """Bus ``/amiro/people`` to ROS4HRI topics and frames (see the module's docstring)."""

    def __init__(self, ros: RosContext, frame: str = "map") -> None:
        super().__init__("ros4hri")
        self.ros = ros
        self.frame = frame
        self._per_person: dict[str, dict[str, Any]] = {}
        self.published = 0

    def on_start(self) -> None:
        self._bodies = self.ros.publisher(IDS, BODIES_TRACKED, depth=1)
        self._persons = self.ros.publisher(IDS, PERSONS_TRACKED, depth=1)
        self._tf = self.ros.publisher(TF, names.TF, depth=100)
        self.create_subscription(names.PEOPLE, People, self._on_people, depth=10)

    def _publishers(self, pid: str) -> dict[str, Any]:
        pubs = self._per_person.get(pid)
        if pubs is None:  # latched: a late subscriber still learns who this person is
            pubs = {
                field: self.ros.publisher(t, PERSON_TOPIC.format(id=pid, field=field), 1, True)
                for field, t in FIELDS.items()
            }
            self._per_person[pid] = pubs
        return pubs

    def _on_people(self, msg: People) -> None:
        types, stamp = self.ros.types, ros_time(self.ros.types, msg.header.stamp)
        header = types.make("std_msgs/msg/Header", stamp=stamp, frame_id=self.frame)
        bodies = [hri_id(p.id) for p in msg.people]
        persons = [person_id(p) for p in msg.people]
        self._bodies.publish(types.make(IDS, header=header, ids=bodies))
        self._persons.publish(types.make(IDS, header=header, ids=persons))
        transforms = []
        for p, body, pid in zip(msg.people, bodies, persons, strict=True):
            pubs = self._publishers(pid)
            pubs["face_id"].publish(types.make(FIELDS["face_id"], data=body))
            pubs["body_id"].publish(types.make(FIELDS["body_id"], data=body))
            pubs["name"].publish(types.make(FIELDS["name"], data=p.name or ""))
            confidence = float(p.confidence)
            pubs["location_confidence"].publish(
                types.make(FIELDS["location_confidence"], data=confidence)
            )
            for child in (f"person_{pid}", f"body_{body}"):
                transforms.append(self._transform(header, child, p.position))
        if transforms:
            self._tf.publish(types.make(TF, transforms=transforms))
        self.published += 1

    def _transform(self, header: Any, child: str, at: Point) -> Any:
        types = self.ros.types
        translation = types.make("geometry_msgs/msg/Vector3", x=at.x, y=at.y, z=at.z)
        rotation = types.make("geometry_msgs/msg/Quaternion", x=0.0, y=0.0, z=0.0, w=1.0)
        return types.make(
            "geometry_msgs/msg/TransformStamped",
            header=header,
            child_frame_id=child,
            transform=types.make(
                "geometry_msgs/msg/Transform", translation=translation, rotation=rotation
            ),
        )


class HriListener(Node):
    """ROS4HRI from another stack to ``People`` on the bus ``topic``: the persons tracked,
    each where her ``person_<id>`` frame is (map frame), with her name and confidence."""

    def __init__(self, ros: RosContext, topic: str = names.PEOPLE, period_s: float = 0.5) -> None:
        super().__init__("ros4hri_listener")
        self.ros = ros
        self.topic = topic
        self.period_s = period_s
        self.tracked: list[str] = []
        self.positions: dict[str, Point] = {}
        self.names: dict[str, str] = {}
        self.confidence: dict[str, float] = {}
        self.stamp = 0.0

    def on_start(self) -> None:
        self.pub = self.create_publisher(self.topic, People)
        self.ros.subscribe(IDS, PERSONS_TRACKED, self._on_tracked, depth=1)
        self.ros.subscribe(TF, names.TF, self._on_tf, depth=100)
        self.create_timer(self.period_s, self._publish)

    def _on_tracked(self, msg: Any) -> None:
        self.tracked = [str(i) for i in msg.ids]
        self.stamp = seconds(msg.header.stamp)
        for pid in self.tracked:
            if pid not in self.names:
                self.names[pid] = ""
                self._listen(pid)

    def _listen(self, pid: str) -> None:
        def on_name(msg: Any) -> None:
            self.names[pid] = str(msg.data)

        def on_confidence(msg: Any) -> None:
            self.confidence[pid] = float(msg.data)

        topic = PERSON_TOPIC.format(id=pid, field="name")
        self.ros.subscribe(FIELDS["name"], topic, on_name, 1, True)
        topic = PERSON_TOPIC.format(id=pid, field="location_confidence")
        self.ros.subscribe(FIELDS["location_confidence"], topic, on_confidence, 1, True)

    def _on_tf(self, msg: Any) -> None:
        for t in msg.transforms:
            child = str(t.child_frame_id)
            if child.startswith("person_"):
                v = t.transform.translation
                self.positions[child.removeprefix("person_")] = Point(v.x, v.y, v.z)

    def _publish(self) -> None:
        people = tuple(
            Person(
                pid, self.names.get(pid) or None, self.positions[pid], self.confidence.get(pid, 1.0)
            )
            for pid in self.tracked
            if pid in self.positions
        )
        self.pub.publish(People(Header(self.stamp, "map"), people))
