"""``amiro perception bench``: the issue's speed targets, measured on this machine.

Coordinate estimation runs the real-data path (:func:`locate_people`: robust torso depth,
clipped-box correction, back-projection, head and robot transforms) on frames of the
generated RGB-D dataset; face identification runs dlib on the shipped portraits.  Wall
time is read only here, to measure speed.
"""

from __future__ import annotations

import statistics
from collections.abc import Callable
from typing import Any

import numpy as np

from amiro.core.clock import wall_seconds
from amiro.core.messages import BoundingBox2D
from amiro.perception.estimation import CameraGeometry, Views
from amiro.perception.face_samples import in_scene, sample_face, views
from amiro.perception.faces import DlibFaceEmbedder, FaceGallery
from amiro.perception.locate import locate_people
from amiro.robot.camera import Camera
from amiro.sim.rgbd_dataset import DatasetSpec, generate


def median_ms(run: Callable[[], object], repeats: int) -> float:
    """Median wall time of ``run`` in ms, after one warm-up call."""
    run()
    times = []
    for _ in range(repeats):
        started = wall_seconds()
        run()
        times.append(1000.0 * (wall_seconds() - started))
    return statistics.median(times)


def estimation_ms(rng: np.random.Generator, frames: int, people: int) -> float:
    """Median time to place one frame's ``people`` detections in the map."""
    camera = Camera()
    geom = CameraGeometry.from_info(camera.info(0.0), camera.params.height, camera.params.forward)
    batch = next(generate(rng, DatasetSpec(people=1, images=1, batch=max(frames, people))))
    n = len(batch.box)
    times = []
    for f in range(frames):
        rows = [(f + k) % n for k in range(people)]
        boxes = [BoundingBox2D(*map(float, batch.box[r])) for r in rows]
        view = Views(
            *(
                a[rows]
                for a in (
                    batch.views.x,
                    batch.views.y,
                    batch.views.theta,
                    batch.views.head_yaw,
                    batch.views.head_pitch,
                )
            )
        )
        depth = batch.depth[f % n].astype(np.float64)
        started = wall_seconds()
        locate_people(geom, depth, boxes, view)
        times.append(1000.0 * (wall_seconds() - started))
    return statistics.median(times)


def face_ms(repeats: int) -> dict[str, float]:
    """Median time to identify one face: in a 640 x 480 frame, and in a head crop (what a
    person detector's box gives)."""
    gallery = FaceGallery(DlibFaceEmbedder(upsample=0))
    for name in ("collins", "hopper"):
        gallery.enrol(name, views(sample_face(name)))
    crop = sample_face("hopper")
    frame = in_scene(crop)
    return {
        "face_ms_per_face_in_frame": round(median_ms(lambda: gallery.identify(frame), repeats), 1),
        "face_ms_per_face_crop": round(median_ms(lambda: gallery.identify(crop), repeats), 1),
    }


def bench(rng: np.random.Generator, frames: int, people: int, repeats: int) -> dict[str, Any]:
    return {
        "people_per_frame": people,
        "estimate_ms_per_frame": round(estimation_ms(rng, frames, people), 3),
        **face_ms(repeats),
        "targets": {"estimate_ms_per_frame": 1.0, "face_ms_per_face": 200.0},
    }
