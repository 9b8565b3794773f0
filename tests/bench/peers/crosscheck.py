"""The physics cross-check of the peer benchmark: after the same N steps from the same
packing, LAMMPS and YADE must agree with us within these tolerances (relative to our
value). The runs are deterministic; what separates the codes is the model details
they do not share, none of which is a bug:
  - the shear force carried by a contact that rolls: we project it onto the new
    contact plane and restore its length, LAMMPS projects it without restoring, YADE
    turns it with the contact frame, twist included;
  - the point where the relative velocity is taken: ours halfway into the overlap,
    LAMMPS and YADE at the radii (differences of overlap / radius ~ 1e-8);
  - LAMMPS integrates by velocity Verlet (full-step velocities in the kinetic
    energy), we and YADE by leapfrog (half-step velocities);
  - clump rotation: our `full` integrator, LAMMPS's Richardson iteration, YADE's
    exact aspherical step;
  - the order of every sum (and, with 2 ranks or threads, its split).
They make the trajectories part slowly, no faster than the order of the sums alone
does: the same code on 2 threads or ranks instead of 1 (nothing changed but how its
sums are split) parts from itself by as much as the codes part from each other.
Measured on the sphere bed (docs/PERFORMANCE.md, "Peers", after 3,000 and 10,000
steps): YADE on 2 threads differed from YADE on 1 by up to 0.6 % in ball-ball
contacts, 1.4 % in wall contacts, 0.7 % in mean normal force, 1.2 % in mean
tangential force and 0.3 % in kinetic energy; the peers differed from us by at most
1.1 %, 1.2 %, 0.8 %, 1.2 % and 1.1 %.
The tolerances leave about three times that:
  counts 3 %: a contact opens or closes where its overlap crosses zero; in the
      sphere bed 0.5 % of the ball-ball contacts and 1.8 % of the ball-wall
      contacts sit within 1 % of the mean overlap of doing so;
  mean normal force 3 %: the contacts carry the bed's weight, the same in every
      code, but the mean is over the contacts, so it moves against the count when
      contacts that carry almost nothing flicker;
  mean tangential force and kinetic energy 5 %: both start from zero (a packing has
      no shear history and no velocities) and grow as the bed sags onto its new
      shear springs, which is where the model details above act.
What a wrong convention does, measured: LAMMPS with half the contact stiffness gave,
after 3,000 steps on the sphere bed, mean normal force -6.3 %, mean tangential force
-10 %, ball-ball contacts +2.7 % and kinetic energy +2.6 % against us: the force
tolerances catch it, the count and energy ones would not. The sharp test of the
conventions is check_conventions.py (closed forms to 1e-4); this cross-check is the
test that the same bed does the same thing in all three codes.
"""

TOLERANCES = [("ball-ball contacts", ("ball_ball", "count"), 0.03),
              ("ball-wall contacts", ("ball_wall", "count"), 0.03),
              ("mean normal force (N)", ("all", "mean_normal_force_N"), 0.03),
              ("mean tangential force (N)", ("all", "mean_tangential_force_N"), 0.05),
              ("kinetic energy (J)", ("kinetic_energy_J",), 0.05)]


def value(record, key):
    v = record
    for k in key:
        v = v[k]
    return float(v)


def report(bed, first, parallel):
    """Prints the table; returns True when every peer value is within tolerance of ours.
    `first`: code -> record of its 1-thread/1-process run; `parallel`: more records
    (2 ranks, 2 threads) checked against our 1-thread run too."""
    ours = first["ballast"]
    others = [("lammps 1", first["lammps"]), ("yade 1", first["yade"])] + [
        (f"{r['code']} 2", r) for r in parallel]
    print(f"\n{bed}: physics after {ours['steps']} steps, relative to ours (1 thread)")
    print("| quantity | ours | " + " | ".join(n for n, _ in others) + " | tolerance |")
    print("|---|---|" + "---|" * len(others) + "---|")
    ok = True
    for name, key, tol in TOLERANCES:
        mine = value(ours, key)
        cells = []
        for _, r in others:
            v = value(r, key)
            d = (v - mine) / abs(mine) if mine else (0.0 if v == 0 else float("inf"))
            ok = ok and abs(d) <= tol
            cells.append(f"{v:.6g} ({d:+.2%}){'' if abs(d) <= tol else ' FAIL'}")
        print(f"| {name} | {mine:.6g} | " + " | ".join(cells) + f" | {tol:.0%} |")
    print(f"{bed}: physics cross-check {'passed' if ok else 'FAILED'}", flush=True)
    return ok
