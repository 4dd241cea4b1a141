#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Per-call cost of the Python binding over the C++ call on the same query.

Two boxes (a cheap query, so the binding's share shows), the same 64-pose cycles as
bench/python_overhead.cpp: apart and penetrating. The C++ half is a library loaded
with ctypes; the two halves alternate in short rounds in one process and each round
gives a difference, so load from other processes, which drifts slowly, cancels out.
Prints the medians over the rounds; --check fails when the median overhead of
distance() with (7,) arrays is 2 us or more.

Usage (from a build with the module and the benchmarks):
  PYTHONPATH=build/python python3 bench/python_overhead.py build/bench/python_overhead.so [--check]
"""
import argparse
import ctypes
import statistics
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


def matrix(p):
    w, x, y, z = p[3:] / np.linalg.norm(p[3:])
    m = np.eye(4)
    m[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    m[:3, 3] = p[:3]
    return m


def python_case(query, poses, calls):
    """A function timing `calls` queries (ns per call), the tracker carrying on."""
    a, b = box(1, 1, 1), box(2, 0.5, 0.5)
    tracker = sc.PairTracker(a, b)
    tracker.distance(cycle(3.0)[0], [0, 0, 0])
    call = getattr(tracker, query)
    origin = np.array([0.0, 0, 0, 1, 0, 0, 0])
    items = [poses[i % POSES] for i in range(calls)]

    def timed():
        start = time.perf_counter_ns()
        for p in items:
            call(p, origin)
        return (time.perf_counter_ns() - start) / calls
    return timed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cpp", help="path of the python_overhead library")
    parser.add_argument("--calls", type=int, default=20000, help="queries per round")
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--check", action="store_true", help="exit 1 at or above the 2 us target")
    args = parser.parse_args()
    native = ctypes.CDLL(args.cpp).sc_bench_cpp_ns
    native.restype, native.argtypes = ctypes.c_double, [ctypes.c_int, ctypes.c_long]
    cases = (("distance(), apart, (7,) arrays", 0, python_case("distance", cycle(3.0), args.calls)),
             ("distance(), apart, 4x4 matrices", 0,
              python_case("distance", [matrix(p) for p in cycle(3.0)], args.calls)),
             ("distance(), penetrating, (7,) arrays", 1, python_case("distance", cycle(1.4), args.calls)),
             ("penetration() -> Result, penetrating", 1, python_case("penetration", cycle(1.4), args.calls)))
    print("| query | C++ ns/call | Python ns/call | overhead ns/call |")
    print("|---|---:|---:|---:|")
    first = None
    for label, penetrating, timed in cases:
        timed(), native(penetrating, args.calls)                    # warm-up
        cpp, py = [], []
        for _ in range(args.rounds):
            cpp.append(native(penetrating, args.calls))
            py.append(timed())
        overhead = statistics.median(p - c for p, c in zip(py, cpp))
        first = overhead if first is None else first
        print(f"| {label} | {statistics.median(cpp):.0f} | {statistics.median(py):.0f} | {overhead:.0f} |")
    print(f"overhead of distance(): {first:.0f} ns per call (target < {TARGET_NS:.0f})")
    if args.check and first >= TARGET_NS:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
