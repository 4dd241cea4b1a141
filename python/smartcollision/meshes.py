# SPDX-License-Identifier: MIT
"""Closed meshes to try the library with: a box and a torus, as (vertices, triangles)
numpy arrays with outward-facing triangles, ready for smartcollision.Model(*mesh)."""
import numpy as np


def box(hx=1.0, hy=1.0, hz=1.0):
    """A box of half extents hx, hy, hz centred at the origin."""
    v = np.array([[x, y, z] for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)], float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


def torus(major=1.0, minor=0.3, around=16, tube=8):
    """A torus about z (non-convex): `around` x `tube` quads, two triangles each."""
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
