#!/usr/bin/python3
"""Gallery of typical clumps, like Fig. 7 of Lu & McDowell (2007).

Reads the HDF5 archives written by `ballast clump -o FILE.h5` (layout in
study/clump_archive.hpp), one per sample, and draws one typical clump of each,
rendered as shaded spheres, with the sample's average number of balls per clump in
the title. "Typical" = the clump whose ball count is nearest the sample mean and,
among those, whose sphericity is nearest the sample's mean sphericity.

Example (the five Table 1 samples):
    for s in 1 2 3 4 5; do
      build/study/ballast clump --preset table1/sample$s --count 2000 --seed 1 \\
          -o out/table1_sample$s.h5
    done
    scripts/clump_gallery.py out/table1_sample{1,2,3,4,5}.h5 -o out/clump_gallery.png
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

LIGHT = np.array([0.4, -0.5, 0.8]) / np.linalg.norm([0.4, -0.5, 0.8])
BASE_COLOUR = np.array([0.62, 0.60, 0.55])  # grey-brown, like granite ballast


def read_sample(path):
    """Everything the gallery needs from one archive."""
    with h5py.File(path, "r") as f:
        if f.attrs.get("format") not in ("ballast-clumps", b"ballast-clumps"):
            sys.exit(f"{path}: not a ballast clump archive (format attribute missing)")
        attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
        return {
            "path": path,
            "attrs": attrs,
            "radius": f["balls/radius"][:],
            "offset": f["balls/offset"][:],
            "first": f["clumps/first_ball"][:],
            "count": f["clumps/ball_count"][:],
            "sphericity": f["shape/sphericity"][:],
        }


def typical_clump(sample):
    counts = sample["count"].astype(float)
    mean = counts.mean()
    nearest = np.abs(counts - mean)
    candidates = np.flatnonzero(nearest == nearest.min())
    sph = sample["sphericity"]
    return candidates[np.argmin(np.abs(sph[candidates] - sph.mean()))]


def sphere_polygons(centres, radii, n_lat=18, n_lon=32):
    """Quads of every ball's surface, minus those hidden inside another ball, shaded."""
    lat = np.linspace(0.0, np.pi, n_lat + 1)
    lon = np.linspace(0.0, 2.0 * np.pi, n_lon + 1)
    polys, colours = [], []
    for i, (c, r) in enumerate(zip(centres, radii)):
        for a in range(n_lat):
            for b in range(n_lon):
                corners = []
                for t, p in ((lat[a], lon[b]), (lat[a], lon[b + 1]), (lat[a + 1], lon[b + 1]),
                             (lat[a + 1], lon[b])):
                    corners.append(c + r * np.array([np.sin(t) * np.cos(p),
                                                     np.sin(t) * np.sin(p), np.cos(t)]))
                corners = np.array(corners)
                mid = corners.mean(axis=0)
                # Drop a quad only when all its corners are inside one other ball: it can
                # never be seen. Partly covered quads stay (the depth sort hides them).
                inside = np.linalg.norm(centres[None, :, :] - corners[:, None, :], axis=2)
                inside = np.all(inside < radii[None, :] * 0.999, axis=0)
                inside[i] = False
                if np.any(inside):
                    continue
                normal = (mid - c) / np.linalg.norm(mid - c)
                shade = 0.45 + 0.55 * max(0.0, float(normal @ LIGHT))
                polys.append(corners)
                colours.append(np.append(BASE_COLOUR * shade, 1.0))
    return polys, colours


def draw(ax, sample, index, label):
    a = sample["attrs"]
    first, n = int(sample["first"][index]), int(sample["count"][index])
    centres = sample["offset"][first:first + n] * 1e3  # mm
    radii = sample["radius"][first:first + n] * 1e3
    polys, colours = sphere_polygons(centres, radii)
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors="none"))
    half = 0.8 * float(a["virtual_radius"]) * 1e3
    for axis in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        axis(-half, half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=22, azim=35)
    ax.set_axis_off()
    mean = sample["count"].mean()
    ax.set_title(f"({label}) {a['preset']}\naverage {mean:.2f} balls per clump "
                 f"(this one {n})", fontsize=9)
    ax.text2D(0.5, -0.02,
              f"{int(a['directions'])} dirs, p {float(a['p']):.1f}, "
              f"c {float(a['c']):.1f}R, D3 {float(a['d3']):.1f}R, "
              f"{int(a['edge_balls'])} edge ball(s), {a['adjacency']}",
              transform=ax.transAxes, ha="center", fontsize=7)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("archives", nargs="+", help="HDF5 files from `ballast clump -o`")
    parser.add_argument("-o", "--output", default="clump_gallery.png", help="PNG to write")
    args = parser.parse_args()

    samples = [read_sample(p) for p in args.archives]
    fig = plt.figure(figsize=(3.4 * len(samples), 4.0))
    for k, sample in enumerate(samples):
        ax = fig.add_subplot(1, len(samples), k + 1, projection="3d")
        draw(ax, sample, typical_clump(sample), "abcdefghij"[k % 10])
    fig.suptitle("Typical clumps (cf. Lu & McDowell 2007, Fig. 7); axes in mm, "
                 "frame = principal axes", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.output, dpi=150)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
