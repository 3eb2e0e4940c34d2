"""Fixtures of the web tests: a served system and a client."""

from web_served import client, running

__all__ = ["client", "running"]
