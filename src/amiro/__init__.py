"""amiro: an open framework for assistive social robots (after the AMIRO paper)."""

__version__ = "0.1.0"
