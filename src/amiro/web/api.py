"""The ``/api`` routes: state, map, behaviours, chat, health, smart home, notifications.

Authentication and CSRF are enforced for the whole prefix by the app's middleware; these
handlers only validate their inputs and hand work to the runtime through the gateway.
"""

from __future__ import annotations

import asyncio
import itertools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

from fastapi import APIRouter, HTTPException, Path, Query, Request

from amiro.behavior.task import TaskError, task_types
from amiro.core import names
from amiro.core.messages import Notification, String
from amiro.environment.assembly import Environment
from amiro.environment.days import clock_date
from amiro.environment.messages import DEVICE_STATES, HEALTH_METRICS, DeviceCommand
from amiro.environment.simulated import SimulatedSensorsNode
from amiro.web.chat import ChatPort
from amiro.web.gateway import GatewayNode
from amiro.web.health import METRIC_INFO
from amiro.web.models import (
    NAME,
    ChatBody,
    DeviceBody,
    EstopBody,
    ScenarioBody,
    SensorBody,
    TaskBody,
)
from amiro.web.robot import RobotPort

T = TypeVar("T")
CALL_TIMEOUT_S = 10.0


@dataclass
class Backend:
    """What the API serves: the robot (embedded or remote), the smart environment with its
    simulated sensors, the gateway and the chat port."""

    robot: RobotPort
    environment: Environment
    sensors: SimulatedSensorsNode
    gateway: GatewayNode
    chat: ChatPort
    demo: bool = False  # the health store holds seeded demo data


def build_router(backend: Backend) -> APIRouter:
    router = APIRouter(prefix="/api")
    gw, robot, env = backend.gateway, backend.robot, backend.environment
    counter = itertools.count(1)

    async def on_runtime(job: Callable[[], T]) -> T:
        try:
            return await asyncio.wait_for(asyncio.wrap_future(gw.call(job)), CALL_TIMEOUT_S)
        except TimeoutError:
            raise HTTPException(503, "the robot's runtime did not answer in time") from None

    @router.get("/me")
    def me(request: Request) -> dict[str, Any]:
        session = request.state.session
        return {"user": request.state.user, "csrf": session.csrf if session else None}

    @router.get("/state")
    def state() -> dict[str, Any]:
        return gw.snapshot

    @router.get(names.MAP)
    def home_map() -> dict[str, Any]:
        home = robot.home
        return {
            "name": home.name,
            "size": list(home.size),
            "rooms": {name: [list(p) for p in r.polygon] for name, r in home.rooms.items()},
            "walls": [[list(w.a), list(w.b)] for w in home.walls],
            "doors": [{"name": d.name, "a": list(d.a), "b": list(d.b)} for d in home.doors],
            "furniture": [
                {"name": f.name, "polygon": [list(p) for p in f.polygon]} for f in home.furniture
            ],
        }

    @router.get("/behaviours")
    def behaviours() -> dict[str, Any]:
        """Task types, and each scenario with the priority it runs at."""
        return {"task_types": sorted(task_types()), "scenarios": robot.scenarios()}

    @router.post("/tasks")
    async def run_task(body: TaskBody) -> dict[str, Any]:
        def submit() -> str:
            return robot.run_task(body.type, body.params, body.priority)

        try:
            return {"run": await on_runtime(submit)}
        except TaskError as exc:
            raise HTTPException(422, str(exc)) from None

    @router.post("/scenarios")
    async def run_scenario(body: ScenarioBody) -> dict[str, Any]:
        """A notification of that kind, at the behaviour's own priority unless one is given
        (a fall at 100 preempts a hydration reminder at 5)."""
        own = robot.scenarios()
        if body.name not in own:
            raise HTTPException(422, f"unknown scenario '{body.name}' (known: {', '.join(own)})")
        ident = f"web-{body.name}-{next(counter)}"
        priority = own[body.name] if body.priority is None else body.priority
        note = Notification(ident, body.user, body.name, priority, reason="dashboard")
        await on_runtime(lambda: gw.runtime.bus.publish(names.NOTIFICATIONS, note))
        return {"id": ident, "priority": priority}

    @router.post("/estop")
    async def estop(body: EstopBody) -> dict[str, Any]:
        """Engage or release the emergency stop (every base driver and the navigation obey
        ``names.EMERGENCY_STOP``)."""
        msg = String("stop" if body.engaged else "release")
        await on_runtime(lambda: gw.runtime.bus.publish(names.EMERGENCY_STOP, msg))
        return {"engaged": body.engaged}

    @router.get("/scan")
    async def scan(most: int = Query(default=360, ge=10, le=2000)) -> dict[str, Any]:
        """The last lidar scan in the map frame (the map's "lidar" switch polls it)."""
        return {"points": await on_runtime(lambda: gw.scan_points(most))}

    @router.post("/chat")
    async def chat(body: ChatBody, request: Request) -> dict[str, Any]:
        user = body.user or str(request.state.user)

        def converse() -> str:
            gw.note_chat(user, body.text, body.lang)
            reply = backend.chat.reply(body.text, body.lang, user)
            gw.note_chat("robot", reply, body.lang)
            return reply

        return {"reply": await on_runtime(converse), "lang": body.lang, "user": user}

    @router.get("/health/users")
    async def health_users() -> dict[str, Any]:
        return {
            "users": await on_runtime(env.health.users),
            "metrics": list(HEALTH_METRICS),
            "info": METRIC_INFO,
            "demo": backend.demo,
        }

    @router.get("/health/{user}/{metric}")
    async def health(
        user: str = Path(pattern=NAME),
        metric: str = Path(pattern=NAME),
        days: int = Query(default=14, ge=1, le=366),
    ) -> dict[str, Any]:
        if metric not in HEALTH_METRICS:
            raise HTTPException(422, f"metric must be one of {', '.join(HEALTH_METRICS)}")

        def query() -> dict[str, Any]:
            today = clock_date(gw.runtime.clock)
            latest = env.health.latest(user, metric)
            trend = env.health.trend(user, metric, today, days)
            return {"latest": latest.to_dict() if latest else None, **trend.to_dict()}

        info = {**METRIC_INFO[metric], "demo": backend.demo}
        return {"user": user, "metric": metric, **info, **await on_runtime(query)}

    @router.post("/devices")
    async def device(body: DeviceBody) -> dict[str, Any]:
        if body.state not in DEVICE_STATES[body.device]:
            raise HTTPException(
                422, f"{body.device} can be {' or '.join(DEVICE_STATES[body.device])}"
            )
        if body.room not in robot.home.rooms:
            raise HTTPException(422, f"no room '{body.room}'")
        cmd = DeviceCommand(env.config.home_id, body.room, body.device, body.state)
        await on_runtime(lambda: gw.runtime.bus.publish(names.DEVICE_COMMAND, cmd))
        return {"sent": True}

    @router.post("/sensors")
    async def sensor(body: SensorBody) -> dict[str, Any]:
        """Set a simulated sensor (the "raise the temperature" button of the demo)."""
        try:
            await on_runtime(lambda: backend.sensors.set(body.room, body.sensor, body.value))
        except ValueError as exc:
            raise HTTPException(422, str(exc)) from None
        return {"set": True}

    @router.get("/notifications")
    async def notifications(limit: int = Query(default=50, ge=1, le=500)) -> dict[str, Any]:
        return {"notifications": await on_runtime(lambda: env.ledger.recent(limit))}

    return router
