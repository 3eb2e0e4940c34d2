"""The 3D estimators: the improved one inverts the camera exactly; the paper's as written."""

from __future__ import annotations

import math

import numpy as np
import pytest

from amiro.core.messages import BoundingBox2D, Pose2D
from amiro.perception.depth import centre_depth, densest_cluster, torso_depth
from amiro.perception.estimation import CameraGeometry, Views, improved, paper_formula
from amiro.robot.camera import Camera


def geometry(cam: Camera) -> CameraGeometry:
    return CameraGeometry.from_info(cam.info(0.0), cam.params.height, cam.params.forward)


@pytest.mark.parametrize("yaw,pitch,theta", [(0.0, 0.0, 0.0), (0.4, 0.2, 1.0), (-0.7, -0.1, -2.5)])
def test_improved_inverts_the_camera(yaw: float, pitch: float, theta: float) -> None:
    cam = Camera()
    pose = Pose2D(1.0, 2.0, theta)
    rng = np.random.default_rng(0)
    heading = theta + yaw
    dist = rng.uniform(1.5, 5.0, 20)
    side = rng.uniform(-0.5, 0.5, 20) * dist
    points = np.stack(
        [
            pose.x + dist * math.cos(heading) - side * math.sin(heading),
            pose.y + dist * math.sin(heading) + side * math.cos(heading),
            rng.uniform(0.3, 1.6, 20),
        ],
        axis=1,
    )
    optical = cam.to_optical(points, pose, yaw, pitch)
    uv = cam.project(optical)
    views = Views.single(pose.x, pose.y, theta, yaw, pitch, 20)
    back = improved(geometry(cam), uv[:, 0], uv[:, 1], optical[:, 2], views)
    np.testing.assert_allclose(back, points, atol=1e-9)


def test_paper_formula_as_written() -> None:
    geom = geometry(Camera())
    views = Views.single(0.0, 0.0, 0.0, 0.2, 0.1, 1)
    u, v, d = np.array([160.0]), np.array([360.0]), np.array([3.0])
    alpha = geom.hfov * (320 - 160) / 320  # the full field of view, "the maximum angle"
    beta = geom.vfov * (360 - 240) / 240
    ((x, y, z),) = paper_formula(geom, u, v, d, views, fov="full")
    assert x == pytest.approx(3.0 * math.cos(alpha + 0.2))
    assert y == pytest.approx(3.0 * math.sin(alpha + 0.2))
    assert z == pytest.approx(geom.mount_height - 3.0 * math.sin(beta + 0.1))


def test_paper_formula_read_with_edge_angles_is_geometrically_consistent() -> None:
    """Read as the angle at the image edge (half the field of view), a pixel on the border
    gets its ray's true angle, and a point on the image's middle row is placed where it is
    (up to the linear-angle approximation inside the image); the full-field reading
    doubles every angle."""
    cam = Camera()
    geom = geometry(cam)
    views = Views.single(0.0, 0.0, 0.0, 0.0, 0.0, 1)
    ray = math.atan((geom.width / 2.0) / geom.fx)  # the border pixel's true angle
    assert ray == pytest.approx(geom.hfov / 2.0)
    d = np.array([3.0])
    ((x, y, _),) = paper_formula(geom, np.array([0.0]), np.array([240.0]), d, views)
    assert math.atan2(y, x) == pytest.approx(ray)
    ((_, y_full, _),) = paper_formula(
        geom, np.array([0.0]), np.array([240.0]), d, views, fov="full"
    )
    assert y_full == pytest.approx(3.0 * math.sin(2.0 * ray))
    # A point 3 m away, 0.6 m to the left, at the camera's height: projected, then placed.
    point = np.array([[3.0 + cam.params.forward, 0.6, cam.params.height]])
    pose = Pose2D(0.0, 0.0, 0.0)
    optical = cam.to_optical(point, pose, 0.0, 0.0)
    (u, v), rng = cam.project(optical)[0], float(np.linalg.norm(optical[0]))
    uvd = np.array([u]), np.array([v]), np.array([rng])
    ((x, y, z),) = paper_formula(geom, *uvd, views)
    assert abs(y - 0.6) < 0.1 and abs(z - cam.params.height) < 0.01  # 4 cm: linear angles
    ((_, y_full, _),) = paper_formula(geom, *uvd, views, fov="full")
    assert abs(y_full - 0.6) > 0.4
    with pytest.raises(ValueError):
        paper_formula(geom, d, d, d, views, fov="quarter")


def test_surface_offset_moves_along_the_ray() -> None:
    geom = geometry(Camera())
    views = Views.single(0.0, 0.0, 0.0, 0.0, 0.0, 1)
    near = improved(geom, np.array([320.0]), np.array([240.0]), np.array([2.0]), views)
    far = improved(geom, np.array([320.0]), np.array([240.0]), np.array([2.0]), views, 0.12)
    assert far[0, 0] - near[0, 0] == pytest.approx(0.12)
    assert far[0, 1] == pytest.approx(near[0, 1]) and far[0, 2] == pytest.approx(near[0, 2])


def test_densest_cluster_rejects_background_and_dropouts() -> None:
    values = np.array([0.0, 2.01, 2.0, 1.99, 2.02, 4.5, 4.6, 0.0, 2.0])
    mask = densest_cluster(values, 0.15)
    assert mask.tolist() == [False, True, True, True, True, False, False, False, True]


def test_torso_depth_ignores_the_wall_behind() -> None:
    depth = np.full((60, 80), 5.0)
    depth[10:50, 30:50] = 2.0  # the person, in a 640 x 480 image scaled by 1/8
    depth[25:28, 35:45] = 0.0  # dropped pixels
    box = BoundingBox2D(320.0, 240.0, 200.0, 360.0)  # wider than the person
    z, u = torso_depth(depth, box, 80 / 640)  # type: ignore[misc]
    assert z == pytest.approx(2.0)
    assert u == pytest.approx(320.0, abs=8.0)
    assert centre_depth(depth, box, 80 / 640) == pytest.approx(2.0)
    assert torso_depth(np.zeros((60, 80)), box, 80 / 640) is None
