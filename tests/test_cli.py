"""The command line: --version, --help everywhere, one-line errors with exit code 2."""

from __future__ import annotations

import argparse
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import get_args

import pytest

from amiro import __version__
from amiro.cli import build_parser, main
from amiro.commands.planning import ENGINES
from amiro.system import shipped_behavior


def amiro(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "amiro.cli", *args],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"amiro {__version__}"


def command_paths(parser: argparse.ArgumentParser) -> Iterator[list[str]]:
    """Every command and subcommand of ``parser``, as the words that name it."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, child in action.choices.items():
                yield [name]
                yield from ([name, *rest] for rest in command_paths(child))


COMMANDS = list(command_paths(build_parser()))


def test_the_walk_finds_the_nested_commands() -> None:
    assert ["run", "hydration"] in COMMANDS
    assert ["plan", "pddl"] in COMMANDS
    assert ["serve"] in COMMANDS


@pytest.mark.parametrize("command", [[], *COMMANDS], ids=" ".join)
def test_every_command_has_help(command: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        main([*command, "--help"])
    assert exc.value.code == 0
    assert f"usage: {' '.join(['amiro', *command])}" in capsys.readouterr().out


@pytest.mark.parametrize("group", ["run", "plan", "nlu", "env", "ros2", "robot", "bench"])
def test_a_group_alone_prints_its_help_and_exits_2(
    group: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main([group]) == 2
    assert capsys.readouterr().out.startswith(f"usage: amiro {group} ")


@pytest.fixture(scope="module")
def loaded_by_help() -> set[str]:
    """The top-level packages loaded by building the whole parser, in a fresh interpreter."""
    script = "import sys, amiro.cli; amiro.cli.build_parser(); print(' '.join(sys.modules))"
    proc = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=120, check=True
    )
    return {name.split(".")[0] for name in proc.stdout.split()}


@pytest.mark.parametrize(
    "heavy",
    [
        "sklearn",
        "unified_planning",
        "fastapi",
        "rclpy",
        "onnxruntime",
        "torch",
        "cv2",
    ],
)
def test_help_does_not_import_heavy_packages(heavy: str, loaded_by_help: set[str]) -> None:
    assert "amiro" in loaded_by_help
    assert heavy not in loaded_by_help


def test_delivery_engines_are_the_planners() -> None:
    from amiro.behavior.planning.config import Engine

    assert get_args(Engine) == ENGINES


def one_line_error(proc: subprocess.CompletedProcess[str]) -> str:
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    return lines[0]


def test_unknown_language_is_a_one_line_error() -> None:
    line = one_line_error(amiro("run", "hydration", "--headless", "--lang", "de"))
    assert "unknown language 'de'" in line


def test_missing_config_file(tmp_path: Path) -> None:
    line = one_line_error(
        amiro("run", "hydration", "--headless", "--config", str(tmp_path / "nope.yaml"))
    )
    assert "no such file" in line


@pytest.mark.parametrize(
    ("content", "expected"),
    [
        ("seed: [1, 2\n", "line"),
        ("sim:\n  lidar:\n    rate: 50\n", "sim.lidar.rate"),
        ("navigation:\n  speed_of_light: 3\n", "navigation.speed_of_light"),
        ("sim:\n  residents:\n    - {name: ana, at: nowhere}\n", "nowhere"),
        ("behavior:\n  handlers:\n    hydration: /no/such/behaviour.yaml\n", "no such file"),
    ],
)
def test_bad_config_is_a_one_line_error(tmp_path: Path, content: str, expected: str) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(content)
    line = one_line_error(amiro("run", "hydration", "--headless", "--config", str(path)))
    assert expected in line


def test_a_misspelt_task_parameter_in_a_configured_behaviour_exits_2(tmp_path: Path) -> None:
    shipped = shipped_behavior("hydration").read_text(encoding="utf-8")
    assert "timeout_s: 10" in shipped
    behaviour = tmp_path / "hydration.yaml"
    behaviour.write_text(shipped.replace("timeout_s: 10", "timout_s: 10", 1), encoding="utf-8")
    path = tmp_path / "bad.yaml"
    path.write_text(f"behavior:\n  handlers:\n    hydration: {behaviour}\n")
    line = one_line_error(amiro("run", "hydration", "--headless", "--config", str(path)))
    assert f"{behaviour}: tasks." in line and "Listen: unknown parameter 'timout_s'" in line


def test_usage_errors_exit_2() -> None:
    proc = amiro("run", "hydration", "--seed", "many")
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    proc = amiro("run", "hydration", "--unreachable", "--person-absent")
    assert proc.returncode == 2


_BIG_REPORT = """
import argparse, sys
from amiro import cli
from amiro.commands.support import emit_json

def build_parser():
    parser = argparse.ArgumentParser()
    parser.add_argument("-v", "--verbose", action="store_true")
    parser.set_defaults(handler=lambda args: emit_json({"rows": list(range(200_000))}) or 0)
    return parser

cli.build_parser = build_parser
sys.exit(cli.main([]))
"""


def test_a_reader_that_goes_away_is_not_an_error() -> None:
    """`amiro ... --json | head`: no traceback, the shell's broken-pipe status."""
    proc = subprocess.Popen(
        [sys.executable, "-c", _BIG_REPORT], stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    assert proc.stdout is not None and proc.stderr is not None
    assert proc.stdout.read(20).startswith(b'{"rows": [0, 1')
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=60) == 141
    assert "Traceback" not in err and "BrokenPipeError" not in err
