#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Distance and penetration depth along a path, and speed against accuracy.

A box moves down through a torus's tube and back up, turning. For a sweep of
tolerances the signed distance (> 0 apart, -|TPDV| penetrating) is recorded at every
step with the time per query, and each reported contact pose is measured by a
fresh query: how far it is from touching is the accuracy the tolerance bounds. Writes a PNG (matplotlib's Agg backend: no display needed).

Usage: python3 depth_along_path.py [--out depth_along_path.png] [--steps 400]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import smartcollision as sc  # noqa: E402
from smartcollision.meshes import box, torus  # noqa: E402


def path(steps):
    """Down onto the top of the tube, to and fro across it pressed in (the depth
    follows the curved, faceted surface), and back up, turning about z."""
    s = np.linspace(0, 1, steps)
    x = 1.0 + 0.25 * np.sin(2 * np.pi * np.clip((s - 0.2) / 0.6, 0, 1))   # out, in, centre
    press = np.clip(np.minimum(s, 1 - s) / 0.2, 0, 1)           # 0 -> 1 -> 0
    height = 0.35 + 0.25 + 0.3 - 0.45 * press                   # bottom from 0.3 above to 0.15 in
    poses = []
    for k in range(steps):
        angle = 0.6 * s[k]
        q = [np.cos(angle / 2), 0, 0, np.sin(angle / 2)]
        poses.append(np.array([x[k], 0.05 * np.sin(6 * s[k]), height[k], *q]))
    return s, poses


def sweep(ring, cube, poses, tolerance, mode):
    """Signed distance at every pose, the mean time per query (us), and the largest
    gap between the reported contact pose and touching: what the tolerance bounds."""
    tracker = sc.PairTracker(cube, ring, sc.Settings(tolerance=tolerance, rotation_mode=mode))
    fixed = np.array([0.0, 0, 0, 1, 0, 0, 0])
    values = np.empty(len(poses))
    contacts = []
    start = time.perf_counter()
    for k, p in enumerate(poses):
        r = tracker.penetration(p, fixed)
        values[k] = r.distance
        if r.penetrating:
            contacts.append(r.contact_pose)
    us = (time.perf_counter() - start) / len(poses) * 1e6
    # A fresh tracker measures each contact pose: its distance, or its depth (EPA)
    # when it still overlaps.
    probe = sc.Settings(tolerance=1e-7, resolve_initial_intersection=True)
    gaps = [abs(sc.PairTracker(cube, ring, probe).distance(c, fixed)) for c in contacts]
    return values, us, max(gaps, default=0.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="depth_along_path.png")
    parser.add_argument("--steps", type=int, default=400)
    args = parser.parse_args()
    ring, cube = sc.Model(*torus(1.0, 0.35, 48, 24)), sc.Model(*box(0.25, 0.25, 0.25))
    s, poses = path(args.steps)
    tolerances = [3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 8))
    print("mode  tolerance  us/query  max |contact pose gap|")
    for mode, marker in ((sc.RotationMode.INPUT, "o-"), (sc.RotationMode.FREE, "s--")):
        errors, speeds = [], []
        for tol in tolerances:
            values, us, gap = sweep(ring, cube, poses, tol, mode)
            errors.append(gap)
            speeds.append(us)
            if tol in (tolerances[0], 1e-3):
                top.plot(s, values, marker[1:] or "-", label=f"{mode.name}, tolerance {tol:g}")
            print(f"{mode.name:5s} {tol:8.0e} {us:9.1f} {gap:12.2e}")
        bottom.loglog(speeds, errors, marker, label=f"{mode.name} rotation mode")
        for tol, x, y in zip(tolerances, speeds, errors):
            bottom.annotate(f"{tol:g}", (x, y), fontsize=7)
    bottom.loglog(speeds, tolerances, alpha=0)  # keeps the tolerances' range in view
    top.axhline(0, color="grey", lw=0.5)
    top.set(xlabel="path parameter", ylabel="distance / -|TPDV|", title="box through a torus")
    top.legend(fontsize=8)
    bottom.set(xlabel="time per query (us)", ylabel="max gap of the contact pose to touching",
               title="speed against accuracy over a tolerance sweep")
    bottom.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
