"""The paper's section-4.2 figures (Tables 7–13), printed beside ours by the evaluation."""

from __future__ import annotations

Axes = tuple[float, float, float]

# (MAE x, y, z), (MSE x, y, z) in metres
OVERALL: tuple[Axes, Axes] = ((0.47, 0.36, 0.28), (0.38, 0.40, 0.15))
BY_DISTANCE: dict[str, tuple[Axes, Axes]] = {
    "2": ((0.44, 0.47, 0.31), (0.28, 0.67, 0.16)),
    "3": ((0.22, 0.43, 0.27), (0.09, 0.58, 0.14)),
    "4": ((0.51, 0.29, 0.25), (0.40, 0.21, 0.13)),
    "5": ((0.72, 0.26, 0.30), (0.74, 0.13, 0.16)),
}
BY_POSTURE: dict[str, tuple[Axes, Axes]] = {
    "standing_front": ((0.38, 0.10, 0.16), (0.21, 0.02, 0.03)),
    "standing_back": ((0.38, 0.10, 0.14), (0.21, 0.02, 0.03)),
    "sitting_desk": ((0.56, 0.43, 0.21), (0.51, 0.32, 0.09)),
    "sitting_couch": ((0.52, 0.60, 0.21), (0.47, 0.84, 0.06)),
    "lying_couch": ((0.53, 0.58, 0.69), (0.49, 0.79, 0.52)),
}
BY_CAMERA: dict[str, tuple[Axes, Axes]] = {
    "centred": ((0.33, 0.16, 0.27), (0.18, 0.05, 0.14)),
    "rotated_right": ((0.52, 0.58, 0.26), (0.48, 0.83, 0.14)),
    "rotated_left": ((0.54, 0.22, 0.31), (0.41, 0.13, 0.16)),
    "right_1m": ((0.51, 0.54, 0.29), (0.46, 0.79, 0.16)),
    "left_1m": ((0.46, 0.30, 0.28), (0.35, 0.19, 0.14)),
}
COUNTING_OVERALL = 0.18
COUNTING_EXCLUDING_LYING = 0.03
COUNTING_BY_POSTURE = {
    "standing_front": 0.00,
    "standing_back": 0.00,
    "sitting_desk": 0.10,
    "sitting_couch": 0.03,
    "lying_couch": 0.82,
}
# distance -> (all postures, excluding lying down)
COUNTING_BY_DISTANCE = {"2": (0.09, 0.02), "3": (0.16, 0.03), "4": (0.23, 0.04), "5": (0.22, 0.04)}
