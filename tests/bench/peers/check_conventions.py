#!/usr/bin/python3
"""Checks, rather than assumes, the stiffness, mass and density conventions behind
the peer benchmark (issue 7): every code must give kn = ks = 5.08e9 N/m per contact
and sum a clump's mass over its balls.

1. Static overlaps. A sphere on the floor, a stack of two spheres and a two-ball
   clump lying on the floor start touching and settle (each code damped its own
   way: damping leaves the static state alone). Their overlaps must be m*g/k: the
   sphere m g/k; the stack m g/k between the balls and 2 m g/k at the floor; each
   ball of the clump its own m_i g/k (the clump's centre of mass is where summed
   masses put it). Positions are compared to 17 digits; overlaps are ~1e-10 m on
   centres at 0.018 m, resolved to ~3e-8 of themselves.
2. One contact as each peer reports it. LAMMPS: two balls and a ball on the floor,
   overlapping by 1e-9 m with a relative tangential velocity, heavy enough not to
   move: after one step Fn = kn*overlap and |Ft| = kt*v*dt. YADE: the kn and ks it
   builds for sphere-sphere and sphere-wall contacts from young = k/R, poisson = 1,
   for unequal radii, and with the functor's MatchMakers.

    /usr/bin/python3 tests/bench/peers/check_conventions.py --ballast build/study/ballast --work DIR
Exit status 1 when a check fails.
"""
import argparse
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ballast_peer  # noqa: E402
import lammps_peer  # noqa: E402
import yade_peer  # noqa: E402
from packing import read_packing  # noqa: E402
from physics import Physics  # noqa: E402

K, G, RHO, R = 5.08e9, 9.81, 2600.0, 0.018125
R1, R2, DX = 0.012, 0.008, 0.016  # the clump: two overlapping balls side by side
# Settled to 1e-4 of the overlap: rounding leaves ~3e-8; any wrong convention is off by
# far more (a missing series factor 2 by 100 %, a YADE wall modulus meant for another
# radius by tens of %, a clump mass corrected for the overlap of its balls by the
# lens's share of their volume, printed below).
TOLERANCE = 1e-4


def mass(r):
    return RHO * 4.0 / 3.0 * math.pi * r ** 3


def lens_volume(r1, r2, d):
    return (math.pi * (r1 + r2 - d) ** 2 * (d * d + 2 * d * r2 - 3 * r2 * r2 + 2 * d * r1
                                            + 6 * r1 * r2 - 3 * r1 * r1) / (12 * d))


def write_packing(path):
    with open(path, "w") as f:
        f.write("# convention checks: sphere on the floor, two-sphere stack, two-ball clump\n")
        f.write(f"0 0.1 0.15 {R!r} {R!r}\n1 0.3 0.15 {R!r} {R!r}\n2 0.3 0.15 {3 * R!r} {R!r}\n")
        f.write(f"3 0.5 0.15 {R1!r} {R1!r}\n3 {0.5 + DX!r} 0.15 {R2!r} {R2!r}\n")


def overlaps(x):
    """Measured overlaps from ball centres in packing order, with their expected values."""
    dist = math.dist(x[1], x[2])
    return [("sphere on the floor", R - x[0][2], mass(R) * G / K),
            ("stack: between the balls", 2 * R - dist, mass(R) * G / K),
            ("stack: at the floor", R - x[1][2], 2 * mass(R) * G / K),
            ("clump: larger ball at the floor", R1 - x[3][2], mass(R1) * G / K),
            ("clump: smaller ball at the floor", R2 - x[4][2], mass(R2) * G / K)]


