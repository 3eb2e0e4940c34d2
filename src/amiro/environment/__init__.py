"""Smart environment and health: sensors, rules, notifications and acknowledgements."""
