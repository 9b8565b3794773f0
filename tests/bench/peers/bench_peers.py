#!/usr/bin/python3
"""Our engine beside LAMMPS and YADE on the same settled beds (issue 7): `make bench-peers`.

1. The conventions (check_conventions.py): all three codes give kn = ks = 5.08e9 N/m
   per contact and summed clump masses.
2. The beds, built once and cached: the box-test preparation of spheres and of Table 2
   Sample 1 clumps with the benchmark's physics (contacts of 5.08e9 N/m everywhere,
   the base included, mu = 0.3, mass mode "sum"), stopped after compaction and
   exported as packing files (beds.py).
3. Per bed, rounds of: ours on 1 and 2 threads, LAMMPS on 1 process and 2 MPI ranks,
   YADE on 1 and 2 threads, all from the same file and for the same number of steps,
   the order turned by one each round so that drift on the host falls on every code.
   Printed: median ball-steps/s of the stepping per code and thread count, our ratio
   to each, our 2-thread/1-thread speed-up, whether our 1- and 2-thread states are
   bit-identical (state hash), and the physics after the run beside each other.
   Each round ends with `ballast bench-bed --scaling` (tests/bench/bed/bench_bed_scaling.hpp):
   our speed-up from 1 to 2 threads measured in one process, copies of the bed
   taking turns every twentieth of the steps so that the host's drift cancels,
   beside what 2 independent copies at once gave in the same turns (the host's
   bound), and the hypervisor's steal during each kind of turn (tests/bench/bed/host_steal.hpp);
   its copies must end in the same state as the runs above.
4. Exit 1 if a convention, the bit identity or the physics cross-check fails.
"""
import argparse
import json
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ballast_peer  # noqa: E402
import beds  # noqa: E402
import check_conventions  # noqa: E402
import crosscheck  # noqa: E402
import lammps_peer  # noqa: E402
import yade_peer  # noqa: E402
from packing import read_packing  # noqa: E402
from physics import Physics  # noqa: E402


def steal_text(share):
    """bench-bed --scaling's host_steal_share as '1 thread a %, 2 threads b %, copies c %'."""
    def pct(v):
        return "unknown" if v is None else f"{100 * v:.1f} %"
    return (f"1 thread {pct(share['one_thread'])}, 2 threads {pct(share['threads'])}, "
            f"copies {pct(share['independent_copies'])}")


def run_one(code, parallel, args, bed, packing, p, work):
    """One timed run; returns its summary record."""
    d = os.path.join(work, f"{bed}_{code}_{parallel}")
    if code == "ballast":
        return ballast_peer.run(args.ballast, packing.source, p, parallel)
    if code == "lammps":
        lammps_peer.write_inputs(packing, p, d)
        log = lammps_peer.run(d, parallel)
        return lammps_peer.results(packing, p, d, parallel, log)
    yade_peer.write_script(packing, p, d)
    return yade_peer.results(packing, yade_peer.run(d, parallel), parallel)


