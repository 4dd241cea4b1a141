# SPDX-License-Identifier: MIT
"""Separate trackers on separate threads (queries run without the GIL) give what
they give alone; one object used by two threads at once refuses, never races."""
import threading
import time

import numpy as np

import smartcollision as sc
from conftest import box, torus


def run_path(tracker, shift):
    out = []
    for k in range(300):
        s = k / 299
        r = tracker.penetration(([1.0 + shift, 0.2 * s, 0.8 - 0.9 * s], [1, 0, 0, 0]), np.eye(4))
        out.append((int(r.status), r.distance, tuple(r.tpdv)))
    return out


def test_separate_trackers_in_threads():
    ring, cube = sc.Model(*torus(around=24, tube=12)), sc.Model(*box(0.25, 0.25, 0.25))
    shifts = [0.0, 0.02, 0.04, 0.06]
    serial = [run_path(sc.PairTracker(cube, ring), s) for s in shifts]
    results = [None] * len(shifts)
    errors = []

    def work(i):
        try:
            results[i] = run_path(sc.PairTracker(cube, ring), shifts[i])
        except Exception as e:  # noqa: BLE001  reported below
            errors.append(e)
    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(shifts))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert results == serial
    assert any(s[0] == int(sc.Status.OK) and s[1] < 0 for s in serial[0])


def test_shared_scene_refuses_while_updating():
    m = sc.Model(*torus(around=32, tube=16))
    scene = sc.Scene()
    for i in range(30):
        scene.add_object(i, m, [0.9 * (i % 6), 0.9 * (i // 6), 0])
        scene.add_to_group(i, i)
    done = threading.Event()
    counts = {"refused": 0, "served": 0}
    unexpected = []

    def updates():
        for _ in range(20):
            scene.update()
        done.set()
    worker = threading.Thread(target=updates)
    worker.start()
    while not done.is_set():
        try:
            scene.has_object(3)
            counts["served"] += 1
        except sc.InvalidOperationError:
            counts["refused"] += 1
        except Exception as e:  # noqa: BLE001
            unexpected.append(e)
    worker.join()
    assert not unexpected
    assert counts["served"] + counts["refused"] > 0
    # The scene is intact: one more update lists the same pairs as before.
    n = len(scene)
    assert scene.update() == n


def test_preprocessing_releases_the_gil():
    """While a model is preprocessed on one thread, another keeps running Python:
    with the GIL held it could not run at all inside the call's window."""
    v, f = torus(around=40, tube=20)
    window = {}

    def build():
        window["start"] = time.perf_counter()
        sc.Model(v, f)
        window["end"] = time.perf_counter()
    worker = threading.Thread(target=build)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    start, end = window["start"], window["end"]
    margin = 0.1 * (end - start)
    inside = [t for t in ticks if start + margin < t < end - margin]
    assert end - start > 0.02, "the build must be long enough to tell"
    assert len(inside) > 100
