"""``amiro robot profiles`` and ``amiro robot run`` (against fake NAOqi services)."""

from __future__ import annotations

import argparse
import json

import pytest
from naoqi_fakes import Recorder

from amiro.commands.robot import register
from amiro.core.config import ConfigError


def _amiro(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="amiro")
    register(parser.add_subparsers())
    args = parser.parse_args(argv)
    code: int = args.handler(args)
    return code


def test_profiles_lists_the_shipped_robots(capsys: pytest.CaptureFixture[str]) -> None:
    assert _amiro(["robot", "profiles", "--json"]) == 0
    rows = {r["name"]: r for r in json.loads(capsys.readouterr().out)["profiles"]}
    assert rows["generic_diff"]["base"] == "differential"
    assert rows["pepper"]["topics"]["scan"] == "/laser" and rows["pepper"]["naoqi"] is True


def test_run_says_a_sentence_on_a_naoqi_robot(
    fake_pepper: tuple[str, Recorder], capsys: pytest.CaptureFixture[str]
) -> None:
    url, rec = fake_pepper
    argv = ["robot", "run", "--adapter", "naoqi", "--url", url, "--say", "Bonjour", "--lang", "fr"]
    assert _amiro([*argv, "--duration", "1", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["adapter"] == "naoqi" and report["profile"] == "pepper"
    assert report["naoqi_calls"] >= 4 and report["naoqi_errors"] == 0
    assert rec.named("say") == [("Bonjour", "French")]
    assert rec.named("stopMove") == [()]  # the base is left still


def test_bad_input_is_a_config_error() -> None:
    with pytest.raises(ConfigError, match="needs --url"):
        _amiro(["robot", "run", "--adapter", "naoqi"])
    with pytest.raises(ConfigError, match="--duration must be positive"):
        _amiro(["robot", "run", "--adapter", "ros2", "--duration", "0"])
    with pytest.raises(ConfigError, match="unknown robot profile"):
        _amiro(["robot", "run", "--adapter", "naoqi", "--url", "tcp://x:1", "--profile", "r2d2"])
