# SPDX-License-Identifier: MIT
"""Shared meshes and helpers of the Python tests."""
import os

import numpy as np
import pytest


def box(hx=1.0, hy=1.0, hz=1.0):
    """A closed box centred at the origin, outward triangles."""
    v = np.array([[x, y, z] for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)], float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


def torus(major=1.0, minor=0.3, around=16, tube=8):
    """A closed, non-convex torus about z, consistently oriented."""
    u = 2 * np.pi * np.arange(around) / around
    w = 2 * np.pi * np.arange(tube) / tube
    uu, ww = np.meshgrid(u, w, indexing="ij")
    r = major + minor * np.cos(ww)
    v = np.stack([r * np.cos(uu), r * np.sin(uu), minor * np.sin(ww)], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(around), np.arange(tube), indexing="ij")
    a = i * tube + j
    b = ((i + 1) % around) * tube + j
    c = ((i + 1) % around) * tube + (j + 1) % tube
    d = i * tube + (j + 1) % tube
    f = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return v, f


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
