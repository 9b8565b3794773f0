"""Particle rotations through the load cycle, after Figs 13-14 of Lu & McDowell (2007).

One circle per particle at its centre (front elevation, x–z), its radius proportional
to the magnitude of the particle's accumulated rotation (particles/rotation_<phase>,
degrees: the vector sum of the rotations about three axes, as the paper). The scale
is shared by the run's three panels: the run's largest rotation draws as a circle of
one nominal particle radius. Classes as in the paper: spheres grey 10°–20°, black
> 20°; clumps grey 0.1°–1°, black > 1°; smaller rotations are open circles.
Centres are those at the end of the phase: at peak load for loading, after the cycle
for unloading and the whole cycle.

  fig13_rotations_<id>.png   a sphere run: loading, unloading, whole cycle (Fig. 13)
  fig14_rotations_<id>.png   a clump run likewise (Fig. 14)
"""
import numpy as np
from matplotlib.collections import PatchCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Circle

from fig_common import LETTERS, MM, elevation, panels, paper_note, save, settlement_at
from paper_values import PHASES, ROTATION_CLASSES, paper_values

PHASE_TITLES = {"loading": "during loading", "unloading": "during unloading",
                "cycle": "after the complete cycle"}
PHASE_POSITION = {"loading": "peak", "unloading": "end", "cycle": "end"}
PHASE_STAGE = {"loading": "peak", "unloading": "after", "cycle": "after"}
CLASS_STYLE = {"open": ("white", "0.35"), "grey": ("0.6", "0.3"), "black": ("black", "black")}


def rotation_classes(degrees, grey, black):
    """Index arrays of the open (< grey), grey ([grey, black]) and black (> black) sets."""
    return {"open": np.flatnonzero(degrees < grey),
            "grey": np.flatnonzero((degrees >= grey) & (degrees <= black)),
            "black": np.flatnonzero(degrees > black)}


def draw_rotations(ax, run, phase, radius_per_degree, limits):
    elevation(ax, run, settlement_at(run, PHASE_STAGE[phase]))
    degrees = run.data(f"particles/rotation_{phase}")
    centres = run.data(f"particles/position_{PHASE_POSITION[phase]}")[:, [0, 2]] * MM
    classes = rotation_classes(degrees, *limits)
    for name, index in classes.items():
        face, edge = CLASS_STYLE[name]
        circles = [Circle(c, r) for c, r in zip(centres[index],
                                                radius_per_degree * degrees[index])]
        ax.add_collection(PatchCollection(circles, facecolor=face, edgecolor=edge,
                                          linewidth=0.4, zorder=3 if name == "open" else 4))
    grey, black = limits
    handles = [Line2D([], [], ls="", marker="o", mfc=CLASS_STYLE[n][0], mec=CLASS_STYLE[n][1],
                      label=f"{text}: {len(classes[n])}")
               for n, text in (("open", f"< {grey:g}°"), ("grey", f"{grey:g}°–{black:g}°"),
                               ("black", f"> {black:g}°"))]
    ax.legend(handles=handles, loc="upper left", fontsize=7, framealpha=0.9,
              title="particles", title_fontsize=7)
    return degrees


def rotations_per_run(run, out_dir):
    """Fig. 13 (spheres) or 14 (clumps) for one loaded run."""
    limits = ROTATION_CLASSES["clumps" if run.is_clumps else "spheres"]
    largest = max(float(run.attribute(f"rotation_{p}_max_deg")) for p in PHASES)
    particle_radius = 0.5 * float(run.scene_value("particles", "diameter")) * MM
    radius_per_degree = particle_radius / largest if largest > 0 else 0.0
    number = 14 if run.is_clumps else 13
    fig, axes = panels(len(PHASES), f"Particle rotations, {run.label} (cf. Fig. {number}): "
                       f"circle radius ∝ rotation, {largest:.3g}° = {particle_radius:.1f} mm; "
                       "front elevation")
    paper = paper_values(run).get("rotation")
    for k, (ax, phase) in enumerate(zip(axes, PHASES)):
        draw_rotations(ax, run, phase, radius_per_degree, limits)
        mean = float(run.attribute(f"rotation_{phase}_mean_deg"))
        peak = float(run.attribute(f"rotation_{phase}_max_deg"))
        p = paper[k] if paper else None
        ax.set_title(f"({LETTERS[k]}) {PHASE_TITLES[phase]}: max {peak:.3g}°, "
                     f"mean {mean:.3g}°" + paper_note(p and (p[1], p[0]), "max {}°, mean {}°"),
                     fontsize=8)
    return save(fig, out_dir, f"fig{number}_rotations_{run.id}")