def static_rows(ballast, work):
    path = os.path.join(work, "conventions.txt")
    write_packing(path)
    packing = read_packing(path)
    p = Physics(steps=20000, damping=0.3)
    ours = os.path.join(work, "ours_after.txt")
    ballast_peer.run(ballast, path, p, 1, local_damping=0.7, export=ours)
    lammps_peer.write_inputs(packing, p, os.path.join(work, "lammps"))
    lammps_peer.run(os.path.join(work, "lammps"), 1)
    lmp = lammps_peer.positions(os.path.join(work, "lammps"))
    yade_peer.write_script(packing, p, os.path.join(work, "yade"), local_damping=0.7)
    raw = yade_peer.run(os.path.join(work, "yade"), 1)
    rows = []
    for code, x in (("ballast", ballast_peer.positions(ours)),
                    ("lammps", [lmp[k] for k in range(packing.balls)]),
                    ("yade", yade_peer.positions(raw))):
        for name, measured, expected in overlaps(x):
            rows.append((code, "overlap, " + name, measured, expected, TOLERANCE))
    return rows


LAMMPS_PROBE = """units si
atom_style sphere
boundary f f f
comm_modify vel yes
region box block -0.1 0.3 -0.1 0.1 -0.1 0.2
create_box 1 box
# Two balls overlapping by 1e-9 m, and a third on the floor by 1e-9 m; density 1e15
# so that one step of the forces moves nothing measurably.
create_atoms 1 single 0.0 0.0 0.1
create_atoms 1 single 0.0 0.0 {z2!r}
create_atoms 1 single 0.2 0.0 {z3!r}
set group all diameter {d!r} density 1e15
velocity all set 0 0 0
set atom 2 vx {v!r}
set atom 3 vx {v!r}
pair_style gran/hooke/history {k!r} {k!r} 0 0 10000 0
pair_coeff * *
neighbor 0.001 bin
timestep {dt!r}
fix move all nve/sphere
fix floor all wall/gran hooke/history {k!r} {k!r} 0 0 10000 0 zplane 0.0 NULL contacts
compute pairs all pair/local dist force p4
dump pairs all local 1 pairs.dump c_pairs[*]
dump_modify pairs format float %.17g
dump floor all custom 1 floor.dump id f_floor[*]
dump_modify floor format float %.17g
run 1
"""


def lammps_rows(work):
    d = os.path.join(work, "lammps_probe")
    os.makedirs(d, exist_ok=True)
    overlap, v, dt = 1e-9, 1e-3, 1e-6
    with open(os.path.join(d, "in.probe"), "w") as f:
        f.write(LAMMPS_PROBE.format(z2=0.1 + 2 * R - overlap, z3=R - overlap, d=2 * R, v=v, k=K,
                                    dt=dt))
    subprocess.run(["lmp", "-in", "in.probe", "-log", "none", "-screen", "none", "-nocite"],
                   cwd=d, check=True, timeout=120)
    _, pair = lammps_peer._dump_rows(os.path.join(d, "pairs.dump"))
    names, floor = lammps_peer._dump_rows(os.path.join(d, "floor.dump"))
    wall = [row for row in floor if row[0] == "3"][0]
    fx, fz = float(wall[2]), float(wall[4])
    return [("lammps", "ball-ball Fn = kn*overlap", float(pair[0][1]), K * overlap, 1e-6),
            ("lammps", "ball-ball |Ft| = kt*v*dt", float(pair[0][2]), K * v * dt, 1e-6),
            ("lammps", "ball-wall Fn = kn*overlap", fz, K * overlap, 1e-6),
            ("lammps", "ball-wall |Ft| = kt*v*dt", abs(fx), K * v * dt, 1e-6)]


