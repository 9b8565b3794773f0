"""The physics every code of the peer benchmark runs (issue 7), and the summary each
reports after N steps, so that the three are compared field by field.

Conventions (checked by check_conventions.py, written up in docs/PERFORMANCE.md):
  - contact stiffness kn = ks = 5.08e9 N/m per CONTACT, ball-ball and ball-wall;
  - Coulomb friction 0.3, no damping of any kind, gravity 9.81 m/s^2 along -z;
  - fixed time step 1e-6 s;
  - density 2600 kg/m^3, clump mass and inertia summed over the balls (overlaps
    counted twice: LAMMPS fix rigid/small, YADE appendClumped, our mass mode "sum");
  - the box: 0.7 x 0.3 m, five infinite planes (x = 0, x = L, y = 0, y = W, z = 0),
    open at the top;
  - neighbour skin: 0.2 x the mean ball radius (our default), rebuilt when a ball has
    moved half of it, in every code.
"""
import dataclasses


@dataclasses.dataclass
class Physics:
    stiffness: float = 5.08e9   # N/m per contact, kn = ks
    friction: float = 0.3
    dt: float = 1e-6            # s
    gravity: float = 9.81       # m/s^2
    density: float = 2600.0     # kg/m^3
    length: float = 0.7         # m
    width: float = 0.3
    height: float = 0.45
    steps: int = 1000
    # Only the convention checks damp (so that bodies settle to their static
    # overlap); each code with its own kind of damping, which leaves the static
    # state alone. Damping ratio of a ball on one contact, 0: none.
    damping: float = 0.0

    def skin(self, packing):
        return 0.2 * packing.mean_radius()


def contact_summary(normals, tangentials):
    """Count, mean normal and mean tangential force of touching contacts, N."""
    n = len(normals)
    return {"count": n,
            "mean_normal_force_N": sum(normals) / n if n else 0.0,
            "mean_tangential_force_N": sum(tangentials) / n if n else 0.0}


def summary(code, threads, processes, packing, steps, timed_steps, seconds, ball_ball,
            ball_wall, kinetic):
    """The result record all three codes print: ball_ball and ball_wall are
    (normals, tangentials) lists over touching contacts; the physics is after `steps`,
    the speed over `timed_steps` of them in `seconds`."""
    both = (ball_ball[0] + ball_wall[0], ball_ball[1] + ball_wall[1])
    return {"code": code, "threads": threads, "processes": processes,
            "packing": packing.source, "bodies": len(packing.bodies), "balls": packing.balls,
            "clumps": packing.clumps, "steps": steps, "timed_steps": timed_steps,
            "seconds": seconds,
            "ball_steps_per_s": packing.balls * timed_steps / seconds if seconds > 0 else 0.0,
            "ball_ball": contact_summary(*ball_ball), "ball_wall": contact_summary(*ball_wall),
            "all": contact_summary(*both), "kinetic_energy_J": kinetic}
