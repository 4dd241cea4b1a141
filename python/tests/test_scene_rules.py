# SPDX-License-Identifier: MIT
"""A scene's results between two updates, add_to_group on an object already in a
group, and the contacts of a pair touching at distance 0 (docs/python.md)."""
import numpy as np
import pytest

import smartcollision as sc
from conftest import box


def test_results_of_a_removed_object_stay_until_the_next_update():
    cube = sc.Model(*box(0.5, 0.5, 0.5))
    scene = sc.Scene()
    scene.add_object(1, cube, [0, 0, 3], center=[0.1, 0.2, 0])
    scene.add_object(2, cube)
    scene.add_to_group(10, 1)
    assert scene.update() == 1
    before, first = scene.results(), scene.result(0, 0)
    scene.remove_object(1)
    assert not scene.has_group(10)
    # The last update's pair, as results() and result() both read it.
    after = scene.results()
    for name, values in before.items():
        np.testing.assert_array_equal(after[name], values, err_msg=name)
    stale = scene.result(0, 0)
    assert stale.distance == first.distance == pytest.approx(2.0)
    assert stale.target_object == 1
    np.testing.assert_array_equal(stale.contact_pose, first.contact_pose)
    assert len(scene.contacts(0, 0)["separation"]) == 0  # contact_points is off
    assert scene.update() == 0
    with pytest.raises(IndexError):
        scene.result(0, 0)


def test_add_to_group_moves_an_object_from_another_group():
    cube = sc.Model(*box(0.5, 0.5, 0.5))
    scene = sc.Scene()
    scene.add_object(1, cube, [0, 0, 3])
    scene.add_to_group(5, 1)
    scene.set_group_pose(5, [1, 2, 3])
    pose = scene.object_pose(1)
    scene.add_to_group(6, 1)
    assert scene.group_of(1) == 6
    assert not scene.has_group(5)
    np.testing.assert_allclose(scene.object_pose(1), pose, atol=1e-12)
    scene.add_to_group(6, 1)  # its own group again: nothing changes
    assert scene.group_of(1) == 6
    with pytest.raises(sc.InvalidIdError):
        scene.remove_from_group(5, 1)


@pytest.mark.parametrize("gap", [0.0, 1e-12, -1e-12])
def test_cubes_touching_face_to_face_list_their_contact(gap):
    cube = sc.Model(*box(0.5, 0.5, 0.5))
    top = [0.25, 0.25, 1.0 + gap]
    tracker = sc.PairTracker(cube, cube)
    result, _ = tracker.update(top, [0, 0, 0])
    assert result.direction_status == sc.DirectionStatus.TOUCHING
    scene = sc.Scene()
    scene.settings = sc.Settings(contact_points=True)
    scene.add_object(1, cube, top)
    scene.add_object(2, cube)
    scene.add_to_group(1, 1)
    assert scene.update() == 1
    for contacts in (tracker.contacts(0), scene.contacts(0, 0)):
        assert len(contacts["separation"]) == 1
        assert contacts["separation"][0] == pytest.approx(gap, abs=1e-9)
        np.testing.assert_allclose(contacts["normal"][0], [0, 0, 1], atol=1e-9)
        np.testing.assert_allclose(contacts["point_on_opponent"][0][2], 0.5, atol=1e-9)
        np.testing.assert_allclose(contacts["point_on_target"][0], contacts["point_on_opponent"][0],
                                   atol=1e-9)
