#!/usr/bin/python3
"""Which phase of our step loses from 1 to 2 threads, and whether 2 independent copies
lose the same there (docs/PERFORMANCE.md,
"Where the sphere step loses, phase by phase").

    tests/bench/peers/phase_copies.py [build/peers/spheres.txt] [--steps 20000] [--rounds 3]

Each round runs `ballast bench-bed --phase-times` with the benchmark's physics three
ways, one after the other: one thread alone; two one-thread copies at once (what the
host gives two independent processes: the host's bound, per phase); two threads. It
prints each phase's median time per step (the force pass; the walls and the
integration) and two speed-ups per phase against the lone thread:
  - 2 threads: lone time / the slower thread's time;
  - the copies: 2 x lone time / the copies' mean time (two copies do twice the work);
    the copies are pinned to vCPUs 0 and 1 (taskset), in that order in the table.
A phase whose 2-thread speed-up is as far below 2 as the copies' is bound by what the
two cores share on this host (caches, memory, the hypervisor), not by our threads'
waits or split. The hypervisor's steal (/proc/stat) over each way is printed beside
it, as `bench-bed --scaling` does. Needs a cached bed (run `make bench-peers` once).
"""
import argparse
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ballast_peer  # noqa: E402
from physics import Physics  # noqa: E402
# The two passes' medians per thread, and the median whole step (the same for all
# threads of a run: it holds the waits and the serial part as well).
PHASES = ("contacts", "walls and integrate", "step")


def cpu_ticks():
    """(wanted, steal) ticks of all vCPUs so far: proc(5), the first line of /proc/stat."""
    with open("/proc/stat") as f:
        fields = [int(x) for x in f.readline().split()[1:9]]
    idle = fields[3] + fields[4]
    return sum(fields) - idle, fields[7]


def medians(output):
    """Per thread, {phase: median µs per step} from bench-bed --phase-times' output."""
    lines = output.splitlines()
    step_line = next(line for line in lines if line.startswith("step, us:"))
    step = float(step_line.split("quartiles")[1].split(",")[1])
    start = next(i for i, line in enumerate(lines) if line.startswith("medians, us per step"))
    threads = []
    for line in lines[start + 1:]:
        if not line.strip().startswith("thread "):
            break
        parts = dict(part.strip().rsplit(" ", 1) for part in line.split(":", 1)[1].split(","))
        threads.append({name: float(parts[name]) for name in PHASES[:2]} | {"step": step})
    return threads


def launch(command, threads, cpu=None):
    """Starts a run; `cpu`: pinned to that vCPU (taskset), so that two copies report
    one vCPU each."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    pin = ["taskset", "-c", str(cpu)] if cpu is not None else []
    return subprocess.Popen(pin + command + ["--threads", str(threads)], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, env=env)


def finish(proc):
    out, _ = proc.communicate()
    if proc.returncode != 0:
        sys.exit(f"phase_copies.py: bench-bed failed:\n{out}")
    return medians(out)


def with_steal(run):
    wanted0, steal0 = cpu_ticks()
    result = run()
    wanted1, steal1 = cpu_ticks()
    share = (steal1 - steal0) / (wanted1 - wanted0) if wanted1 > wanted0 else 0.0
    return result, 100.0 * share


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("bed", nargs="?", default=ballast_peer.SPHERE_BED)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args()
    ballast, bed = ballast_peer.binary_and_bed(args.bed, "phase_copies.py")
    command = [ballast, "bench-bed", bed, "--steps", str(args.steps),
               "--phase-times"] + ballast_peer.physics_flags(Physics())
    print(f"{os.path.basename(args.bed)}, {args.steps} steps: median µs per step of each phase; "
          "speed-up against the lone thread")
    print("| round | phase | 1 thread | copies (vCPU 0, 1) | 2 threads (each) | copies' speed-up "
          "| 2 threads' speed-up | steal: alone, copies, 2 threads |")
    print("|---|---|---|---|---|---|---|---|")
    ratios = {name: ([], []) for name in PHASES}
    for r in range(1, args.rounds + 1):
        alone, s1 = with_steal(lambda: finish(launch(command, 1)))
        copies, sc = with_steal(lambda: [finish(c)[0] for c in [launch(command, 1, cpu=0),
                                                               launch(command, 1, cpu=1)]])
        two, s2 = with_steal(lambda: finish(launch(command, 2)))
        for name in PHASES:
            lone = alone[0][name]
            each_copy = [c[name] for c in copies]
            each_thread = [t[name] for t in two]
            copies_speedup = 2.0 * lone / statistics.mean(each_copy)
            two_speedup = lone / max(each_thread)
            ratios[name][0].append(copies_speedup)
            ratios[name][1].append(two_speedup)
            print(f"| {r} | {name} | {lone:.1f} | {', '.join(f'{x:.1f}' for x in each_copy)} "
                  f"| {', '.join(f'{x:.1f}' for x in each_thread)} | {copies_speedup:.2f} "
                  f"| {two_speedup:.2f} | {s1:.1f}, {sc:.1f}, {s2:.1f} % |")
    for name in PHASES:
        copies_speedups, two_speedups = ratios[name]
        print(f"{name}: median speed-up over the rounds, "
              f"copies {statistics.median(copies_speedups):.2f}, "
              f"2 threads {statistics.median(two_speedups):.2f}")


if __name__ == "__main__":
    main()