YADE_PROBE = """
import math
k = {k!r}
def contact(r1, r2, young1, young2, ip2):
    O.reset()
    m1 = O.materials.append(FrictMat(young=young1, poisson=1.0, density=2600, frictionAngle=0.3))
    m2 = O.materials.append(FrictMat(young=young2, poisson=1.0, density=2600, frictionAngle=0.3))
    if r2 is None:  # a sphere on a wall
        O.bodies.append(wall((0, 0, 0), axis=2, sense=1, material=m2))
        O.bodies.append(sphere((0, 0, r1 - 1e-9), r1, material=m1))
    else:
        O.bodies.append(sphere((0, 0, 0), r1, material=m1))
        O.bodies.append(sphere((0, 0, r1 + r2 - 1e-9), r2, material=m2))
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [ip2],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0, gravity=(0, 0, 0))]
    O.dt = 1e-12
    O.step()
    i = [i for i in O.interactions if i.isReal][0]
    return i.phys.kn, i.phys.ks, i.phys.normalForce.norm() / i.geom.penetrationDepth
plain = Ip2_FrictMat_FrictMat_FrictPhys
matched = lambda: Ip2_FrictMat_FrictMat_FrictPhys(kn=MatchMaker(algo="val", val=k),
                                                  ks=MatchMaker(algo="val", val=k))
R, R1, R2 = {R!r}, {R1!r}, {R2!r}
rows = []
for name, args in (("equal spheres, E = k/R", (R, R, k / R, k / R, plain())),
                   ("sphere on a wall, E = k/R", (R, None, k / R, k / R, plain())),
                   ("unequal spheres, E_i = k/R_i", (R1, R2, k / R1, k / R2, plain())),
                   ("small sphere on a wall, E = k/R_mean", (R2, None, k / R2, 2 * k / (R1 + R2), plain())),
                   ("unequal spheres, MatchMaker", (R1, R2, 1e9, 1e9, matched())),
                   ("small sphere on a wall, MatchMaker", (R2, None, 1e9, 1e9, matched()))):
    rows.append((name,) + contact(*args))
import json
json.dump(rows, open("probe.json", "w"))
"""


def yade_rows(work):
    d = os.path.join(work, "yade_probe")
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "probe.py"), "w") as f:
        f.write(YADE_PROBE.format(k=K, R=R, R1=R1, R2=R2))
    subprocess.run(["yade", "-n", "-x", "-j", "1", "probe.py"], cwd=d, check=True, timeout=300,
                   capture_output=True)
    import json
    rows = []
    for name, kn, ks, fn_over_un in json.load(open(os.path.join(d, "probe.json"))):
        # The wall against a sphere it was not sized for is the one convention that
        # cannot give k: shown, expected off, so the MatchMaker rows are the fix.
        expected = K if "R_mean" not in name else 2 * (K * R2 / R2) * (2 * K * R2 / (R1 + R2)) / (
            K + 2 * K * R2 / (R1 + R2))
        rows.append(("yade", f"kn, {name}", kn, expected, 1e-12))
        rows.append(("yade", f"ks, {name}", ks, expected, 1e-12))
        rows.append(("yade", f"Fn/overlap, {name}", fn_over_un, expected, 1e-6))
    return rows


def run(ballast, work):
    """Runs every check and prints them; returns the number that failed."""
    os.makedirs(work, exist_ok=True)
    print("conventions: static overlaps (damped to rest), one contact in LAMMPS and in YADE")
    v_lens = lens_volume(R1, R2, math.hypot(DX, R1 - R2))
    print(f"  the clump's balls overlap by {v_lens / (4 / 3 * math.pi * (R1**3 + R2**3)):.1%} of "
          "their volume: the error a mass corrected for overlaps would make")
    rows = static_rows(ballast, work) + lammps_rows(work) + yade_rows(work)
    failed = 0
    for code, what, measured, expected, tol in rows:
        error = abs(measured - expected) / abs(expected)
        ok = error <= tol
        failed += not ok
        print(f"  {'ok  ' if ok else 'FAIL'} {code:8s} {what:48s} {measured:.10g} vs {expected:.10g}"
              f" (rel. error {error:.1e}, tolerance {tol:.0e})")
    print(f"conventions: {len(rows) - failed} of {len(rows)} checks passed", flush=True)
    return failed


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ballast", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    return 1 if run(a.ballast, a.work) else 0


if __name__ == "__main__":
    sys.exit(main())