def bench_bed(bed, path, steps, args, work):
    packing = read_packing(path)
    p = Physics(steps=steps)
    runs = [(code, n) for n in (1, 2) for code in ("ballast", "lammps", "yade")]
    records = {r: [] for r in runs}
    load_before = os.getloadavg()
    print(f"\n== {bed}: {len(packing.bodies)} bodies, {packing.balls} balls, {steps} steps of "
          f"{p.dt:g} s, {args.rounds} rounds; host load average {load_before[0]:.1f} on "
          f"{os.cpu_count()} cores ==", flush=True)
    scaling = []
    chunk = max(1, steps // 20)
    for k in range(args.rounds):
        order = runs[k % len(runs):] + runs[:k % len(runs)]
        for code, n in order:
            r = run_one(code, n, args, bed, packing, p, work)
            records[(code, n)].append(r)
            print(f"  round {k + 1}: {code:7s} {n} {'ranks' if code == 'lammps' else 'threads'}:"
                  f" {r['ball_steps_per_s']:.3e} ball-steps/s ({r['seconds']:.2f} s)", flush=True)
        s = ballast_peer.run(args.ballast, packing.source, p, 2,
                             extra=("--scaling", "--chunk", str(chunk)))
        scaling.append(s)
        print(f"  round {k + 1}: ballast 1 against 2 threads in one process, turns of {chunk} "
              f"steps: speed-up {s['speedup']['ratio']:.3f}; 2 independent copies "
              f"{s['independent_copies']['ratio']:.3f}; the host's steal "
              f"{steal_text(s['host_steal_share'])}", flush=True)
    median = {r: statistics.median(x["ball_steps_per_s"] for x in records[r]) for r in runs}
    print(f"\n{bed}: ball-steps/s, median of {args.rounds} rounds")
    print("| code | 1 thread / process | 2 threads / ranks | 2 / 1 | ours / this, 1 | ours / this, 2 |")
    print("|---|---|---|---|---|---|")
    for code in ("ballast", "lammps", "yade"):
        one, two = median[(code, 1)], median[(code, 2)]
        r1 = median[("ballast", 1)] / one
        r2 = median[("ballast", 2)] / two
        print(f"| {code} | {one:.3g} | {two:.3g} | {two / one:.2f} | {r1:.2f} | {r2:.2f} |")
    hashes = {x["state_hash"] for n in (1, 2) for x in records[("ballast", n)]}
    hashes |= {h for x in scaling for h in x["state_hash"]}
    identical = len(hashes) == 1
    print(f"ours: 2 threads / 1 thread = {median[('ballast', 2)] / median[('ballast', 1)]:.2f}; "
          f"state after {steps} steps {'bit-identical' if identical else 'DIFFERS'} on 1 and 2 "
          f"threads over all rounds, --scaling's copies included ({', '.join(sorted(hashes))})")
    speedup = [x["speedup"]["ratio"] for x in scaling]
    bound = [x["independent_copies"]["ratio"] for x in scaling]
    print(f"ours, 2 / 1 thread in one process (bench-bed --scaling), per round: "
          f"{', '.join(f'{v:.2f}' for v in speedup)} (median {statistics.median(speedup):.2f}); "
          f"the host's bound, 2 independent copies at once: "
          f"{', '.join(f'{v:.2f}' for v in bound)} (median {statistics.median(bound):.2f}); "
          f"the host's steal, per round: {'; '.join(steal_text(x['host_steal_share']) for x in scaling)}")
    # The same ratios round by round: the runs of one round are minutes apart, so
    # slow drift on the host cancels in them, and their spread shows how far the
    # host moved a ratio within this run.
    def per_round(num, den):
        return ", ".join(f"{a['ball_steps_per_s'] / b['ball_steps_per_s']:.2f}"
                         for a, b in zip(records[num], records[den]))
    print(f"ours, per round: 2 / 1 thread {per_round(('ballast', 2), ('ballast', 1))}; "
          f"/ LAMMPS, 1: {per_round(('ballast', 1), ('lammps', 1))}; "
          f"/ YADE, 1: {per_round(('ballast', 1), ('yade', 1))}")
    physics_ok = crosscheck.report(bed, {code: records[(code, 1)][0] for code in
                                         ("ballast", "lammps", "yade")},
                                   [records[("lammps", 2)][0], records[("yade", 2)][0]])
    load_after = os.getloadavg()
    print(f"{bed}: host load average {load_after[0]:.1f} after the runs (1-minute)")
    return {"bed": bed, "packing": path, "steps": steps, "rounds": args.rounds,
            "load_average": [load_before[0], load_after[0]],
            "omp_wait_policy": os.environ.get("OMP_WAIT_POLICY", "default"),
            "median_ball_steps_per_s": {f"{c}_{n}": v for (c, n), v in median.items()},
            "records": {f"{c}_{n}": v for (c, n), v in records.items()},
            "scaling": scaling,
            "bit_identical": identical, "physics_ok": physics_ok}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ballast", required=True, help="the ballast binary")
    ap.add_argument("--cases", default=os.path.join(os.path.dirname(__file__), "..", "..", "..",
                                                     "cases"), help="the cases/ directory")
    ap.add_argument("--cache", required=True, help="where the beds are cached (build/peers)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--beds", default="spheres,sample1", help="comma-separated: spheres, sample1")
    ap.add_argument("--steps-spheres", type=int, default=10000)
    ap.add_argument("--steps-sample1", type=int, default=1000)
    ap.add_argument("--skip-conventions", action="store_true")
    ap.add_argument("--omp-wait-policy", choices=("active", "passive"),
                    help="OMP_WAIT_POLICY for the OpenMP codes (ours and YADE); default: "
                         "their own. 'passive' keeps idle threads from spinning, which on a "
                         "host busy with other work can slow a 2-thread run tenfold")
    a = ap.parse_args()
    if a.omp_wait_policy:
        os.environ["OMP_WAIT_POLICY"] = a.omp_wait_policy
    work = os.path.join(a.cache, "runs")
    os.makedirs(work, exist_ok=True)
    failed = []
    if not a.skip_conventions and check_conventions.run(a.ballast, os.path.join(work, "conventions")):
        failed.append("conventions")
    results = []
    for bed in a.beds.split(","):
        path = beds.ensure(bed, a.ballast, a.cases, a.cache)
        r = bench_bed(bed, path, getattr(a, f"steps_{bed}"), a, work)
        results.append(r)
        if not r["bit_identical"]:
            failed.append(f"{bed}: bit identity")
        if not r["physics_ok"]:
            failed.append(f"{bed}: physics")
    with open(os.path.join(a.cache, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    print(f"\nresults: {os.path.join(a.cache, 'results.json')}")
    if failed:
        print("bench-peers: FAILED: " + "; ".join(failed))
        return 1
    print("bench-peers: conventions, bit identity and physics cross-checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
