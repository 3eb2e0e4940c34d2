"""Dialogue: what the robot says and how it understands answers (en, ro, fr)."""
