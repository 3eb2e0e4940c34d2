"""``amiro serve``'s configuration: one environment section, overridden by the flags."""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest

from amiro.commands.serve import apply_flags
from amiro.core.config import ConfigError
from amiro.web.served import load_serve_config

FILE = """
environment:
  home_id: flat
  database: sqlite:///health.db
  reminders:
    timezone: Europe/Bucharest
    calendar: [{title: physiotherapy, at: "2026-07-15T16:30:00"}]
web:
  port: 9000
"""


def flags(**given: object) -> argparse.Namespace:
    values = {"mqtt": None, "home": None, "db": None, "host": None, "port": None}
    return argparse.Namespace(**{**values, **given})


def test_the_file_fills_the_systems_environment(tmp_path: Path) -> None:
    path = tmp_path / "serve.yaml"
    path.write_text(FILE)
    cfg = load_serve_config(str(path))
    env = cfg.system.environment
    assert (env.home_id, env.database) == ("flat", "sqlite:///health.db")
    assert env.reminders.timezone == "Europe/Bucharest" and len(env.reminders.calendar) == 1
    assert cfg.web.port == 9000


def test_flags_override_the_environment_and_the_web_section() -> None:
    cfg = load_serve_config(None)
    assert cfg.system.environment.mqtt is None
    args = flags(mqtt="mqtt://broker:1884", home="flat_2", db="sqlite:///x.db", port=8765)
    out = apply_flags(cfg, args)
    env = out.system.environment
    assert env.mqtt is not None and env.mqtt.url == "mqtt://broker:1884"
    assert (env.home_id, env.database, out.web.port) == ("flat_2", "sqlite:///x.db", 8765)
    assert out.system.sim == cfg.system.sim  # the rest is untouched


@pytest.mark.parametrize("bad", [{"mqtt": "http://broker"}, {"home": "Bad Home!"}])
def test_bad_flags_are_one_line_errors(bad: dict[str, str]) -> None:
    with pytest.raises(ConfigError) as err:
        apply_flags(load_serve_config(None), flags(**bad))
    assert "\n" not in str(err.value)
