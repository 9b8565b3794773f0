#!/usr/bin/python3
"""Our engine at several git revisions on the same beds, to say which change bought what
(docs/PERFORMANCE.md, "What bought what").

    tests/bench/peers/compare_revisions.py REV_A REV_B HEAD
    tests/bench/peers/compare_revisions.py "HEAD:--simd-lanes 0" HEAD --beds-only spheres

A revision may carry bench-bed flags after a colon ("REV:FLAGS"): one build, run
with and without them, says what a switch buys. Each revision is checked out once as a detached worktree under build/revisions/REV and
its `ballast` binary built there (Release, as the top-level Makefile builds it). Then,
for every bed of build/peers (the benchmark's cached packing files: run `make
bench-peers` once to make them) and for 1 and 2 threads, every revision runs
`ballast bench-bed` with the benchmark's physics, in rounds with the order turned by
one each round so that drift on the host falls on every revision. Printed: the median
ball-steps/s per revision, its ratio to the first revision, its 2/1-thread speed-up and
its state hash after the run (equal hashes: the revisions compute the same numbers;
revisions on both sides of the change that widened engine/state_hash to the energy
ledger, walls and clock differ in hash whatever they compute);
then the median over rounds of each round's ratio to the first revision, which a
host whose speed drifts over minutes leaves alone better than a ratio of medians.
With --phase-times, each run also times its phases (`bench-bed --phase-times`) and a
last table gives, per revision, the integration's median time per step over the force
pass's (the slower thread's of each): a change to one pass shows in that ratio even
when the host's speed moves by more than the change between two runs.
"""
import argparse
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ballast_peer  # noqa: E402
from physics import Physics  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))


def git(*args):
    return subprocess.run(["git", "-C", ROOT, *args], check=True, capture_output=True,
                          text=True).stdout.strip()


def build_revision(spec, work):
    """The ballast binary of `spec` ("REV" or "REV:FLAGS"), built in its own worktree;
    returns (label, path, flags)."""
    rev, _, flags = spec.partition(":")
    short = git("rev-parse", "--short", rev)
    tree = os.path.join(work, short)
    binary = os.path.join(tree, "build", "study", "ballast")
    if not os.path.isdir(tree):
        git("worktree", "add", "--detach", tree, rev)
    if not os.path.exists(binary):
        print(f"building {rev} ({short}) in {tree}", flush=True)
        subprocess.run(["cmake", "-S", tree, "-B", os.path.join(tree, "build"),
                        "-DCMAKE_BUILD_TYPE=Release"], check=True, capture_output=True)
        subprocess.run(["cmake", "--build", os.path.join(tree, "build"), "-j2", "--target",
                        "ballast"], check=True, capture_output=True)
    return (f"{short} {flags}" if flags else short), binary, flags.split()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("revisions", nargs="+", help="git revisions; ratios are to the first")
    ap.add_argument("--beds", default=os.path.join(ROOT, "build", "peers"),
                    help="folder with spheres.txt and sample1.txt (make bench-peers makes them)")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "revisions"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--steps-spheres", type=int, default=10000)
    ap.add_argument("--steps-sample1", type=int, default=1000)
    ap.add_argument("--beds-only", choices=("spheres", "sample1"),
                    help="one bed instead of both")
    ap.add_argument("--phase-times", action="store_true",
                    help="also compare the integration's time per step to the force pass's")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    builds = [build_revision(r, a.work) for r in a.revisions]
    for bed in (a.beds_only,) if a.beds_only else ("spheres", "sample1"):
        path = os.path.join(a.beds, f"{bed}.txt")
        if not os.path.exists(path):
            sys.exit(f"compare_revisions: no bed {path}: run `make bench-peers` once to build it")
        p = Physics(steps=getattr(a, f"steps_{bed}"))
        rate = {(s, n): [] for s, _, _ in builds for n in (1, 2)}
        hashes = {(s, n): set() for s, _, _ in builds for n in (1, 2)}
        share = {(s, n): [] for s, _, _ in builds for n in (1, 2)}  # integration / force pass
        runs = [(b, n) for n in (1, 2) for b in builds]
        print(f"\n== {bed}: {p.steps} steps, {a.rounds} rounds ==", flush=True)
        for k in range(a.rounds):
            for (short, binary, flags), n in runs[k % len(runs):] + runs[:k % len(runs)]:
                timed = ["--phase-times"] if a.phase_times else []
                r = ballast_peer.run(binary, path, p, n, extra=flags + timed)
                rate[(short, n)].append(r["ball_steps_per_s"])
                if a.phase_times:
                    threads = r["phase_times"]["thread_medians"]
                    share[(short, n)].append(
                        max(t["walls_and_integrate_us"] for t in threads) /
                        max(t["contacts_us"] for t in threads))
                hashes[(short, n)].add(r["state_hash"])
                print(f"  round {k + 1}: {short} {n} threads: {r['ball_steps_per_s']:.3e}",
                      flush=True)
        first = builds[0][0]
        print(f"\n{bed}: ball-steps/s, median of {a.rounds} rounds")
        print("| revision | 1 thread | 2 threads | 2 / 1 | / first, 1 | / first, 2 | state hash |")
        print("|---|---|---|---|---|---|---|")
        med = {key: statistics.median(v) for key, v in rate.items()}
        for short, _, _ in builds:
            one, two = med[(short, 1)], med[(short, 2)]
            h = sorted(hashes[(short, 1)] | hashes[(short, 2)])
            print(f"| {short} | {one:.3g} | {two:.3g} | {two / one:.2f} | "
                  f"{one / med[(first, 1)]:.2f} | {two / med[(first, 2)]:.2f} | {', '.join(h)} |")
        print(f"\n{bed}: median over rounds of each round's ratio to {first} (range)")
        print("| revision | 1 thread | 2 threads | 2 / 1 in the round |")
        print("|---|---|---|---|")
        for short, _, _ in builds:
            cells = []
            for n in (1, 2):
                q = [x / y for x, y in zip(rate[(short, n)], rate[(first, n)])]
                cells.append(f"{statistics.median(q):.3f} ({min(q):.2f}–{max(q):.2f})")
            q = [y / x for x, y in zip(rate[(short, 1)], rate[(short, 2)])]
            cells.append(f"{statistics.median(q):.2f} ({min(q):.2f}–{max(q):.2f})")
            print(f"| {short} | " + " | ".join(cells) + " |")
        if a.phase_times:
            print(f"\n{bed}: integration / force pass, medians per step of the slower thread; "
                  "median over rounds (range)")
            print("| revision | 1 thread | 2 threads |")
            print("|---|---|---|")
            for short, _, _ in builds:
                cells = [f"{statistics.median(share[(short, n)]):.3f} "
                         f"({min(share[(short, n)]):.3f}–{max(share[(short, n)]):.3f})"
                         for n in (1, 2)]
                print(f"| {short} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
