# SPDX-License-Identifier: MIT
"""10^5 queries (distance, penetration with its fields and contacts), 2.5x10^4
failing calls and 10^4 scene updates leave the resident set where it was."""
import os

import numpy as np
import pytest

import smartcollision as sc
from conftest import box

CALLS = 100_000
# A leak of a result object or an array (>= 100 bytes) per call would add >= 10 MB.
BOUND = 2 * 1024 * 1024


def rss():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def grows(step, calls=CALLS):
    for k in range(calls // 10):                 # warm-up: caches and free lists grow
        step(k)
    before = rss()
    for k in range(calls):
        step(k)
    return rss() - before


@pytest.fixture(scope="module")
def tracker():
    """A small box over a large one: cheap queries, so 10^5 of them stay short."""
    return sc.PairTracker(sc.Model(*box(0.3, 0.3, 0.3)), sc.Model(*box(1, 1, 1)))


def test_distance_calls(tracker):
    poses = [np.array([0.5 * np.sin(k / 50.0), 0, 1.5]) for k in range(100)]
    origin = np.zeros(3)
    assert grows(lambda k: tracker.distance(poses[k % 100], origin)) < BOUND


def test_penetration_calls(tracker):
    poses = [(np.array([0.1, 0, 1.25 - 0.1 * k / 10]), np.array([1.0, 0, 0, 0])) for k in range(10)]
    tracker.distance([0.1, 0, 1.5], np.eye(4))               # seen apart first

    def step(k):
        r = tracker.penetration(poses[k % 10], np.eye(4))
        assert r.penetrating or k % 10 == 0
        r.tpdv, r.contact_pose, r.target_feature.vertices
        tracker.contacts()
    assert grows(step) < BOUND


def test_error_calls(tracker):
    bad = np.array([np.nan, 0, 0])

    def step(_):
        try:
            tracker.distance(bad, bad)
        except sc.InvalidArgumentError:
            pass
    assert grows(step, CALLS // 4) < BOUND


def test_scene_updates():
    m = sc.Model(*box(0.4, 0.4, 0.4))
    scene = sc.Scene()
    for i in range(4):
        scene.add_object(i, m, [1.0 * i, 0, 0])
        scene.add_to_group(i, i)

    def step(k):
        scene.set_group_pose(k % 4, [1.0 * (k % 4), 0.01 * (k % 7), 0])
        scene.update()
        scene.results()
    assert grows(step, CALLS // 10) < BOUND
