"""Perception: people and objects, faces, 3D positions, and support for the Search task."""
