#!/usr/bin/python3
"""How many of a sphere packing's open neighbour-list candidates nearly touch
(docs/PERFORMANCE.md, "What bought what": why the live lists' cover has a small
headroom; engine Simulation::live_cover_above).

    tests/bench/peers/near_gaps.py build/peers/spheres.txt

Reads an `x y z r` packing (SI units), takes the engine's default skin (0.2 × the
mean radius) and prints the candidate pairs (gap < skin), those touching (gap < 0)
and the open ones whose gap is within 1/64 skin and within 1 µm. Brute force over
all pairs, in chunks: fine for a few thousand spheres.
"""
import sys

import numpy as np


def main():
    a = np.loadtxt(sys.argv[1], comments="#", ndmin=2)
    if a.shape[1] != 4:
        sys.exit("near_gaps.py: expects an 'x y z r' sphere packing, got %d columns" % a.shape[1])
    x, r = a[:, :3], a[:, 3]
    skin = 0.2 * r.mean()
    gaps = []
    for i in range(len(r) - 1):
        d = np.linalg.norm(x[i + 1:] - x[i], axis=1) - (r[i + 1:] + r[i])
        gaps.append(d[d < skin])
    g = np.concatenate(gaps)
    open_ = g[g >= 0.0]
    print("balls %d, skin %.4g m" % (len(r), skin))
    print("candidates %d, touching %d, open %d" % (len(g), len(g) - len(open_), len(open_)))
    print("open within skin/64 (%.3g m): %d" % (skin / 64, (open_ <= skin / 64).sum()))
    print("open within 1 um: %d" % (open_ <= 1e-6).sum())


if __name__ == "__main__":
    main()
