#!/usr/bin/python3
"""One row per box-test run: the table of docs/TRIALS.md.

    /usr/bin/python3 scripts/trials.py LABEL=RUN.h5 [LABEL=RUN.h5 ...] [--csv FILE]

Each argument is a run archive (`ballast run -o`) with the label its row gets; the
row holds what a change to the preparation or the loading does to the quantities the
paper's argument rests on: porosity, how the seating ended, the sleeper's bearing,
rotation during loading and over the cycle, settlement and rebound, and the top
layer's vertical displacement beneath and beside the sleeper at peak load.
scripts/validation_trials.sh runs the trials and calls this script.
"""
import argparse
import csv
import sys

from ballast_archive import ArchiveError, open_archive
from compare import quantities
from validation import seating

COLUMNS = (  # (compare.py key, header, format)
    ("porosity_grid", "porosity", "{:.3f}"),
    ("contacts_peak_sleeper_bodies", "bearing at 40 kN", "{:.0f}"),
    ("contacts_peak_max_force_N", "max force (kN)", "{:.1f}"),
    ("rotation_loading_mean_deg", "rot. loading mean (°)", "{:.3g}"),
    ("rotation_loading_max_deg", "rot. loading max (°)", "{:.3g}"),
    ("rotation_cycle_max_deg", "rot. cycle max (°)", "{:.3g}"),
    ("settlement_peak_mm", "settl. peak (mm)", "{:.3g}"),
    ("resilient_settlement_mm", "resilient (mm)", "{:.3g}"),
    ("zone_beneath_dz_peak_mm", "beneath dz (mm)", "{:.3g}"),
    ("zone_beside_dz_peak_mm", "beside dz (mm)", "{:.3g}"),
)
KN = {"contacts_peak_max_force_N"}  # shown in kN in the table, N in the CSV


def row(label, path):
    """(label, seating text, {key: value}) of the archive's one run."""
    runs = open_archive(path).select(None)
    if len(runs) != 1:
        raise ArchiveError(f"{path}: {len(runs)} runs with status ok; a trial is one run")
    run = runs[0]
    values = {k: v for k, _, v, _, _ in quantities(run)}
    ended, ratio = seating(run)
    seat = ended if ratio is None else f"{ended} ({ratio:.2g})"
    return label, seat, values


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", metavar="LABEL=RUN.h5")
    parser.add_argument("--csv", metavar="FILE", help="also write the table as CSV")
    args = parser.parse_args(argv)
    rows = []
    try:
        for item in args.runs:
            label, sep, path = item.partition("=")
            if not sep or not label or not path:
                parser.error(f"'{item}': expected LABEL=RUN.h5")
            rows.append(row(label, path))
    except (ArchiveError, OSError) as e:
        print(f"trials.py: {e}", file=sys.stderr)
        return 2
    header = ["trial", "seating ended by"] + [h for _, h, _ in COLUMNS]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for label, seat, values in rows:
        cells = [label, seat] + ["—" if values.get(k) is None else
                                 f.format(values[k] * (1e-3 if k in KN else 1.0))
                                 for k, _, f in COLUMNS]
        print("| " + " | ".join(cells) + " |")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["trial", "seating"] + [k for k, _, _ in COLUMNS])
            for label, seat, values in rows:
                w.writerow([label, seat] + [values.get(k, "") for k, _, _ in COLUMNS])
    return 0


if __name__ == "__main__":
    sys.exit(main())
