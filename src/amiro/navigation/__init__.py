"""Navigation: costmaps, global planning, path following and the MoveTo action."""
