# SPDX-License-Identifier: MIT
"""Cases whose answers are known in closed form: two boxes apart and pressed into
each other (a convex pair's depth is exact), poses in every accepted form."""
import numpy as np
import pytest

import smartcollision as sc
from conftest import box, quat_about


@pytest.fixture
def boxes():
    return sc.Model(*box(1, 1, 1)), sc.Model(*box(2, 0.5, 0.5))


def test_distance_of_separated_boxes(boxes):
    a, b = boxes
    tracker = sc.PairTracker(a, b)
    rng = np.random.default_rng(1)
    for _ in range(50):
        offset = rng.uniform(-6, 6, size=3)
        gap = np.abs(offset) - np.array([3, 1.5, 1.5])          # per-axis gaps of the boxes
        if np.all(gap <= 0):
            continue
        expected = np.linalg.norm(np.maximum(gap, 0))
        tracker.forget()
        assert tracker.distance(offset, np.zeros(3)) == pytest.approx(expected, abs=1e-9)


def test_depth_of_pressed_boxes(boxes):
    a, b = boxes
    tracker = sc.PairTracker(a, b, sc.Settings(tolerance=1e-4))
    assert tracker.distance([0.3, 0.2, 1.6], [0, 0, 0]) == pytest.approx(0.1)
    for depth in (0.05, 0.2, 0.4):
        r = tracker.penetration([0.3, 0.2, 1.5 - depth], [0, 0, 0])
        assert r.penetrating
        assert r.distance == pytest.approx(-depth, abs=1e-4)
        np.testing.assert_allclose(r.tpdv, [0, 0, -depth], atol=1e-4)
        np.testing.assert_allclose(r.normal, [0, 0, 1], atol=1e-9)
        np.testing.assert_array_equal(r.rpdv, np.zeros(3))           # INPUT mode
        np.testing.assert_allclose(r.contact_position, [0.3, 0.2, 1.5], atol=1e-4)
        np.testing.assert_allclose(r.contact_pose[:3, 3], [0.3, 0.2, 1.5], atol=1e-4)
        c = tracker.contacts()
        assert len(c["separation"]) >= 1
        np.testing.assert_allclose(c["separation"], -depth, atol=1e-4)


def test_pose_forms_agree(boxes):
    a, b = boxes
    q = quat_about([1, 2, 3], 0.7)
    w, x, y, z = q
    rot = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                    [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                    [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = rot, [0.5, 4, 0.2]
    values = []
    for pose in (m, ([0.5, 4, 0.2], q), np.concatenate([[0.5, 4, 0.2], q]), m.tolist()):
        values.append(sc.PairTracker(a, b).distance(pose, np.eye(4)))
    assert max(values) - min(values) < 1e-12
    assert sc.PairTracker(a, b).distance([0.5, 4, 0.2], np.eye(4)) == pytest.approx(4 - 1 - 0.5)


def test_features_and_stored_mesh(boxes):
    a, b = boxes
    r = sc.PairTracker(a, b).penetration([0.3, 0.2, 1.6], [0, 0, 0])
    assert r.target_feature.type == sc.FeatureType.FACE or len(r.target_feature.vertices) >= 1
    verts = a.vertices()
    assert verts.shape == (8, 3) and not verts.flags.writeable
    # The target's feature lies on the plane z = -1 of its own frame (its bottom).
    for i in r.target_feature.vertices:
        assert verts[i, 2] == -1.0
    assert a.triangles().dtype == np.int32 and a.triangles().shape == (12, 3)
    np.testing.assert_array_equal(a.bounds, [[-1, -1, -1], [1, 1, 1]])


def test_inside_out_is_flipped():
    v, f = box()
    m = sc.Model(v, f[:, ::-1])
    assert m.stats().flipped

    def canonical(t):  # each triangle's cycle started at its smallest index
        return [tuple(np.roll(row, -int(np.argmin(row)))) for row in t]
    assert canonical(m.triangles()) == canonical(f)
