# SPDX-License-Identifier: MIT
"""SmartCollision: minimum distance and dynamic penetration depth (TPDV, RPDV)
between triangle meshes, from numpy arrays.

    import numpy as np, smartcollision as sc
    box = sc.Model(V, F)                      # V: float (n, 3), F: int (m, 3)
    tracker = sc.PairTracker(box, box)
    tracker.distance([0, 0, 3], np.eye(4))    # > 0 apart, <= 0 penetrating
    r = tracker.penetration([0, 0, 0.9], np.eye(4))
    r.tpdv, r.rpdv, r.contact_pose, r.normal

Poses are world-from-model: a 4x4 matrix, a position (3,), a (7,) array
(position, quaternion w, x, y, z) or a pair (position, quaternion).
See PairTracker, Scene, Model, Settings and Result.
"""
from ._core import *  # noqa: F401,F403

__version__ = "0.1.0"

