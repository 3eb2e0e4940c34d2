"""Bad output paths at the CLI: one line on stderr and exit 2, before any work is done;
``-v`` keeps the traceback for whoever is debugging."""

from __future__ import annotations

from pathlib import Path

import pytest

from amiro.cli import main


@pytest.fixture
def blocker(tmp_path: Path) -> Path:
    """A file where the commands below expect a folder."""
    path = tmp_path / "afile"
    path.write_text("not a folder")
    return path


@pytest.mark.parametrize(
    "argv",
    [
        ["slam", "simulate", "--out", "{b}/x.log"],
        ["asr", "synthesize", "{cmds}", "{b}/out"],
        ["record", "hydration", "--out", "{b}/x.mcap"],
        ["perception", "evaluate", "--out", "{b}/d"],
    ],
)
def test_an_unwritable_output_is_one_line_and_exit_2(
    argv: list[str], blocker: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cmds = tmp_path / "commands.txt"
    cmds.write_text("turn on the lights\n")
    args = [a.format(b=blocker, cmds=cmds) for a in argv]
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("amiro: error: ") and "\n" not in err and str(blocker) in err
    assert blocker.read_text() == "not a folder"


def test_verbose_keeps_the_traceback(blocker: Path) -> None:
    with pytest.raises(OSError):
        main(["-v", "slam", "simulate", "--out", f"{blocker}/x.log"])
