"""Fixtures of the environment tests: a real mosquitto broker and MQTT peers."""

from env_broker import broker, peer_factory

__all__ = ["broker", "peer_factory"]
