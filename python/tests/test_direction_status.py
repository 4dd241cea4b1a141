# SPDX-License-Identifier: MIT
"""Result.direction_status says what a direction's update found. Two unit cubes along
x, their faces x - 1 apart: the gap against the tolerance decides separated,
touching or penetrating; the cases without a result each have their own value."""
import numpy as np
import pytest

import smartcollision as sc
from conftest import box, quat_about

DS = sc.DirectionStatus


@pytest.fixture
def cube():
    return sc.Model(*box(0.5, 0.5, 0.5))


def test_values_follow_the_gap(cube):
    tracker = sc.PairTracker(cube, cube)
    tol = tracker.settings.tolerance
    cases = [(1.5, DS.SEPARATED), (1.0 + 0.5 * tol, DS.TOUCHING), (1.0, DS.TOUCHING),
             (0.9, DS.PENETRATING), (1.5, DS.SEPARATED)]
    for x, expected in cases:
        r = tracker.penetration([x, 0, 0], np.eye(4))
        gap = x - 1.0
        assert r.direction_status == expected, (x, r.direction_status)
        assert r.has_depth == (gap < -tol)
        if r.has_depth:
            assert np.linalg.norm(r.tpdv) == pytest.approx(-gap, abs=tol)
        else:
            np.testing.assert_array_equal(r.tpdv, np.zeros(3))
    flush = tracker.penetration([1.0, 0, 0], np.eye(4))
    assert flush.penetrating and not flush.has_depth   # distance 0 without a depth


def test_no_result_cases(cube):
    far = sc.PairTracker(cube, cube, sc.Settings(max_distance=0.2))
    r = far.penetration([1.5, 0, 0], np.eye(4))
    assert r.status == sc.Status.NO_RESULT
    assert r.direction_status == DS.BEYOND_MAX_DISTANCE
    assert far.penetration([1.1, 0, 0], np.eye(4)).direction_status == DS.SEPARATED
    inside = sc.PairTracker(cube, cube).penetration([0.5, 0, 0], np.eye(4))
    assert inside.status == sc.Status.INVALID_INITIAL_TRANSFORMATION
    assert inside.direction_status == DS.FIRST_SEEN_INTERSECTING


def test_a_proxy_out_of_iterations_lags(cube):
    tracker = sc.PairTracker(cube, cube, sc.Settings(max_iterations=1))
    assert tracker.penetration([1.5, 0, 0], np.eye(4)).direction_status == DS.SEPARATED
    turned = ([0.6, 0, 0], quat_about([0, 0, 1], 0.4))
    r = tracker.penetration(turned, np.eye(4))
    assert r.has_depth and r.direction_status == DS.LAGGING
    tracker.settings = sc.Settings()
    for _ in range(6):
        r = tracker.penetration(turned, np.eye(4))
        if r.direction_status != DS.LAGGING:
            break
    assert r.direction_status == DS.PENETRATING


def test_scene_arrays_match_results(cube):
    scene = sc.Scene()
    scene.add_object(1, cube, [1.5, 0, 0])
    scene.add_object(2, cube)
    scene.add_to_group(10, 1)
    for x, expected in ((1.5, DS.SEPARATED), (0.9, DS.PENETRATING)):
        scene.set_group_pose(10, [x, 0, 0])
        assert scene.update() == 1
        res = scene.results()
        assert res["direction_status"].shape == (1, 2)
        assert res["direction_status"][0, 0] == int(expected)
        assert res["direction_status"][0, 1] == int(DS.NOT_COMPUTED)   # the static group is no target
        for d in range(2):
            assert int(scene.result(0, d).direction_status) == res["direction_status"][0, d]
