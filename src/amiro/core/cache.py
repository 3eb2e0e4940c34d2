"""Where amiro keeps what it derives once and reuses: trained NLU models, joined weights."""

from __future__ import annotations

import os
from pathlib import Path


def cache_dir() -> Path:
    """``$AMIRO_CACHE``, else ``$XDG_CACHE_HOME/amiro``, else ``~/.cache/amiro``."""
    if "AMIRO_CACHE" in os.environ:
        return Path(os.environ["AMIRO_CACHE"])
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "amiro"
