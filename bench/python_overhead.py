#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Per-call cost of the Python binding over the C++ call on the same query.

Two boxes (a cheap query, so the binding's share shows), the same 64-pose cycles as
bench/python_overhead.cpp: apart (distance) and penetrating (penetration). Prints
ns per call of each side and their difference; --check fails when the difference of
distance() with (7,) arrays exceeds the 2 us target. The two sides are timed in
alternating rounds and each keeps its fastest round, so that load from other
processes, which only slows a round down, cancels out.

Usage (from a build with the module and the benchmarks):
  PYTHONPATH=build/python python3 bench/python_overhead.py build/bench/python_overhead [--check]
"""
import argparse
import subprocess
import time

import numpy as np

import smartcollision as sc

POSES = 64
TARGET_NS = 2000.0


def box(hx, hy, hz):
    v = np.array([[x, y, z] for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)], float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return sc.Model(v, f)


def cycle(height):
    a = 2 * np.pi * np.arange(POSES) / POSES
    return [np.array([0.1 * np.cos(t), 0.1 * np.sin(t), height + 0.02 * np.sin(t), 1.0, 0, 0, 0.02 * np.sin(t)])
            for t in a]


def per_call(call, poses, calls):
    origin = np.array([0.0, 0, 0, 1, 0, 0, 0])
    for i in range(calls // 10):
        call(poses[i % POSES], origin)
    items = [poses[i % POSES] for i in range(calls)]
    start = time.perf_counter_ns()
    for p in items:
        call(p, origin)
    return (time.perf_counter_ns() - start) / calls


def python_side(calls):
    a, b = box(1, 1, 1), box(2, 0.5, 0.5)
    out = {}
    for name, height, query in (("apart", 3.0, "distance"), ("penetrating", 1.4, "distance"),
                                ("penetrating_result", 1.4, "penetration")):
        tracker = sc.PairTracker(a, b)
        tracker.distance(cycle(3.0)[0], [0, 0, 0])
        out[name] = per_call(getattr(tracker, query), cycle(height), calls)
    tracker = sc.PairTracker(a, b)
    matrices = []
    for p in cycle(3.0):
        w, x, y, z = p[3:] / np.linalg.norm(p[3:])
        m = np.eye(4)
        m[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
        m[:3, 3] = p[:3]
        matrices.append(m)
    out["apart_matrix"] = per_call(tracker.distance, matrices, calls)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cpp", help="path of the python_overhead C++ program")
    parser.add_argument("--calls", type=int, default=100000)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--check", action="store_true", help="exit 1 above the 2 us target")
    args = parser.parse_args()
    cpp, py = {}, {}
    for _ in range(args.rounds):
        text = subprocess.run([args.cpp, str(args.calls)], capture_output=True, text=True,
                              check=True).stdout
        for k, v in (line.split() for line in text.splitlines()):
            cpp[k] = min(cpp.get(k, float("inf")), float(v))
        for k, v in python_side(args.calls).items():
            py[k] = min(py.get(k, float("inf")), v)
    print("| query | C++ ns/call | Python ns/call | overhead ns/call |")
    print("|---|---:|---:|---:|")
    rows = (("distance(), apart, (7,) arrays", "apart", "apart"),
            ("distance(), apart, 4x4 matrices", "apart", "apart_matrix"),
            ("distance(), penetrating, (7,) arrays", "penetrating", "penetrating"),
            ("penetration() -> Result, penetrating", "penetrating", "penetrating_result"))
    for label, c, p in rows:
        print(f"| {label} | {cpp[c]:.0f} | {py[p]:.0f} | {py[p] - cpp[c]:.0f} |")
    overhead = py["apart"] - cpp["apart"]
    print(f"overhead of distance(): {overhead:.0f} ns per call (target < {TARGET_NS:.0f})")
    if args.check and overhead >= TARGET_NS:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
