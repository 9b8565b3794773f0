"""Contact-force networks, after Figs 10-12 of Lu & McDowell (2007).

Front elevation (x–z projection) of every ball–ball contact touching at a stage: a
line between the two ball centres, its width proportional to |F| (the thickest line
of a panel is that panel's largest force). The archive stores these from
contacts/{before,peak,after}/{from,to,force}; the counts, max and mean in the titles
are that group's attributes (ball–ball plus ball–wall contacts, as the paper counts
walls; the drawn lines are ball–ball only).

  fig10_contacts_before.png   every run before loading, one panel each (Fig. 10)
  fig11_contacts_<id>.png     a sphere run before, at peak, after unloading (Fig. 11)
  fig12_contacts_<id>.png     a clump run likewise (Fig. 12)
"""
import numpy as np
from matplotlib.collections import LineCollection

from fig_common import (LETTERS, MM, STAGE_TITLES, elevation, panels, paper_note,
                        peak_load_kn, save, settlement_at)
from paper_values import STAGES, paper_values

MAX_WIDTH = 2.5  # points, the line of a panel's largest force


def stage_stats(run, stage):
    a = lambda name: run.attribute(name, f"contacts/{stage}")  # noqa: E731
    return {"count": int(a("ball_contacts")) + int(a("wall_contacts")),
            "ball": int(a("ball_contacts")), "wall": int(a("wall_contacts")),
            "max": float(a("max_force")), "mean": float(a("mean_force"))}


def draw_network(ax, run, stage):
    """One panel: the network of `stage` over the box and the sleeper."""
    elevation(ax, run, settlement_at(run, stage))
    start = run.data(f"contacts/{stage}/from")
    end = run.data(f"contacts/{stage}/to")
    force = run.data(f"contacts/{stage}/force")
    if len(force):
        order = np.argsort(force)  # strongest drawn last, on top
        segments = np.stack([start[order][:, [0, 2]], end[order][:, [0, 2]]], axis=1) * MM
        widths = MAX_WIDTH * force[order] / force.max()
        ax.add_collection(LineCollection(segments, linewidths=widths, colors="black",
                                         capstyle="round", zorder=3))


def stage_title(run, stage, letter):
    s = stage_stats(run, stage)
    label = STAGE_TITLES[stage]
    if stage == "peak":
        label += f" ({peak_load_kn(run):g} kN)"
    paper = paper_values(run).get("contacts")
    p = paper[STAGES.index(stage)] if paper else None
    return (f"({letter}) {label}: max {s['max']:.0f} N, mean {s['mean']:.1f} N,\n"
            f"{s['count']:,} contacts ({s['ball']:,} ball–ball + {s['wall']:,} wall)"
            + paper_note(p and (p[1], p[2], p[0]), "max {:,} N, mean {} N, {:,} contacts"))


def stages_of(run):
    return [s for s in STAGES if run.has(f"contacts/{s}")]


def contacts_per_run(run, out_dir):
    """Fig. 11 (spheres) or 12 (clumps): the run's networks through the cycle."""
    stages = stages_of(run)
    number = 12 if run.is_clumps else 11
    fig, axes = panels(len(stages), f"Contact forces, {run.label} (cf. Fig. {number}): "
                       "line width ∝ contact force, thickest = panel maximum; front elevation")
    for k, (ax, stage) in enumerate(zip(axes, stages)):
        draw_network(ax, run, stage)
        ax.set_title(stage_title(run, stage, LETTERS[k]), fontsize=8)
    return save(fig, out_dir, f"fig{number}_contacts_{run.id}")


def contacts_before(runs, out_dir):
    """Fig. 10: every run's network under self-weight, before loading."""
    fig, axes = panels(len(runs), "Contact forces prior to loading (cf. Fig. 10): "
                       "line width ∝ contact force, thickest = panel maximum")
    for k, (ax, run) in enumerate(zip(axes, runs)):
        draw_network(ax, run, "before")
        ax.set_title(f"{run.label}\n" + stage_title(run, "before", LETTERS[k % 26]),
                     fontsize=8)
    return save(fig, out_dir, "fig10_contacts_before")
