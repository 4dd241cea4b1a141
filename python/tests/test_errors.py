# SPDX-License-Identifier: MIT
"""Bad input raises the exception of the library's error code, with its message,
and changes nothing."""
import os
import warnings

import numpy as np
import pytest

import smartcollision as sc
from conftest import box, torus


def test_hierarchy():
    assert issubclass(sc.InvalidArgumentError, sc.Error) and issubclass(sc.InvalidArgumentError, ValueError)
    assert issubclass(sc.InvalidGeometryError, ValueError)
    assert issubclass(sc.InvalidIdError, LookupError)
    assert issubclass(sc.InvalidOperationError, RuntimeError)
    assert issubclass(sc.InitialIntersectionError, sc.Error)
    assert issubclass(sc.CacheFileWarning, UserWarning)


@pytest.mark.parametrize("vertices, triangles, error, words", [
    (box()[0][:, :2], box()[1], sc.InvalidArgumentError, "shape (8, 2)"),
    (box()[0].ravel(), box()[1], sc.InvalidArgumentError, "expected (n, 3)"),
    (box()[0], box()[1][:, :2], sc.InvalidArgumentError, "triangles: shape"),
    (box()[0].astype(complex), box()[1], TypeError, "complex"),
    (box()[0].astype(str), box()[1], TypeError, "vertices"),
    (box()[0], box()[1].astype(float), TypeError, "triangles"),
    (np.where(np.arange(24).reshape(8, 3) == 5, np.nan, box()[0]), box()[1], sc.InvalidArgumentError, ""),
    (box()[0] * 1e101, box()[1], sc.InvalidArgumentError, ""),
    (box()[0], np.where(box()[1] == 7, 8, box()[1]), sc.InvalidArgumentError, "index"),
    (box()[0], np.where(box()[1] == 7, -1, box()[1]), sc.InvalidArgumentError, "index"),
    (box()[0], box()[1].astype(np.int64) + 2**40, sc.InvalidArgumentError, "out of range"),
    (box()[0], box()[1][:-1], sc.InvalidGeometryError, ""),
    (box()[0], box()[1][:, ::-1][[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10]].tolist() + [[1, 7, 3]],
     sc.InvalidGeometryError, ""),
])
def test_bad_mesh(vertices, triangles, error, words):
    with pytest.raises(error) as info:
        sc.Model(vertices, triangles)
    assert words in str(info.value)
    assert str(info.value), "the library's message is carried"


def test_soup_accepts_open_mesh_and_lists():
    v, f = box()
    m = sc.Model(v.tolist(), f[:-1].tolist(), kind=sc.ModelKind.TRIANGLE_SOUP)
    assert m.stats().triangles == 11


@pytest.mark.parametrize("pose, error", [
    ([0, 0, np.nan], sc.InvalidArgumentError),
    ([0, 0], sc.InvalidArgumentError),
    (np.eye(3), sc.InvalidArgumentError),
    (np.diag([1.0, 1.0, 2.0, 1.0]), sc.InvalidArgumentError),       # not a rotation
    (np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1.0]]), sc.InvalidArgumentError),
    (([0, 0, 3], [0, 0, 0, 0]), sc.InvalidArgumentError),              # zero quaternion
    (([0, 0, 3], [1, 0, 0]), sc.InvalidArgumentError),
    ([0, 0, 1e101], sc.InvalidArgumentError),
    ("abc", TypeError),
])
def test_bad_pose(pose, error):
    m = sc.Model(*box())
    tracker = sc.PairTracker(m, m)
    assert tracker.distance([0, 0, 3], [0, 0, 0]) == pytest.approx(1.0)
    with pytest.raises(error):
        tracker.distance(pose, [0, 0, 0])
    # Nothing changed: the tracker still follows the pair from where it was.
    assert tracker.tracking()
    assert tracker.distance([0, 0, 2.5], [0, 0, 0]) == pytest.approx(0.5)


@pytest.mark.parametrize("pose, words", [
    ([1, 0], r"shape \(2,\)"),       # a short position, not a (position, quaternion) pair
    (None, "None"),
    (([0, 0, 3], [1, 0, 0]), "quaternion"),
])
def test_bad_pose_says_what_is_wrong(pose, words):
    m = sc.Model(*box())
    with pytest.raises(sc.InvalidArgumentError, match=words):
        sc.PairTracker(m, m).distance(pose, [0, 0, 0])


def test_huge_unsigned_index_says_where():
    v, t = box()
    t = t.astype(np.uint64)
    t[2, 1] = 2**63
    with pytest.raises(sc.InvalidArgumentError, match=r"index at \[2, 1\] out of range"):
        sc.Model(v, t)


def test_bad_settings():
    m = sc.Model(*box())
    with pytest.raises(sc.InvalidArgumentError, match="tolerance"):
        sc.PairTracker(m, m, sc.Settings(tolerance=-1))
    tracker = sc.PairTracker(m, m)
    for bad in (sc.Settings(max_iterations=0), sc.Settings(safety_coefficient=1.5),
                sc.Settings(max_distance=float("nan")), sc.Settings(threads=100000),
                sc.Settings(proxy_travel_ratio=0.5)):
        with pytest.raises(sc.InvalidArgumentError):
            tracker.settings = bad
        with pytest.raises(sc.InvalidArgumentError):
            bad.validate()
    assert tracker.settings.max_iterations == sc.Settings().max_iterations
    assert sc.Settings(proxy_travel_ratio=2).proxy_travel_ratio == 2


