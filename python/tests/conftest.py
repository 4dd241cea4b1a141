# SPDX-License-Identifier: MIT
"""Shared meshes and helpers of the Python tests."""
import os

import numpy as np
import pytest

from smartcollision.meshes import box, torus  # noqa: F401 (the tests import them from here)


def read_off(path):
    words = [w for line in open(path) for w in line.split("#")[0].split()]
    nv, nf = int(words[1]), int(words[2])
    v = np.array(words[4:4 + 3 * nv], float).reshape(nv, 3)
    rest = np.array(words[4 + 3 * nv:], int).reshape(nf, 4)
    return v, rest[:, 1:]


def quat_about(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * axis])


@pytest.fixture
def l_prism():
    return read_off(os.path.join(os.environ["SC_TEST_DATA_DIR"], "l_prism.off"))


@pytest.fixture
def reference_program():
    path = os.environ.get("SC_PYTHON_REFERENCE")
    if not path:
        pytest.fail("SC_PYTHON_REFERENCE is not set (run through ctest)")
    return path
