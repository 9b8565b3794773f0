#!/usr/bin/python3
"""Speed against accuracy for clump beds: rotation integrators and mass modes.

Settles the smoke-scale box-test bed of Table 2 Sample 1 clumps (240 clumps in a
350 x 150 mm box: preparation by radius expansion, then compaction at 10 g and
1 g) once per variant, from the same seed, and tabulates cost per step, settled
porosity (5 mm grid under the sleeper's footprint), coordination number and mean
accumulated rotation. Writes a Markdown table (docs/TRADEOFFS.md quotes it).

    /usr/bin/python3 scripts/tradeoffs.py [--ballast build/study/ballast] [--threads 2]
"""
import argparse
import json
import subprocess
import sys

VARIANTS = [
    ("pfc", "paper"),
    ("full", "paper"),
    ("pfc", "sum"),
    ("pfc", "uniform"),
    ("full", "uniform"),
]


def run(ballast, threads, rotation, mass, max_stage_steps):
    cmd = [ballast, "run", "cases/box_test/smoke.json", "--json", "--threads", str(threads),
           "--set", f"/preparation/max_stage_steps={max_stage_steps}",
           "--set", "/particles/shape=table2/sample1",
           "--set", "/preparation/stop_after=compact",
           "--set", f"/numerics/rotation={rotation}",
           "--set", f"/particles/mass_mode={mass}"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--ballast", default="build/study/ballast")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--max-stage-steps", type=int, default=150000,
                   help="step limit per settling stage (the smoke scene's own is 150000)")
    a = p.parse_args()
    rows = []
    for rotation, mass in VARIANTS:
        r = run(a.ballast, a.threads, rotation, mass, a.max_stage_steps)
        steps = sum(s["steps"] for s in r["stages"])
        seconds = sum(s["seconds"] for s in r["stages"])
        rows.append((rotation, mass, r, steps, seconds))
        print(f"done: {rotation}/{mass}", file=sys.stderr)
    base = rows[0][2]
    print("| rotation | mass mode | balls | dt (µs) | steps | µs/step | ball-steps/s |"
          " porosity | Δ porosity | Z | Δ Z | mean rotation (°) | settled stages |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for rotation, mass, r, steps, seconds in rows:
        z = r["contacts_before"]["coordination"]
        settled = sum(1 for s in r["stages"] if s["settled"])
        print(f"| {rotation} | {mass} | {r['balls']} | {r['dt_s'] * 1e6:.3f} | {steps} |"
              f" {seconds / steps * 1e6:.1f} | {r['balls'] * steps / seconds:.3g} |"
              f" {r['porosity_grid']:.4f} | {r['porosity_grid'] - base['porosity_grid']:+.4f} |"
              f" {z:.2f} | {z - base['contacts_before']['coordination']:+.2f} |"
              f" {r['rotation_cycle']['mean_deg']:.1f} | {settled}/{len(r['stages'])} |")


if __name__ == "__main__":
    main()
