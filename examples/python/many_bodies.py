#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A scene of many bodies: tori and boxes drifting in a box-shaped room.

Each body is its own group, moved every frame with set_group_pose; the floor is a
static object. The motion is scripted, not simulated: bodies pass through one
another, and a pair's depth keeps growing while its tracked contact pose stays
outside. Every frame update() lists the pairs within reach and results()
gives them as arrays: the script counts contacts and penetrations and reports the
deepest one and the time per frame.

Usage: python3 many_bodies.py [--bodies 40] [--frames 100] [--threads 0]
"""
import argparse
import time

import numpy as np

import smartcollision as sc
from smartcollision.meshes import box, torus


def quaternion(rotvec):
    angle = np.linalg.norm(rotvec)
    if angle < 1e-12:
        return np.array([1.0, 0, 0, 0])
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * rotvec / angle])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bodies", type=int, default=40)
    parser.add_argument("--frames", type=int, default=100)
    parser.add_argument("--threads", type=int, default=0, help="scene threads (0: automatic)")
    args = parser.parse_args()
    rng = np.random.default_rng(1)
    ring, brick = sc.Model(*torus(0.5, 0.15, 24, 12)), sc.Model(*box(0.3, 0.2, 0.1))
    floor = sc.Model(*box(5, 5, 0.1))
    scene = sc.Scene()
    scene.settings = sc.Settings(tolerance=1e-3, max_distance=0.2, threads=args.threads,
                                 resolve_initial_intersection=True)
    scene.add_object(0, floor, [0, 0, -0.1])                 # static: never moves
    side = int(np.ceil(np.sqrt(args.bodies)))
    start = np.array([[1.4 * (k % side) - 0.7 * side, 1.4 * (k // side) - 0.7 * side, 0.6]
                      for k in range(args.bodies)])
    velocity = rng.normal(scale=0.01, size=(args.bodies, 3))
    spin = rng.normal(scale=0.02, size=(args.bodies, 3))
    for k in range(args.bodies):
        scene.add_object(k + 1, ring if k % 2 == 0 else brick, start[k])
        scene.add_to_group(k + 1, k + 1)                   # one group per body
    position, rotvec = start.copy(), np.zeros((args.bodies, 3))
    seconds, deepest, pairs_seen = 0.0, 0.0, 0
    for frame in range(args.frames):
        position += velocity
        position[:, 2] -= 0.004                          # settling towards the floor
        rotvec += spin
        for k in range(args.bodies):
            scene.set_group_pose(k + 1, (position[k], quaternion(rotvec[k])))
        t0 = time.perf_counter()
        n = scene.update()
        seconds += time.perf_counter() - t0
        res = scene.results()
        ok = res["status"] == int(sc.Status.OK)
        depth = np.where(ok, -res["distance"], -np.inf)
        penetrating = int(np.sum(depth >= 0))
        pairs_seen += n
        if n and depth.max() > deepest:
            deepest = float(depth.max())
        if frame % max(1, args.frames // 10) == 0:
            print(f"frame {frame:4d}: {n:3d} pairs within 0.2, {penetrating:3d} directions penetrating")
    print(f"{args.bodies} bodies, {args.frames} frames: {seconds / args.frames * 1e3:.2f} ms per update, "
          f"{pairs_seen / args.frames:.1f} pairs per frame, deepest penetration {deepest:.4f}")


if __name__ == "__main__":
    main()
