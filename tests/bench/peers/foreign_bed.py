#!/usr/bin/python3
"""Beds from elsewhere: does our engine run a packing written by another code, in that
code's order or in none, as fast as its own, against LAMMPS on the same bed?

    foreign_bed.py [--rounds N] [--csv OUT] [--beds spheres|sample1]

From make bench-peers' beds (build/peers/spheres.txt, sample1.txt) it makes:
  lammps-spheres    the sphere bed after 20,000 steps of LAMMPS under the benchmark's
                    law, written by LAMMPS (write_dump, 17 digits) in its atom order
  shuffled-spheres  that file's lines in random order (seed 1)
  shuffled-sample1  our Sample 1 bed with its clumps in random order (seed 1)
and times, round after round in turned order, our engine on 1 and 2 threads with the
file's numbering kept (bench-bed --keep-file-order) and as the engine numbers it
(Simulation::sort_bodies_spatially), and LAMMPS on 1 process, on each bed and on ours.
Prints the engine's decision on each bed's numbering (mean step between consecutive
bodies, before and sorted), the medians, each against LAMMPS on the same bed (as a ratio of
medians and as the median of each round's ratio, with its range), and the state hashes (a
bed's shufflings sort to one numbering, so to one hash). Needs lmp (make bench-peers
installs it). docs/PERFORMANCE.md, "Beds from elsewhere", quotes its output.
"""
import argparse
import csv
import os
import random
import re
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ballast_peer  # noqa: E402
import lammps_peer  # noqa: E402
from packing import read_packing  # noqa: E402
from physics import Physics  # noqa: E402

STEPS = {"spheres": 10000, "sample1": 1000}


def lammps_written(source, out, work):
    """The bed after 20,000 LAMMPS steps, as LAMMPS writes it (x y z r, its order)."""
    if os.path.exists(out):
        return out
    directory = os.path.join(work, "lammps-written")
    lammps_peer.write_inputs(read_packing(source), Physics(steps=20000), directory)
    lammps_peer.run(directory, 1)
    names, rows = lammps_peer._dump_rows(os.path.join(directory, "atoms.dump"))
    col = {n: i for i, n in enumerate(names)}
    with open(out + ".partial", "w") as f:
        f.write(f"# {source} after 20000 steps of LAMMPS (write_dump order)\n")
        for row in rows:
            f.write(" ".join(row[col[c]] for c in ("x", "y", "z", "radius")) + "\n")
    os.replace(out + ".partial", out)
    return out


def shuffled(source, out):
    """The packing's bodies (a clump's lines stay together) in random order."""
    bodies, clumps = {}, False
    for line in open(source):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        fields = line.split()
        clumps = len(fields) == 5
        bodies.setdefault(fields[0] if clumps else len(bodies), []).append(line)
    keys = list(bodies)
    random.Random(1).shuffle(keys)
    with open(out, "w") as f:
        f.write(f"# {source}, bodies in random order (seed 1)\n")
        for k in keys:
            f.writelines(bodies[k])
    return out


def lammps_rate(path, steps, work, name):
    packing = read_packing(path)
    directory = os.path.join(work, "lammps-" + name)
    lammps_peer.write_inputs(packing, Physics(steps=steps), directory)
    log = lammps_peer.run(directory, 1)
    seconds = float(re.search(r"Loop time of ([0-9.eE+-]+) on", log).group(1))
    return packing.balls * steps / seconds, None


def ours_rate(ballast, path, steps, threads, keep):
    extra = ("--keep-file-order",) if keep else ()
    r = ballast_peer.run(ballast, path, Physics(steps=steps), threads, extra=extra)
    return r["ball_steps_per_s"], r["state_hash"]


