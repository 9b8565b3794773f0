#!/usr/bin/python3
"""What a scene pays for a part it may leave out: each part on and off, on make
bench-peers' settled beds (build/peers/spheres.txt, sample1.txt), one thread.

    optional_costs.py [--rounds N] [--before BALLAST] [--csv OUT]

Each row is one part, measured two ways:
  instructions  per ball-step, counted by callgrind: two runs of N1 and N2 steps from
                the same bed, so that set-up and output cancel (as callgrind_per_step.sh);
                exact and repeatable, the figure to quote;
  time          ball-steps/s, medians over --rounds rounds that take turns, on and off
                (a shared host: read the ratio, not the rate).
Parts:
  energy ledger    bench-bed --energy-ledger (SimulationSettings::energy_ledger), with
                   local damping 0 (the peer benchmark) and 0.7 (the box test's α)
  frictionless     the spin and torque of frictionless spheres, which the engine does
  spin             not compute; with --before BALLAST (a build from before it left them
                   out, e.g. one compare_revisions.py made), that build is the "on" side;
                   it keeps the energy ledger in every run, so "off" keeps it too
docs/PERFORMANCE.md, "What a scene pays for", quotes its output.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ballast_peer  # noqa: E402
from physics import Physics  # noqa: E402

ROOT = ballast_peer.ROOT
BEDS = os.path.join(ROOT, "build", "peers")
# Steps: callgrind runs N1 and N2; timed runs take STEPS.
CALLGRIND_STEPS = {"spheres": (500, 1500), "sample1": (200, 700)}
STEPS = {"spheres": 20000, "sample1": 5000}


def parts(before):
    """(part, bed, friction, flags common to both, flags or binary of 'on', of 'off')."""
    rows = []
    for bed in ("spheres", "sample1"):
        for alpha in (0.0, 0.7):
            damping = ["--local-damping", repr(alpha)] if alpha else []
            rows.append((f"energy ledger, local damping {alpha:g}", bed, 0.3, damping,
                         ["--energy-ledger"], []))
    if before:
        # That build keeps the ledger in every run: this side keeps it too.
        for lanes, label in ((["--simd-lanes", "-1"], "SIMD kernel"),
                             (["--simd-lanes", "0"], "scalar pass")):
            rows.append((f"frictionless spin, {label}", "spheres", 0.0, lanes, before,
                         ["--energy-ledger"]))
    return rows


def command(ballast, bed, steps, flags, friction):
    return [ballast, "bench-bed", os.path.join(BEDS, bed + ".txt"), "--steps", str(steps),
            "--threads", "1", "--json"] + ballast_peer.physics_flags(Physics(friction=friction)) + flags


def side(default, common, extra):
    """The binary and flags of one side: `extra` is either more flags or a binary."""
    if isinstance(extra, str):
        return extra, common
    return default, common + extra


def instructions(cmd, work):
    out = os.path.join(work, "cg.out")
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}"] + cmd,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True,
                   env=dict(os.environ, OMP_NUM_THREADS="1"))
    for line in open(out):
        if line.startswith("summary:"):
            return int(line.split()[1])
    raise RuntimeError(f"no summary in {out}")


def per_ball_step(ballast, bed, flags, friction, balls, work):
    n1, n2 = CALLGRIND_STEPS[bed]
    i1 = instructions(command(ballast, bed, n1, flags, friction), work)
    i2 = instructions(command(ballast, bed, n2, flags, friction), work)
    return (i2 - i1) / ((n2 - n1) * balls)


def rate(ballast, bed, flags, friction):
    done = subprocess.run(command(ballast, bed, STEPS[bed], flags, friction), capture_output=True,
                          text=True, check=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    return json.loads(done.stdout)["ball_steps_per_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--before", help="a ballast binary that computes frictionless spin")
    ap.add_argument("--csv", help="write the table here too")
    args = ap.parse_args()
    ballast = os.environ.get("BALLAST", os.path.join(ROOT, "build", "study", "ballast"))
    for bed in ("spheres", "sample1"):
        if not os.path.exists(os.path.join(BEDS, bed + ".txt")):
            raise SystemExit(f"optional_costs.py: no bed {bed} in {BEDS} (run make bench-peers once)")
    balls = {bed: sum(1 for line in open(os.path.join(BEDS, bed + ".txt"))
                      if line.strip() and not line.lstrip().startswith("#"))
             for bed in ("spheres", "sample1")}
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for part, bed, friction, common, on, off in parts(args.before):
            on_bin, on_flags = side(ballast, common, on)
            off_bin, off_flags = side(ballast, common, off)
            ir_on = per_ball_step(on_bin, bed, on_flags, friction, balls[bed], work)
            ir_off = per_ball_step(off_bin, bed, off_flags, friction, balls[bed], work)
            rates = {"on": [], "off": []}
            for r in range(args.rounds):
                order = ("on", "off") if r % 2 == 0 else ("off", "on")
                for which in order:
                    b, f = (on_bin, on_flags) if which == "on" else (off_bin, off_flags)
                    rates[which].append(rate(b, bed, f, friction))
            t_on, t_off = statistics.median(rates["on"]), statistics.median(rates["off"])
            rows.append({"part": part, "bed": bed, "balls": balls[bed],
                         "instructions_on": round(ir_on, 1), "instructions_off": round(ir_off, 1),
                         "instruction_share_pct": round(100 * (ir_on - ir_off) / ir_on, 2),
                         "rate_on": f"{t_on:.4g}", "rate_off": f"{t_off:.4g}",
                         "time_share_pct": round(100 * (1 - t_on / t_off), 1)})
            print(f"{part} ({bed}): {ir_on:.0f} -> {ir_off:.0f} instructions per ball-step, "
                  f"{t_on:.3g} -> {t_off:.3g} ball-steps/s", flush=True)
    print("\n| part | bed | instructions per ball-step, on → off | share of a step | "
          "ball-steps/s, on → off (medians) | time share |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['part']} | {r['bed']} | {r['instructions_on']:.0f} → {r['instructions_off']:.0f} "
              f"| {r['instruction_share_pct']:.1f} % | {r['rate_on']} → {r['rate_off']} "
              f"| {r['time_share_pct']:.1f} % |")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
