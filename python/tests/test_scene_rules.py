# SPDX-License-Identifier: MIT
"""The contacts of a pair touching at distance 0 (docs/api.md, "Contact points")."""
import numpy as np
import pytest

import smartcollision as sc
from conftest import box


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