def numbering(ballast, path):
    """The engine's decision on the bed's numbering, as bench-bed logs it."""
    done = subprocess.run([ballast, "bench-bed", path, "--steps", "1", "--threads", "1"]
                          + ballast_peer.physics_flags(Physics(steps=1)),
                          capture_output=True, text=True, timeout=300)
    lines = [l for l in done.stderr.splitlines() if "numbering kept" in l or "renumbered" in l]
    return lines[0] if lines else f"(no numbering line; exit {done.returncode})"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--cache", default=os.path.join(ballast_peer.ROOT, "build", "peers"))
    ap.add_argument("--csv", help="write the medians here")
    ap.add_argument("--beds", choices=tuple(STEPS),
                    help="only the beds of this kind (default: both kinds)")
    args = ap.parse_args()
    ballast = os.environ.get("BALLAST", os.path.join(ballast_peer.ROOT, "build", "study", "ballast"))
    work = os.path.join(args.cache, "foreign")
    os.makedirs(work, exist_ok=True)
    kinds = [args.beds] if args.beds else list(STEPS)
    ours = {k: os.path.join(args.cache, f"{k}.txt") for k in kinds}
    for path in ours.values():
        if not os.path.exists(path):
            raise SystemExit(f"foreign_bed.py: no bed at {path} (run make bench-peers once)")
    beds = []
    if "spheres" in ours:
        lmp = lammps_written(ours["spheres"], os.path.join(work, "lammps-spheres.txt"), work)
        beds += [("ours-spheres", ours["spheres"], "spheres"),
                 ("lammps-spheres", lmp, "spheres"),
                 ("shuffled-spheres", shuffled(lmp, os.path.join(work, "shuffled-spheres.txt")),
                  "spheres")]
    if "sample1" in ours:
        beds += [("ours-sample1", ours["sample1"], "sample1"),
                 ("shuffled-sample1",
                  shuffled(ours["sample1"], os.path.join(work, "shuffled-sample1.txt")), "sample1")]
    for bed, path, _ in beds:
        print(f"{bed}: {numbering(ballast, path)}", flush=True)
    runs = [(bed, code, threads, keep) for bed, _, _ in beds
            for code, threads, keep in (("ballast", 1, True), ("ballast", 1, False),
                                        ("ballast", 2, True), ("ballast", 2, False),
                                        ("lammps", 1, None))]
    paths = {bed: (path, kind) for bed, path, kind in beds}
    rates = {r: [] for r in runs}
    hashes = {}
    for k in range(args.rounds):
        order = runs[k % len(runs):] + runs[:k % len(runs)]
        for run in order:
            bed, code, threads, keep = run
            path, kind = paths[bed]
            if code == "lammps":
                rate, h = lammps_rate(path, STEPS[kind], work, bed)
            else:
                rate, h = ours_rate(ballast, path, STEPS[kind], threads, keep)
                hashes.setdefault((bed, keep), set()).add(h)
            rates[run].append(rate)
        print(f"round {k + 1} of {args.rounds} done", flush=True)

    rows = []
    print("\n| bed | ours, file's order, 1 | ours, sorted, 1 | ours, file's order, 2 | ours, sorted, 2 "
          "| LAMMPS, 1 | ours sorted / LAMMPS, 1 | the same, round by round |")
    print("|---|---|---|---|---|---|---|---|")
    for bed, _, _ in beds:
        med = {(c, t, keep): statistics.median(rates[(bed, c, t, keep)])
               for (b, c, t, keep) in runs if b == bed}
        lammps = med[("lammps", 1, None)]
        cells = [med[("ballast", 1, True)], med[("ballast", 1, False)], med[("ballast", 2, True)],
                 med[("ballast", 2, False)], lammps]
        # Each round's ratio of our run to LAMMPS's on the same bed, which ran minutes
        # apart at most: a host whose speed drifts leaves their median alone better than
        # the ratio of the two medians (compare_revisions.py does the same).
        paired = [o / l for o, l in zip(rates[(bed, "ballast", 1, False)],
                                        rates[(bed, "lammps", 1, None)])]
        by_round = statistics.median(paired)
        print(f"| {bed} | " + " | ".join(f"{v:.3g}" for v in cells) +
              f" | **{med[('ballast', 1, False)] / lammps:.2f}** | {by_round:.2f} "
              f"({min(paired):.2f}–{max(paired):.2f}) |")
        rows.append([bed] + [f"{v:.4g}" for v in cells] +
                    [f"{med[('ballast', 1, False)] / lammps:.3f}", f"{by_round:.3f}",
                     f"{min(paired):.3f}", f"{max(paired):.3f}"])
    print("\nstate hashes (1 and 2 threads, every round), file's order kept / sorted:")
    for bed, _, _ in beds:
        print(f"  {bed}: {', '.join(sorted(hashes[(bed, True)]))} / {', '.join(sorted(hashes[(bed, False)]))}")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["bed", "ours_file_order_1", "ours_sorted_1", "ours_file_order_2", "ours_sorted_2",
                        "lammps_1", "ours_sorted_over_lammps_1", "round_ratio_median",
                        "round_ratio_min", "round_ratio_max"])
            w.writerows(rows)


if __name__ == "__main__":
    main()
