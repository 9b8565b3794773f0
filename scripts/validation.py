#!/usr/bin/python3
"""Our box-test figures beside Lu & McDowell (2007)'s, as a Markdown table.

    /usr/bin/python3 scripts/validation.py spheres=runs/spheres.h5 sample1=runs/sample1.h5

Each argument is NAME=ARCHIVE, NAME one of spheres, sample1, sample2; an archive is
a `ballast run -o` file (group /run) or a study archive's run group given as
ARCHIVE:/runs/ID. The paper's numbers are from its Figs 11-18 and section 3.3.
"""
import sys

import h5py

# name: (porosity, contacts before/peak/after (count, max N, mean N), rotation mean/max
# loading, unloading, cycle (deg), max displacement at peak / after (mm))
PAPER = {
    "spheres": {
        "porosity": 0.37,
        "contacts": [(10337, 482, 29.9), (10323, 4050, 336.2), (10328, 1012, 42.7)],
        "rotation": [(5.18, 48.3), (2.92, 26.5), (7.25, 63.2)],
        "displacement_mm": (8.25, 11.79),
    },
    "sample1": {
        "porosity": 0.35,
        "contacts": [(282955, 374, 15.4), (282955, 4233, 164.1), (282955, 1354, 34.4)],
        "rotation": [(0.061, 8.89), (0.033, 3.15), (0.062, 3.31)],
        "displacement_mm": (2.34, 2.32),
    },
    "sample2": {"porosity": 0.37},
}


def open_run(spec):
    path, _, group = spec.partition(":")
    f = h5py.File(path, "r")
    return f[group or "run"]


def row(label, ours, paper, fmt="{:.3g}"):
    p = "—" if paper is None else fmt.format(paper)
    o = "—" if ours is None else fmt.format(ours)
    return f"| {label} | {o} | {p} |"


def table(name, run):
    a = run.attrs
    paper = PAPER.get(name, {})
    lines = [f"### {name} ({int(a['bodies'])} bodies, {int(a['balls'])} balls, "
             f"dt {a['dt'] * 1e6:.3f} µs, {a['wall_seconds'] / 60:.1f} min on the run's machine)",
             "", "| quantity | ours | paper |", "|---|---|---|"]
    lines.append(row("porosity, 5 mm grid under the sleeper", a["porosity_grid"],
                     paper.get("porosity")))
    spheres = run["porosity/sphere_porosity"][:]
    if len(spheres):
        heights = ", ".join(f"{h * 1e3:.0f}" for h in run["porosity/sphere_heights"][:])
        lines.append(row(f"porosity, measurement spheres on the column axis (mean of z = "
                         f"{heights} mm)", float(spheres.mean()), paper.get("porosity")))
    stages = [("before loading", "before"), ("at peak load", "peak"), ("after unloading", "after")]
    for k, (label, group) in enumerate(stages):
        if group not in run["contacts"]:
            continue
        c = run["contacts"][group].attrs
        pc = paper.get("contacts", [None] * 3)[k]
        lines.append(row(f"contacts {label}: count (ball–ball + ball–wall)",
                         c["ball_contacts"] + c["wall_contacts"], pc and pc[0], "{:.0f}"))
        lines.append(row(f"contacts {label}: max force (N)", c["max_force"], pc and pc[1],
                         "{:.0f}"))
        lines.append(row(f"contacts {label}: mean force (N)", c["mean_force"], pc and pc[2],
                         "{:.1f}"))
    if int(a["loaded"]):
        for k, phase in enumerate(["loading", "unloading", "cycle"]):
            pr = paper.get("rotation", [None] * 3)[k]
            lines.append(row(f"rotation, {phase}: mean (°)", a[f"rotation_{phase}_mean_deg"],
                             pr and pr[0]))
            lines.append(row(f"rotation, {phase}: max (°)", a[f"rotation_{phase}_max_deg"],
                             pr and pr[1]))
        pd = paper.get("displacement_mm", (None, None))
        lines.append(row("max displacement at 40 kN (mm)", a["max_displacement_peak"] * 1e3,
                         pd[0]))
        lines.append(row("max displacement after the cycle (mm)",
                         a["max_displacement_after"] * 1e3, pd[1]))
        lines.append(row("sleeper settlement at peak (mm)", a["settlement_peak"] * 1e3, None))
        lines.append(row("permanent settlement (mm)", a["permanent_settlement"] * 1e3, None))
        lines.append(row("resilient settlement (mm)", a["resilient_settlement"] * 1e3, None))
        lines.append(row("sleeper force error, rms (N)", a["rms_force_error"], None, "{:.0f}"))
    return "\n".join(lines)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for arg in sys.argv[1:]:
        name, _, spec = arg.partition("=")
        if name not in PAPER:
            sys.exit(f"unknown sample name '{name}' (allowed: {', '.join(PAPER)})")
        print(table(name, open_run(spec)))
        print()


if __name__ == "__main__":
    main()
