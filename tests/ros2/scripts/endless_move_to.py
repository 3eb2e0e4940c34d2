"""An amiro process serving /amiro/navigation/move_to (amiro_interfaces/action/MoveTo) with a
stand-in MoveTo that never arrives: a feedback every 0.1 s until the process is killed.

Usage: endless_move_to.py DOMAIN_ID.  Prints "serving" once the action server is up.
"""

import sys

from amiro.core import names
from amiro.core.bus import ActionServer
from amiro.core.clock import SimClock
from amiro.core.messages import Pose2D
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.deploy.codecs import MoveToCodec
from amiro.navigation.move_to import MoveToFeedback
from amiro.ros2.actions import ActionExporter
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext


class Endless(Node, ActionServer):
    def __init__(self):
        super().__init__("endless")
        self.handles = []

    def on_start(self):
        self.create_action_server(names.MOVE_TO, self)
        self.create_timer(0.1, self._tick)

    def execute(self, handle):
        self.handles.append(handle)

    def _tick(self):
        for h in self.handles:
            if not h.done:
                h.publish_feedback(MoveToFeedback(Pose2D(0.0, 0.0, 0.0), 1.0))


def main():
    ros = RosContext("amiro_test_server", int(sys.argv[1]))
    runtime = Runtime(SimClock(speed=1.0))
    runtime.add(Ros2Bridge(ros))
    runtime.add(Endless())
    runtime.add(ActionExporter(ros, MoveToCodec()))
    runtime.start()
    print("serving", flush=True)
    while True:
        runtime.spin_for(0.01)


if __name__ == "__main__":
    main()
