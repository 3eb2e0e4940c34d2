"""The cloud ledger's pending notifications on disk, so that they outlive a cloud restart.

One JSON file holds every unacknowledged notification with its behaviour's latest
checkpoint.  Each change rewrites it whole through a temporary file and ``os.replace``, so a
crash leaves either the old or the new content, never half of one.  A file that cannot be
read or does not parse is moved aside (``<name>.corrupt``), counted and logged, and the
ledger starts empty: a lost reminder is better than a cloud that cannot start.
"""

from __future__ import annotations

import logging
import os
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, ValidationError

from amiro.core.messages import Notification

log = logging.getLogger("amiro.deploy.ledger")

FORMAT_VERSION = 1


class LedgerFile(BaseModel):
    """The file's content: notifications by id, and checkpoints by notification id."""

    model_config = ConfigDict(extra="forbid")

    version: int = FORMAT_VERSION
    pending: dict[str, Notification] = {}
    checkpoints: dict[str, dict[str, Any]] = {}


class LedgerStore:
    def __init__(self, path: Path) -> None:
        self.path = path
        self.corrupt = 0  # files moved aside since this process started
        self.write_errors = 0

    def load(self) -> LedgerFile:
        """What the last process left; empty when there is no file or it is unusable."""
        try:
            text = self.path.read_text(encoding="utf-8")
        except FileNotFoundError:
            return LedgerFile()
        except (OSError, UnicodeDecodeError) as exc:
            return self._set_aside(f"unreadable ({exc})")
        try:
            content = LedgerFile.model_validate_json(text)
        except ValidationError as exc:
            return self._set_aside(f"not a ledger ({exc.error_count()} errors)")
        if content.version != FORMAT_VERSION:
            return self._set_aside(f"format version {content.version}, expected {FORMAT_VERSION}")
        return content

    def save(self, content: LedgerFile) -> None:
        """Replace the file atomically; a failed write is logged and counted, not raised."""
        temporary = self.path.with_name(f"{self.path.name}.tmp")
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            with temporary.open("w", encoding="utf-8") as out:
                out.write(content.model_dump_json())
                out.flush()
                os.fsync(out.fileno())
            os.replace(temporary, self.path)
        except OSError as exc:
            self.write_errors += 1
            log.error("notification ledger %s: cannot write: %s", self.path, exc)

    def _set_aside(self, why: str) -> LedgerFile:
        self.corrupt += 1
        aside = self.path.with_name(f"{self.path.name}.corrupt")
        try:
            os.replace(self.path, aside)
            log.error(
                "notification ledger %s: %s; moved to %s, starting empty", self.path, why, aside
            )
        except OSError as exc:
            log.error("notification ledger %s: %s; cannot move it aside (%s)", self.path, why, exc)
        return LedgerFile()
