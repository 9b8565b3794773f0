"""Our engine in the peer benchmark: `ballast bench-bed` (tests/bench/bed/cmd_bench_bed.cpp) on
the same packing file, with the same physics (cases/bench_bed.hpp)."""
import json
import os
import subprocess

from packing import read_packing


ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
SPHERE_BED = os.path.join(ROOT, "build", "peers", "spheres.txt")  # make bench-peers' cache


def physics_flags(p):
    """The bench-bed flags that give it the benchmark's physics `p` (physics.Physics)."""
    return ["--stiffness", repr(p.stiffness), "--friction", repr(p.friction), "--dt", repr(p.dt),
            "--density", repr(p.density)]


def binary_and_bed(bed, script):
    """The ballast binary ($BALLAST, else the build's) and `bed`, checked to exist;
    exits naming `script` when it does not (the beds are make bench-peers' cache)."""
    if not os.path.exists(bed):
        raise SystemExit(f"{script}: no bed at {bed} (run make bench-peers once)")
    return os.environ.get("BALLAST", os.path.join(ROOT, "build", "study", "ballast")), bed


def run(ballast, packing_path, p, threads, local_damping=0.0, export=None, timeout=900,
        extra=()):
    """Runs bench-bed; returns its JSON record (the same fields as the peers' and a
    state hash). `export`: also write the bed after the last step there; `extra`:
    more bench-bed flags (e.g. --simd-lanes 0)."""
    command = [ballast, "bench-bed", packing_path, "--steps", str(p.steps), "--threads",
               str(threads), "--json"] + physics_flags(p)
    if local_damping:
        command += ["--local-damping", repr(local_damping)]
    if export:
        command += ["--export-packing", export]
    command += list(extra)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    done = subprocess.run(command, capture_output=True, text=True, timeout=timeout, env=env)
    if done.returncode != 0:
        raise RuntimeError(f"ballast bench-bed failed (exit {done.returncode}):\n{done.stderr[-2000:]}")
    return json.loads(done.stdout)


def positions(export):
    return read_packing(export).centres
