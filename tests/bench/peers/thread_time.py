#!/usr/bin/python3
"""Where each of two threads spends a bench-bed run (docs/PERFORMANCE.md, "What bought
what": why the thread shares follow measured time, engine/timed_split.hpp).

    tests/bench/peers/thread_time.py [build/peers/spheres.txt] [--steps 20000]
    BALLAST=build/revisions/REV/build/study/ballast tests/bench/peers/thread_time.py

Runs `ballast bench-bed` on 2 threads with the benchmark's physics under `perf record`
(cpu-clock sampling: this VM exposes no hardware counters) and prints, per thread, the
share of its samples in the force pass, in the gather and integration, in the serial
part of the step (the main thread alone) and in OpenMP (libgomp: waiting at the
barriers and at the start of the next step's region). Threads that finish their
shares together wait little; the difference between the two threads' force-pass
shares is the imbalance of the split. Needs linux-perf and a cached bed (run `make
bench-peers` once).
"""
import argparse
import collections
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ballast_peer  # noqa: E402
from physics import Physics  # noqa: E402


def phase(symbol, dso):
    """The part of the step a sample belongs to."""
    if "libgomp" in dso:
        return "OpenMP wait"
    # The sphere kernels (engine/sphere_kernel.hpp): ball_ball and sphere_pass_simd are
    # the force pass, update_spheres the leapfrog.
    if any(k in symbol for k in ("contact_pass", "compute_contacts", "ball_ball", "sphere_pass")):
        return "force pass"
    if any(k in symbol for k in ("integrate", "step_bod", "step_spheres", "gather_body_force",
                                 "update_spheres")):
        return "integrator"
    return "serial and other"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("bed", nargs="?", default=ballast_peer.SPHERE_BED)
    ap.add_argument("--steps", type=int, default=20000)
    args = ap.parse_args()
    ballast, bed = ballast_peer.binary_and_bed(args.bed, "thread_time.py")
    with tempfile.TemporaryDirectory() as work:
        data = os.path.join(work, "perf.data")
        run = ["perf", "record", "-q", "-F", "5000", "-o", data, ballast, "bench-bed", bed,
               "--steps", str(args.steps), "--threads", "2",
               "--json"] + ballast_peer.physics_flags(Physics())
        subprocess.run(run, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       env=dict(os.environ, OMP_NUM_THREADS="2"))
        script = subprocess.run(["perf", "script", "-i", data, "-F", "tid,ip,sym,dso",
                                 "--hide-call-graph"], check=True, capture_output=True, text=True)
    per_thread = collections.defaultdict(collections.Counter)
    for line in script.stdout.splitlines():
        fields = line.split(None, 1)
        if len(fields) < 2 or not fields[0].isdigit():
            continue
        tid, rest = fields
        dso = rest[rest.rfind("(") + 1:].rstrip(")") if "(" in rest else ""
        per_thread[int(tid)][phase(rest, dso)] += 1
    # The two threads of the run are the two with the most samples; the main one
    # (lowest id) also runs the serial part.
    threads = sorted(sorted(per_thread, key=lambda t: -sum(per_thread[t].values()))[:2])
    names = ["force pass", "integrator", "serial and other", "OpenMP wait"]
    print(f"{os.path.basename(ballast)} on {os.path.basename(args.bed)}, {args.steps} steps, "
          "2 threads: share of each thread's perf samples")
    print("| thread | samples | " + " | ".join(names) + " |")
    print("|---" * (len(names) + 2) + "|")
    for k, t in enumerate(threads):
        c = per_thread[t]
        n = sum(c.values())
        cells = " | ".join(f"{100.0 * c[x] / n:.1f} %" for x in names)
        print(f"| {'main' if k == 0 else 'other'} | {n} | {cells} |")


if __name__ == "__main__":
    main()
