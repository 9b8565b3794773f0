"""YADE from a packing file: writes a script for `yade -n -x -j T`, runs it and reads
back the time of the stepping and the physics.

The model, with every factor checked by check_conventions.py:
  FrictMat + Ip2_FrictMat_FrictMat_FrictPhys + Law2_ScGeom_FrictPhys_CundallStrack:
      kn = 2 (E1 R1)(E2 R2) / (E1 R1 + E2 R2), ks = the same with E_i R_i nu_i, and a
      sphere-wall contact takes the sphere's radius for both sides. With one radius R
      and E = k/R, nu = 1 every contact, ball-ball and ball-wall, has kn = ks = k
      ("kn is E R for equal spheres, ks/kn is poisson"). Clumps have balls of many
      radii, and no single wall modulus then gives k against all of them, so they
      set kn and ks per contact through the functor's MatchMakers (algo 'val');
  clumps: O.bodies.appendClumped, which sums the members' masses and inertias
      (parallel axes, overlaps counted twice: our mass mode "sum");
  sphere mass 4/3 pi r^3 rho from the material density;
  NewtonIntegrator(damping=0): leapfrog, half-step velocities like ours, exact
      aspherical rotation of clumps; O.dt fixed (no time stepper engine);
  InsertionSortCollider(verletDist = skin/2): bounds grown by half the skin, so
      pairs within about a skin are listed and the sort reruns after a move of half
      the skin, as in the other two codes.
"""
import json
import os
import subprocess
import sys

from physics import summary

PEERS = os.path.dirname(os.path.abspath(__file__))

# Runs inside YADE's Python. PARAMS is filled in by write_script.
SCRIPT = r'''
import json, math, sys, time
PARAMS = json.loads(r"""{params}""")
sys.path.insert(0, PARAMS["peers"])
from packing import read_packing

p = PARAMS
pk = read_packing(p["packing"])
k = p["stiffness"]
one_radius = len(set(pk.radii)) == 1
friction = math.atan(p["friction"])
if one_radius:
    mat = O.materials.append(FrictMat(young=k / pk.radii[0], poisson=1.0, density=p["density"],
                                      frictionAngle=friction))
    ip2 = Ip2_FrictMat_FrictMat_FrictPhys()
else:
    mat = O.materials.append(FrictMat(young=k / pk.mean_radius(), poisson=1.0,
                                      density=p["density"], frictionAngle=friction))
    ip2 = Ip2_FrictMat_FrictMat_FrictPhys(kn=MatchMaker(algo="val", val=k),
                                          ks=MatchMaker(algo="val", val=k))
L, W = p["length"], p["width"]
for position, axis, sense in (((0, 0, 0), 0, 1), ((L, 0, 0), 0, -1), ((0, 0, 0), 1, 1),
                              ((0, W, 0), 1, -1), ((0, 0, 0), 2, 1)):
    O.bodies.append(wall(position, axis=axis, sense=sense, material=mat))
members = []  # YADE ids of each packing body's balls
for body in pk.bodies:
    spheres = [sphere(pk.centres[i], pk.radii[i], material=mat) for i in body]
    if len(body) == 1:
        members.append([O.bodies.append(spheres[0])])
    else:
        members.append(O.bodies.appendClumped(spheres)[1])
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()], verletDist=0.5 * p["skin"]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [ip2],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=p["local_damping"], gravity=(0, 0, -p["gravity"])),
]
O.dt = p["dt"]
O.run(1, True)  # set-up: the first sort of all bounds from scratch, not timed
start = time.time()
O.run(p["steps"] - 1, True)
seconds = time.time() - start
assert O.dt == p["dt"] and O.iter == p["steps"], (O.dt, O.iter)

walls = set(range(5))
ball_ball, ball_wall = ([], []), ([], [])
for i in O.interactions:
    if not i.isReal or i.geom.penetrationDepth <= 0:
        continue
    kind = ball_wall if i.id1 in walls or i.id2 in walls else ball_ball
    kind[0].append(i.phys.normalForce.norm())
    kind[1].append(i.phys.shearForce.norm())
kinetic = 0.0
for b in O.bodies:
    if b.id in walls or b.isClumpMember:
        continue
    s = b.state
    w = s.ori.conjugate().Rotate(s.angVel)  # body frame, where the inertia is diagonal
    kinetic += 0.5 * s.mass * s.vel.squaredNorm() + 0.5 * sum(s.inertia[d] * w[d] ** 2 for d in range(3))
positions = [[list(O.bodies[i].state.pos) for i in ids] for ids in members]
result = {{"seconds": seconds, "ball_ball": ball_ball, "ball_wall": ball_wall,
          "kinetic": kinetic, "positions": positions, "steps": O.iter}}
with open(p["result"], "w") as f:
    json.dump(result, f)
'''


def write_script(packing, p, directory, local_damping=0.0):
    os.makedirs(directory, exist_ok=True)
    params = {"peers": PEERS, "packing": os.path.abspath(packing.source),
              "result": os.path.abspath(os.path.join(directory, "result.json")),
              "stiffness": p.stiffness, "friction": p.friction, "dt": p.dt, "gravity": p.gravity,
              "density": p.density, "length": p.length, "width": p.width, "steps": p.steps,
              "skin": p.skin(packing), "local_damping": local_damping}
    path = os.path.join(directory, "bed.py")
    with open(path, "w") as f:
        f.write(f"# generated by tests/bench/peers/yade_peer.py from {packing.source}\n")
        f.write(SCRIPT.format(params=json.dumps(params, indent=1)))
    return path


def run(directory, threads, timeout=900):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    done = subprocess.run(["yade", "-n", "-x", "-j", str(threads), "bed.py"], cwd=directory,
                          capture_output=True, text=True, timeout=timeout, env=env)
    result = os.path.join(directory, "result.json")
    if done.returncode != 0 or not os.path.exists(result):
        tail = "\n".join((done.stdout + done.stderr).splitlines()[-15:])
        raise RuntimeError(f"YADE failed in {directory} (exit {done.returncode}):\n{tail}")
    with open(result) as f:
        return json.load(f)


def results(packing, raw, threads):
    # Timed: steps 2..N (the first one built the collider's lists from scratch).
    return summary("yade", threads, 1, packing, raw["steps"], raw["steps"] - 1, raw["seconds"],
                   tuple(raw["ball_ball"]), tuple(raw["ball_wall"]), raw["kinetic"])


def positions(raw):
    """Ball centres after the run, in packing ball order."""
    return [tuple(x) for body in raw["positions"] for x in body]
