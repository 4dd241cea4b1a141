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


def torus(major=0.5, minor=0.15, around=24, tube=12):
    u = 2 * np.pi * np.arange(around) / around
    w = 2 * np.pi * np.arange(tube) / tube
    uu, ww = np.meshgrid(u, w, indexing="ij")
    r = major + minor * np.cos(ww)
    v = np.stack([r * np.cos(uu), r * np.sin(uu), minor * np.sin(ww)], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(around), np.arange(tube), indexing="ij")
    a, d = i * tube + j, i * tube + (j + 1) % tube
    b, c = ((i + 1) % around) * tube + j, ((i + 1) % around) * tube + (j + 1) % tube
    return v, np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])


def box(hx, hy, hz):
    v = np.array([[x, y, z] for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)], float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


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
    ring, brick = sc.Model(*torus()), sc.Model(*box(0.3, 0.2, 0.1))
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
