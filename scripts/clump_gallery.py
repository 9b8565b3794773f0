#!/usr/bin/python3
"""Gallery of typical clumps, like Fig. 7 of Lu & McDowell (2007).

Reads the HDF5 archives written by `ballast clump -o FILE.h5` (layout in
study/archive/clump_archive.hpp), one per sample, and draws one typical clump of each,
rendered as shaded spheres, with the sample's average number of balls per clump in
the title. "Typical" = the clump whose ball count is nearest the sample mean and,
among those, whose sphericity is nearest the sample's mean sphericity. The drawing
is scripts/clump_render.py's, shared with scripts/figures.py.

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

from clump_render import draw_clump, parameter_caption, typical_clump  # noqa: E402


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


def draw(ax, sample, index, label):
    a = sample["attrs"]
    mean = sample["count"].mean()
    title = (f"({label}) {a['preset']}\naverage {mean:.2f} balls per clump "
             f"(this one {int(sample['count'][index])})")
    draw_clump(ax, sample, index, title, parameter_caption(a))


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
