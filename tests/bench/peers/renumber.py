#!/usr/bin/python3
"""Renumber the bodies of a packing file cell by cell along a chosen slowest axis.

    renumber.py IN OUT --slowest x|y|z

Our engine splits the bodies between threads by index, so the slowest axis of the
numbering is the one the boundary between two threads' shares cuts; the balls in a
contact across it are read by one core and written by the other every step. The
bed generator numbers bodies across the settled bed's smallest section
(cases/sphere_packing.hpp); a file brought from another code keeps its own order,
and this script renumbers it the same way. It also makes the comparison of
docs/PERFORMANCE.md, "Numbering along the bed's smallest section": the same bed
numbered with x slowest and with z slowest.

Cells are cubes of the largest ball diameter; a body goes to the cell of its mean
ball centre; cells are taken with the chosen axis slowest, then the others in the
order z, y, x, and bodies within a cell in their order in the file. A clump's balls
stay together and in their order. Every number is written back with repr(), which is
exact: the positions do not change by a bit. It prints how many touching contacts
(ball pairs of different bodies) lie across the middle of the numbering before and
after: those two threads' equal shares would meet across.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from packing import read_packing  # noqa: E402

AXES = {"x": 0, "y": 1, "z": 2}


def order(packing, slowest):
    """Body indices in the new order."""
    cell = 2.0 * packing.max_radius()
    lo = [min(c[d] for c in packing.centres) for d in range(3)]
    axes = [slowest] + [d for d in (2, 1, 0) if d != slowest]

    def key(k):
        members = packing.bodies[k]
        mean = [sum(packing.centres[i][d] for i in members) / len(members) for d in range(3)]
        return tuple(math.floor((mean[d] - lo[d]) / cell) for d in axes) + (k,)

    return sorted(range(len(packing.bodies)), key=key)


def touching_across_middle(packing, rank):
    """Touching ball pairs of different bodies whose bodies lie on either side of the
    middle of the numbering `rank` (body -> its number): the contacts two threads'
    equal shares would meet across."""
    cell = 2.0 * packing.max_radius()
    body_of = [0] * packing.balls
    for k, members in enumerate(packing.bodies):
        for i in members:
            body_of[i] = k
    grid = {}
    for i, c in enumerate(packing.centres):
        grid.setdefault(tuple(math.floor(v / cell) for v in c), []).append(i)
    middle = len(packing.bodies) / 2.0
    count = 0
    for (cx, cy, cz), members in grid.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get((cx + dx, cy + dy, cz + dz), ()):
                        for i in members:
                            if j <= i or body_of[i] == body_of[j]:
                                continue
                            if (rank[body_of[i]] < middle) == (rank[body_of[j]] < middle):
                                continue
                            reach = packing.radii[i] + packing.radii[j]
                            if sum((a - b) ** 2 for a, b in zip(packing.centres[i],
                                                                packing.centres[j])) < reach * reach:
                                count += 1
    return count


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--slowest", choices=sorted(AXES), required=True)
    a = ap.parse_args()
    p = read_packing(a.input)
    new_order = order(p, AXES[a.slowest])
    rank = [0] * len(new_order)
    for new, k in enumerate(new_order):
        rank[k] = new
    print(f"touching contacts across the middle of the numbering: "
          f"{touching_across_middle(p, list(range(len(new_order))))} in {a.input}, "
          f"{touching_across_middle(p, rank)} renumbered with {a.slowest} slowest")
    lines = [f"# {os.path.basename(a.input)} renumbered cell by cell, {a.slowest} slowest "
             f"(tests/bench/peers/renumber.py)"]
    for new, k in enumerate(new_order):
        for i in p.bodies[k]:
            x, y, z = p.centres[i]
            ball = f"{x!r} {y!r} {z!r} {p.radii[i]!r}"
            lines.append(f"{new} {ball}" if p.clumps else ball)
    with open(a.output, "w") as f:
        f.write("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
