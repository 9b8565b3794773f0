#!/usr/bin/python3
"""The figures of Lu & McDowell (2007) from a ballast archive, as PNG files.

    /usr/bin/python3 scripts/figures.py ARCHIVE.h5 --out DIR [--runs ID1,ID2]

ARCHIVE is a study archive (`ballast study -o`, every run with status ok) or a single
run (`ballast run -o`). Writes into DIR, one line per file on stdout:

  fig07_clumps.png                 a typical clump of each clump run (Fig. 7)
  fig10_contacts_before.png        contact forces before loading, every run (Fig. 10)
  fig11_contacts_<id>.png          sphere run: before, at peak, after unloading (Fig. 11)
  fig12_contacts_<id>.png          clump run, the same (Fig. 12)
  fig13_rotations_<id>.png         sphere run: loading, unloading, cycle (Fig. 13)
  fig14_rotations_<id>.png         clump run, the same (Fig. 14)
  fig15_displacements_<id>.png     sphere run: at peak and after the cycle (Fig. 15)
  fig16_displacements_<id>.png     clump run at the same scale (Fig. 16)
  fig17_displacements_<id>.png     clump run magnified (Fig. 17), when it needs it
  fig18_load_deformation.png       sleeper force against settlement, every run (Fig. 18)
  fig_zones.png                    top layer beneath and beside the sleeper: mean vertical
                                   displacement per sample, with the paper's directions
                                   (archives with zones/; cf. Figs 15-17)
  fig_cycles.png                   permanent and resilient settlement against the number
                                   of load cycles, per sample (runs of two cycles or more)

What each shows and what to look for: docs/FIGURES.md. A figure that the archive
cannot give (no clump templates in a single-run file, a run stopped before loading,
no zones/ in an archive written before runs measured them) is left out with a line
on stderr. Exit status 0 when every figure that could be drawn was; 1 when the
archive is unreadable, has no usable run, or a figure failed.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ballast_archive import (ArchiveError, add_run_arguments, chosen_runs,  # noqa: E402
                             open_archive)
from clump_render import draw_clump, parameter_caption, typical_clump  # noqa: E402
from fig_common import LETTERS, MM, save  # noqa: E402
from fig_contacts import contacts_before, contacts_per_run  # noqa: E402
from fig_cycles import cycles_figure  # noqa: E402
from fig_displacements import displacements  # noqa: E402
from fig_rotations import rotations_per_run  # noqa: E402
from fig_zones import zone_figure  # noqa: E402


GALLERY_COLUMNS = 5  # clumps per row in Fig. 7, as the paper's five samples


def note(text):
    print(f"figures.py: {text}", file=sys.stderr)


def clump_gallery(runs, out_dir):
    """Fig. 7: the typical clump of each clump run whose templates the archive holds."""
    samples = [(r, r.clump_templates()) for r in runs if r.is_clumps]
    for r, s in samples:
        if s is None:
            note(f"Fig. 7: run '{r.id}' holds no clump templates (an archive written "
                 "before runs stored them): left out")
    samples = [(r, s) for r, s in samples if s is not None and len(s["count"])]
    if not samples:
        return []
    cols = min(len(samples), GALLERY_COLUMNS)
    rows = -(-len(samples) // cols)
    fig = plt.figure(figsize=(max(3.4 * cols, 5.0), 4.0 * rows))
    for k, (run, sample) in enumerate(samples):
        ax = fig.add_subplot(rows, cols, k + 1, projection="3d")
        index = typical_clump(sample)
        title = (f"({LETTERS[k % 26]}) {run.id}: {run.shape}\naverage "
                 f"{sample['count'].mean():.2f} balls per clump (this one "
                 f"{int(sample['count'][index])})")
        draw_clump(ax, sample, index, title, parameter_caption(sample["attrs"]))
    fig.suptitle("Typical clump of each clump run (cf. Fig. 7), principal frame", fontsize=9)
    return [save(fig, out_dir, "fig07_clumps")]


def load_deformation(runs, out_dir):
    """Fig. 18: sleeper force against sleeper settlement through the cycle."""
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for run in runs:
        settlement = run.data("series/settlement") * MM
        force = run.data("series/sleeper_force") / 1e3
        ax.plot(settlement, force, lw=1.2, label=f"{run.label}: permanent "
                f"{float(run.attribute('permanent_settlement')) * MM:.3g} mm")
    ax.set_xlabel("sleeper settlement (mm, downward positive)")
    ax.set_ylabel("sleeper force (kN)")
    ax.set_title("Load–deformation over the load cycle (cf. Fig. 18)\n"
                 "the paper: spheres keep settling after the peak, clumps rebound", fontsize=9)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7, ncol=1 + len(runs) // 12)
    return [save(fig, out_dir, "fig18_load_deformation")]


def render(runs, out_dir):
    """Every figure the runs allow; returns (paths written, figures that failed)."""
    written, failed = [], []

    def attempt(name, draw, *args):
        try:
            written.extend(draw(*args))
        except (ArchiveError, KeyError, ValueError) as e:
            note(f"{name} not drawn: {e}")
            failed.append(name)

    loaded = [r for r in runs if r.loaded]
    for r in runs:
        if not r.loaded:
            note(f"run '{r.id}' stopped before loading: only its Fig. 10 panel is drawn")
    attempt("Fig. 7", clump_gallery, runs, out_dir)
    attempt("Fig. 10", contacts_before, runs, out_dir)
    for r in loaded:
        attempt(f"Figs 11-12 of run '{r.id}'", lambda r=r: [contacts_per_run(r, out_dir)])
        attempt(f"Figs 13-14 of run '{r.id}'", lambda r=r: [rotations_per_run(r, out_dir)])
    if loaded:
        attempt("Figs 15-17", displacements, loaded, out_dir, note)
        attempt("Fig. 18", load_deformation, loaded, out_dir)
        attempt("fig_zones", zone_figure, loaded, out_dir, note)
        attempt("fig_cycles", cycles_figure, loaded, out_dir)
    return written, failed


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_run_arguments(parser)
    parser.add_argument("--out", required=True, help="folder for the PNG files")
    args = parser.parse_args(argv)
    try:
        with open_archive(args.archive) as archive:
            runs = chosen_runs(archive, args.runs, "draw")
            os.makedirs(args.out, exist_ok=True)
            written, failed = render(runs, args.out)
    except ArchiveError as e:
        note(str(e))
        return 1
    if failed:
        note(f"{len(failed)} figure(s) failed, {len(written)} written")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
