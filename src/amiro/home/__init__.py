"""The home a robot serves: its rooms, places, doors and map, and the people who live there.

Shared by the simulator and by a real robot: nothing here knows which one runs.
"""
