"""The settled beds of the peer benchmark, built once by the box-test preparation and
cached as packing files (build/peers/<bed>.txt, with the log of the run beside it).

The preparation runs with the benchmark's own contact law, so that the bed is at
rest under it: balls, walls and the base at 2 x 5.08e9 N/m (5.08e9 per contact in
series; the paper's rubber base would leave overlaps of micrometres that a stiff
base turns into kilonewtons), friction 0.3 for the last stage too, clump mass mode
"sum", and stop_after "compact": radius expansion, the frictionless settling under
10 g (it runs to its 400,000-step limit, and it is what makes the bed dense enough
to settle: without it, the Sample 1 bed was still at an unbalanced-force ratio of
0.1 after 400,000 steps of compaction at 10 g and as many at 1 g), then compaction
at 10 g and at 1 g to a ratio of 0.005.
"""
import os
import subprocess

SCENES = {"spheres": "spheres_settle_400k.json", "sample1": "sample1_settle_400k.json"}

SETTINGS = ["/materials/ball_stiffness=1.016e10", "/materials/wall_stiffness=1.016e10",
            "/materials/base_stiffness=1.016e10", "/materials/friction_loading=0.3",
            "/particles/mass_mode=sum", "/preparation/stop_after=compact"]


def ensure(bed, ballast, cases, cache, threads=2):
    """Path of the cached bed, built first if missing or built by another recipe
    (the command that built it is kept beside it in <bed>.cmd)."""
    if bed not in SCENES:
        raise ValueError(f"unknown bed '{bed}' (allowed: {', '.join(SCENES)})")
    os.makedirs(cache, exist_ok=True)
    path = os.path.join(cache, f"{bed}.txt")
    recipe = ["run", os.path.join("box_test", SCENES[bed])] + [f"--set {s}" for s in SETTINGS]
    stamp = os.path.join(cache, f"{bed}.cmd")
    if os.path.exists(path) and os.path.exists(stamp) and open(stamp).read() == "\n".join(recipe):
        print(f"bed {bed}: cached {path}", flush=True)
        return path
    partial = path + ".partial"
    command = [ballast, "run", os.path.join(cases, recipe[1]), "--threads", str(threads),
               "--export-packing", partial]
    for s in SETTINGS:
        command += ["--set", s]
    print(f"bed {bed}: building it once ({' '.join(command)}); minutes", flush=True)
    # Passive waiting: a spinning OpenMP barrier on a busy host slows the run tenfold
    # or more; the preparation is not what is timed.
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    with open(os.path.join(cache, f"{bed}.log"), "w") as log:
        done = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=env)
    if done.returncode != 0:
        raise RuntimeError(f"building bed {bed} failed (exit {done.returncode}); see "
                           f"{os.path.join(cache, bed + '.log')}")
    os.replace(partial, path)  # only a finished bed is ever cached
    with open(stamp, "w") as f:
        f.write("\n".join(recipe))
    return path
