"""Core: bus, messages, clock, configuration, nodes and their supervision."""
