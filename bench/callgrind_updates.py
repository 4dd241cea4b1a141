#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Instructions per update of the carried tracker from `warm_jump --callgrind-updates`
(any case; the PD case shown) run as

    valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file=OUT \\
        build/bench/warm_jump --only=pd --runs=1 --callgrind-updates

which writes OUT.1, OUT.2, ... (dump n counts update n - 1 of the path). Prints the
median, p99 and maximum over every update but the first (as warm_jump's PD target),
the same without the jump steps (every 200th), and the slowest updates.
Usage: callgrind_updates.py OUT [--jump-every=200] [--top=25]"""
import glob
import math
import re
import sys


def totals(prefix):
    counts = {}
    for name in glob.glob(glob.escape(prefix) + ".*"):
        match = re.fullmatch(re.escape(prefix) + r"\.(\d+)", name)
        if not match:
            continue
        with open(name) as f:
            for line in f:
                if line.startswith(("summary:", "totals:")):
                    counts[int(match.group(1)) - 1] = int(line.split()[1])
                    break
    return counts


def quantile(values, q):
    values = sorted(values)
    x = q * (len(values) - 1)
    lo = int(math.floor(x))
    hi = min(lo + 1, len(values) - 1)
    return values[lo] + (values[hi] - values[lo]) * (x - lo)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    options = dict(a[2:].split("=", 1) for a in sys.argv[1:] if a.startswith("--"))
    if len(args) != 1:
        sys.exit(__doc__)
    every = int(options.get("jump-every", 200))
    top = int(options.get("top", 25))
    counts = totals(args[0])
    steps = {k: v for k, v in counts.items() if k >= 1}
    if not steps:
        sys.exit("no dumps named %s.N" % args[0])
    ordinary = [v for k, v in steps.items() if k % every != 0]
    for label, values in (("all updates", list(steps.values())), ("without jumps", ordinary)):
        print("%-14s %5d updates: median %6.0f k, p99 %6.0f k, max %7.0f k, total %.1f M" %
              (label, len(values), quantile(values, 0.5) / 1e3, quantile(values, 0.99) / 1e3,
               max(values) / 1e3, sum(values) / 1e6))
    slowest = sorted(steps.items(), key=lambda kv: -kv[1])[:top]
    print("slowest: " + " ".join("%d:%.0fk" % (k, v / 1e3) for k, v in slowest))


if __name__ == "__main__":
    main()
