"""The localisers ``navigation.localization`` names (see :mod:`amiro.core.registry`).

Kind ``localization``: ``factory(grid: GridMap, cfg: NavigationConfig, initial_pose: Pose2D |
None, rng: np.random.Generator | None) -> Localizer``.

Only names and import paths here: the config module imports this.
"""

from __future__ import annotations

from amiro.core.registry import register

register("localization", "amcl", "amiro.navigation.stack:amcl_localizer")
register("localization", "oracle", "amiro.navigation.stack:oracle_localizer")
