"""Our engine in the peer benchmark: `ballast bench-bed` (study/cmd_bench_bed.cpp) on
the same packing file, with the same physics (cases/bench_bed.hpp)."""
import json
import os
import subprocess

from packing import read_packing


def run(ballast, packing_path, p, threads, local_damping=0.0, export=None, timeout=900,
        extra=()):
    """Runs bench-bed; returns its JSON record (the same fields as the peers' and a
    state hash). `export`: also write the bed after the last step there; `extra`:
    more bench-bed flags (e.g. --simd-lanes 0)."""
    command = [ballast, "bench-bed", packing_path, "--steps", str(p.steps), "--threads",
               str(threads), "--json", "--stiffness", repr(p.stiffness), "--friction",
               repr(p.friction), "--dt", repr(p.dt), "--density", repr(p.density)]
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