def test_initial_intersection():
    m = sc.Model(*box())
    tracker = sc.PairTracker(m, m)
    with pytest.raises(sc.InitialIntersectionError):
        tracker.distance([0, 0, 1], [0, 0, 0])
    assert tracker.penetration([0, 0, 1], [0, 0, 0]).status == sc.Status.INVALID_INITIAL_TRANSFORMATION
    resolving = sc.PairTracker(m, m, sc.Settings(resolve_initial_intersection=True))
    assert resolving.distance([0, 0, 1.5], [0, 0, 0]) == pytest.approx(-0.5, abs=1e-3)


def test_direction_and_margin():
    m = sc.Model(*box())
    tracker = sc.PairTracker(m, m)
    tracker.distance([0, 0, 3], [0, 0, 0])
    with pytest.raises(sc.InvalidArgumentError):
        tracker.contacts(direction=2)
    with pytest.raises(sc.InvalidArgumentError):
        tracker.contacts(margin=-1.0)
    with pytest.raises(IndexError):
        m.stats(piece=1)


def scene_state(scene):
    return [scene.has_object(i) for i in (1, 2, 3)], [scene.group_of(i) for i in (1, 2)], scene.group_pose(5)


def test_scene_misuse_changes_nothing():
    m = sc.Model(*box())
    soup = sc.Model(*box(), kind=sc.ModelKind.TRIANGLE_SOUP)
    scene = sc.Scene()
    scene.add_object(1, m, [0, 0, 3])
    scene.add_object(2, m)
    scene.add_to_group(5, 1)
    before = scene_state(scene)
    misuse = [
        (lambda: scene.add_object(1, m), sc.InvalidIdError),            # duplicate id
        (lambda: scene.add_object(3, soup), sc.InvalidOperationError),  # wrong kind
        (lambda: scene.add_object(3, m, [np.inf, 0, 0]), sc.InvalidArgumentError),
        (lambda: scene.remove_object(7), sc.InvalidIdError),
        (lambda: scene.add_to_group(5, 9), sc.InvalidIdError),
        (lambda: scene.remove_from_group(6, 1), sc.InvalidIdError),
        (lambda: scene.set_group_pose(6, [0, 0, 0]), sc.InvalidIdError),
        (lambda: scene.set_group_pose(sc.STATIC_GROUP, [0, 0, 1]), sc.InvalidOperationError),
        (lambda: scene.set_group_activity(sc.STATIC_GROUP, sc.Activity.ACTIVE), sc.InvalidOperationError),
        (lambda: scene.set_pair_activity(5, 5, sc.PairActivity.ACTIVE), sc.InvalidArgumentError),
        (lambda: scene.set_group_pose(5, np.full(3, np.nan)), sc.InvalidArgumentError),
        (lambda: scene.group_pose(6), sc.InvalidIdError),
        (lambda: scene.result(0), IndexError),
    ]
    for call, error in misuse:
        with pytest.raises(error) as info:
            call()
        assert str(info.value)
        after = scene_state(scene)
        assert after[:2] == before[:2]
        np.testing.assert_array_equal(after[2], before[2])
    assert scene.update() == 1
    assert scene.results()["distance"][0, 0] == pytest.approx(1.0)
    # The direction is checked before anything of the pair is read (a bad one read past
    # the pair's two groups first, and the error then depended on the bytes there).
    for d in (2, -1, 3):
        with pytest.raises(sc.InvalidArgumentError, match="direction"):
            scene.result(0, d)


def test_cache_file(tmp_path):
    v, f = box()
    path = str(tmp_path / "box.sccache")
    first = sc.Model(v, f, cache_file=path)
    assert os.path.exists(path) and not first.stats().from_cache
    assert sc.Model(v, f, cache_file=path).stats().from_cache
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        m = sc.Model(v, f, cache_file=str(tmp_path / "missing" / "dir" / "box.sccache"))
    assert m.stats().triangles == 12
    assert any(issubclass(w.category, sc.CacheFileWarning) for w in caught)
    # A path object works; a number is not a path.
    assert sc.Model(v, f, cache_file=tmp_path / "box.sccache").stats().from_cache
    with pytest.raises(TypeError):
        sc.Model(v, f, cache_file=3)
    pieces = sc.Model.from_pieces([(v, f), (v + 3, f)], cache_files=[path, tmp_path / "second.sccache"])
    assert pieces.piece_count == 2 and pieces.stats(0).from_cache and not pieces.stats(1).from_cache


def test_build_threads(tmp_path):
    # A non-convex torus: the cache file is the same bytes on one and two threads.
    v, f = torus(around=48, tube=24)
    files = [tmp_path / "one.sccache", tmp_path / "two.sccache"]
    models = [sc.Model(v, f, cache_file=files[i], threads=i + 1) for i in range(2)]
    assert models[0].stats().patches == models[1].stats().patches > 1
    assert files[0].read_bytes() == files[1].read_bytes()
    assert sc.Model.from_pieces([(v, f)], threads=2).stats().patches == models[0].stats().patches
    for bad in (-1, 257):
        with pytest.raises(sc.InvalidArgumentError, match="threads"):
            sc.Model(v, f, threads=bad)
