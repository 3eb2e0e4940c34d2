"""Request bodies of the dashboard API: every input is validated before it reaches a node."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

NAME = r"^[a-z0-9_]{1,40}$"


class Body(BaseModel):
    model_config = ConfigDict(extra="forbid")


class LoginBody(Body):
    user: str = Field(min_length=1, max_length=64)
    password: str = Field(min_length=1, max_length=256)


class ChatBody(Body):
    text: str = Field(min_length=1, max_length=500)
    lang: Literal["en", "ro", "fr"] = "en"
    user: str = Field(
        default="",
        pattern=r"^[a-z0-9_]{0,40}$",
        description="the resident speaking (a tablet by their chair); empty: the signed-in user",
    )


class TaskBody(Body):
    type: str = Field(pattern=r"^[A-Za-z]{1,40}$")
    params: dict[str, Any] = Field(default_factory=dict, max_length=20)
    priority: int = Field(default=3, ge=0, le=100)


class ScenarioBody(Body):
    name: str = Field(pattern=NAME)
    user: str = Field(default="", pattern=r"^[a-z0-9_]{0,40}$")
    priority: int | None = Field(
        default=None, ge=0, le=100, description="none: the behaviour's own priority"
    )


class EstopBody(Body):
    engaged: bool = Field(strict=True)


class DeviceBody(Body):
    room: str = Field(pattern=NAME)
    device: Literal["lights", "blinds"]
    state: Literal["on", "off", "open", "close"]


class SensorBody(Body):
    room: str = Field(pattern=NAME)
    sensor: Literal["temperature", "humidity", "luminosity"]
    value: float = Field(ge=-50.0, le=100_000.0, allow_inf_nan=False)
