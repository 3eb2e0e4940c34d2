"""Typed YAML configuration and its one-line errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from amiro.core.config import ConfigError, Section, load


class Motor(Section):
    max_speed: float = 0.5
    name: str = "left"


class Robot(Section):
    port: int = 1
    motor: Motor = Motor()


def write(tmp_path: Path, text: str, name: str = "robot.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def load_error(path: Path) -> str:
    with pytest.raises(ConfigError) as info:
        load(Robot, path)
    message = str(info.value)
    assert "\n" not in message
    assert str(path) in message
    return message


def test_valid_yaml_loads(tmp_path: Path) -> None:
    cfg = load(Robot, write(tmp_path, "port: 3\nmotor:\n  max_speed: 1.5\n"))
    assert cfg == Robot(port=3, motor=Motor(max_speed=1.5, name="left"))
    with pytest.raises(ValueError):  # sections are frozen
        cfg.port = 4  # type: ignore[misc]


def test_empty_file_gives_defaults(tmp_path: Path) -> None:
    assert load(Robot, write(tmp_path, "")) == Robot()


def test_missing_file(tmp_path: Path) -> None:
    message = load_error(tmp_path / "absent.yaml")
    assert "no such file" in message


def test_invalid_yaml_names_line(tmp_path: Path) -> None:
    message = load_error(write(tmp_path, "port: 3\nmotor: x: y\n"))
    assert "line 2" in message


def test_invalid_yaml_unclosed_list(tmp_path: Path) -> None:
    message = load_error(write(tmp_path, "port: 3\nmotor:\n  max_speed: [1, 2\n"))
    assert "line " in message


def test_wrong_type_names_dotted_path(tmp_path: Path) -> None:
    message = load_error(write(tmp_path, "port: 3\nmotor:\n  max_speed: fast\n"))
    assert "motor.max_speed" in message
    assert "number" in message


def test_unknown_key_names_dotted_path(tmp_path: Path) -> None:
    message = load_error(write(tmp_path, "motor:\n  max_sped: 1.0\n"))
    assert "motor.max_sped" in message


def test_several_problems_still_one_line(tmp_path: Path) -> None:
    message = load_error(write(tmp_path, "port: many\nmotor:\n  max_speed: fast\n  bogus: 1\n"))
    assert "port" in message
    assert "2 more problems" in message


def test_top_level_must_be_mapping(tmp_path: Path) -> None:
    message = load_error(write(tmp_path, "- 1\n- 2\n"))
    assert "mapping" in message
