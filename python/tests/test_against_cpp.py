# SPDX-License-Identifier: MIT
"""The module gives, bit for bit, what the C++ API gives on the same inputs:
sc_python_reference runs sc::PairTracker on the poses the test writes and prints
every field; the same poses go through smartcollision.PairTracker.update."""
import subprocess

import numpy as np
import pytest

import smartcollision as sc
from conftest import box, quat_about, torus


def path_poses(n, seed):
    """a moves from apart, through b, and out again, turning; b turns slowly."""
    rng = np.random.default_rng(seed)
    axis_a, axis_b = rng.normal(size=3), rng.normal(size=3)
    poses = []
    for k in range(n):
        s = k / (n - 1)
        pos_a = np.array([2.6 - 4.0 * s, 0.3 * np.sin(5 * s), 0.2])
        pos_b = np.array([0.0, 0.0, 0.05 * s])
        poses.append(((pos_a, quat_about(axis_a, 0.8 * s)), (pos_b, quat_about(axis_b, 0.1 * s))))
    return poses


def reference(program, kind, settings, centers, meshes, poses):
    lines = [f"kind {int(kind)}",
             f"settings {settings.tolerance!r} {int(settings.rotation_mode)} {settings.max_iterations} "
             f"{int(settings.resolve_initial_intersection)} {settings.max_distance!r}"]
    for name, c in zip(("center_a", "center_b"), centers):
        lines.append(name + " " + " ".join(repr(float(x)) for x in c))
    for v, f in meshes:
        lines.append(f"mesh {len(v)} {len(f)}")
        lines += [" ".join(repr(float(x)) for x in row) for row in v]
        lines += [" ".join(str(int(i)) for i in row) for row in f]
    lines.append(f"poses {len(poses)}")
    for (pa, qa), (pb, qb) in poses:
        lines.append(" ".join(repr(float(x)) for x in [*pa, *qa, *pb, *qb]))
    out = subprocess.run([program], input="\n".join(lines) + "\n", capture_output=True, text=True,
                         check=True).stdout
    return [line.split() for line in out.splitlines()]


def flatten(result, contacts):
    """The module's result in the reference program's field order."""
    fields = [int(result.status), result.distance]
    for v in (result.normal, result.point_on_target, result.point_on_opponent, result.tpdv,
              result.rpdv, result.contact_position, result.contact_orientation):
        fields += list(v)
    fields += [result.target_object, result.opponent_object, result.target_piece, result.opponent_piece]
    for feat in (result.target_feature, result.opponent_feature):
        verts = list(feat.vertices) + [-1] * (3 - len(feat.vertices))
        fields += [int(feat.type), *verts, int(feat.is_virtual)]
    fields.append(len(contacts["separation"]))
    for k in range(len(contacts["separation"])):
        for name in ("point_on_target", "point_on_opponent", "normal"):
            fields += list(contacts[name][k])
        fields.append(contacts["separation"][k])
        fields += [int(contacts[name][k]) for name in
                   ("target_object", "opponent_object", "target_piece", "opponent_piece")]
    return fields


def parse(tokens):
    return [float(t) if any(c in t for c in ".eEn") else int(t) for t in tokens]


@pytest.mark.parametrize("mode", list(sc.RotationMode.__members__.values()))
@pytest.mark.parametrize("shapes", ["torus-box", "prism-torus"])
def test_tracker_equals_cpp(reference_program, l_prism, mode, shapes):
    meshes = {"torus-box": (torus(), box(0.4, 0.4, 0.4)), "prism-torus": (l_prism, torus())}[shapes]
    settings = sc.Settings(tolerance=2e-3, rotation_mode=mode, max_iterations=20)
    centers = (np.array([0.1, -0.2, 0.05]), np.zeros(3))
    poses = path_poses(40, seed=int(mode) + 7 * len(shapes))
    expected = reference(reference_program, sc.ModelKind.CLOSED_POLYHEDRON, settings, centers, meshes, poses)

    a, b = (sc.Model(v, f) for v, f in meshes)
    tracker = sc.PairTracker(a, b, settings, center_a=centers[0], center_b=centers[1])
    got = []
    penetrating = 0
    for pa, pb in poses:
        results = tracker.update(pa, pb)
        penetrating += results[0].penetrating
        for d, r in enumerate(results):
            got.append(flatten(r, tracker.contacts(d)))
    assert penetrating > 5, "the path must go through penetration"
    assert len(got) == len(expected)
    for k, (g, e) in enumerate(zip(got, expected)):
        assert g == parse(e), f"pose {k // 2}, direction {k % 2}"


def test_soup_equals_cpp(reference_program):
    meshes = (torus(), box(0.3, 0.3, 0.3))
    settings = sc.Settings()
    poses = path_poses(20, seed=3)
    expected = reference(reference_program, sc.ModelKind.TRIANGLE_SOUP, settings, (np.zeros(3),) * 2,
                         meshes, poses)
    a, b = (sc.Model(v, f, kind=sc.ModelKind.TRIANGLE_SOUP) for v, f in meshes)
    tracker = sc.PairTracker(a, b)
    for k, (pa, pb) in enumerate(poses):
        for d, r in enumerate(tracker.update(pa, pb)):
            assert flatten(r, tracker.contacts(d)) == parse(expected[2 * k + d]), f"pose {k}"


def test_scene_equals_tracker(l_prism):
    """The same pair through a Scene (groups, results as arrays) and a PairTracker.
    The scene composes each object's pose with its group's: poses differ by
    rounding (1e-16), which the proxy's iterations carry into the depth (1e-12
    measured), six orders below the tolerance; hence 1e-9 here, not bit equality."""
    prism, ring = sc.Model(*l_prism), sc.Model(*torus())
    scene = sc.Scene()
    scene.add_object(10, prism, center=[0.1, -0.2, 0.05])
    scene.add_object(20, ring)
    scene.add_to_group(1, 10)
    scene.add_to_group(2, 20)
    tracker = sc.PairTracker(prism, ring, center_a=[0.1, -0.2, 0.05])
    for (pa, qa), (pb, qb) in path_poses(30, seed=11):
        scene.set_group_pose(1, (pa, qa))
        scene.set_group_pose(2, (pb, qb))
        assert scene.update() == 1
        res = scene.results()
        assert res["groups"].tolist() == [[1, 2]]
        ra, rb = tracker.update((pa, qa), (pb, qb))
        for d, r in enumerate((ra, rb)):
            assert res["status"][0, d] == int(r.status)
            if not r.ok:
                assert np.isnan(res["distance"][0, d])
                continue
            assert res["distance"][0, d] == pytest.approx(r.distance, rel=0, abs=1e-9)
            for name in ("normal", "tpdv", "rpdv", "contact_position", "contact_orientation",
                         "point_on_target", "point_on_opponent"):
                np.testing.assert_allclose(res[name][0, d], getattr(r, name), rtol=0, atol=1e-9)
            assert res["target_object"][0, d] == (10, 20)[d]
            single = scene.result(0, d)
            np.testing.assert_allclose(single.contact_pose, r.contact_pose, rtol=0, atol=1e-9)
