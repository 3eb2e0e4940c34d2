"""Configuration of the navigation stack (the ``navigation:`` section)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal

from pydantic import Field

from amiro.core.config import Section
from amiro.core.registry import backend_name
from amiro.navigation import backends as _backends  # noqa: F401 - registers the names


class NavigationConfig(Section):
    backend: Literal["amiro", "nav2"] = Field(
        default="amiro",
        description="amiro: amiro's own MoveTo (localisation, A*, DWA); nav2: MoveTo is a "
        "client of the robot's own Nav2 (/navigate_to_pose), in a ROS 2 deployment's edge",
    )
    map: Path | None = Field(default=None, description="map_server YAML; None: the home's map")
    localization: Annotated[str, backend_name("localization")] = Field(
        default="amcl",
        description="amcl: particle filter on /odom + /scan; oracle: the simulator's true pose",
    )
    start_place: str | None = Field(
        default="dock",
        description="where AMCL starts when nothing gives an initial pose (a robot boots on "
        "its dock; the embedded simulator gives the robot's configured start instead); "
        "None: global localisation",
    )
    amcl_particles: int = Field(default=500, ge=10, description="most particles (KLD adapts)")
    amcl_beams: int = Field(default=60, ge=4, description="lidar beams per filter update")
    planning_resolution: float = Field(default=0.1, gt=0.0)
    robot_radius: float = Field(default=0.25, gt=0.0)
    safety_margin: float = Field(default=0.08, ge=0.0)
    max_speed: float = Field(default=0.35, gt=0.0)
    max_turn: float = Field(default=1.0, gt=0.0)
    control_hz: float = Field(default=10.0, gt=0.0)
