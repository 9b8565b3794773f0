"""Particle displacement vectors, after Figs 15-17 of Lu & McDowell (2007).

Front elevation (x–z) of each particle's displacement from the start of loading to
peak load and to the end of the cycle: an arrow from the particle's centre at the
start, its x and z components drawn magnified. Figs 15 (spheres) and 16 (clumps) use
one magnification for every run drawn together, so that runs compare at a glance:
the largest displacement of all runs draws as TARGET_MM (at most; factors are 1, 2,
5 × 10^k). Fig. 17 redraws a clump run magnified further (the paper: ×80), with the
factor that draws its own largest vector as TARGET_MM, when that is larger than the
common one; every title states its factor. The max in a title is the largest 3-D
displacement (the run's attributes max_displacement_peak and _after).

  fig15_displacements_<id>.png   a sphere run at peak and after the cycle
  fig16_displacements_<id>.png   a clump run, same scale as Fig. 15
  fig17_displacements_<id>.png   a clump run, magnified
"""
import math

from fig_common import (LETTERS, MM, elevation, panels, paper_note, peak_load_kn, save,
                        settlement_at)
from paper_values import paper_values

TARGET_MM = 40.0  # drawn length of the largest vector, about one particle diameter
STAGES = (("peak", "max_displacement_peak", "peak", "at peak load"),
          ("end", "max_displacement_after", "after", "after one cycle"))


def nice_below(value):
    """The largest of 1, 2, 5 × 10^k (k any integer) not above `value` > 0."""
    decade = 10.0 ** math.floor(math.log10(value))
    return max(m * decade for m in (1.0, 2.0, 5.0, 10.0) if m * decade <= value * (1 + 1e-12))


def nice_factor(wanted):
    """A round magnification not above `wanted`, at least 1."""
    return nice_below(wanted) if math.isfinite(wanted) and wanted > 1.0 else 1.0


def largest_displacement(run):
    """Largest 3-D displacement of the run (m), at peak or after the cycle."""
    return max(float(run.attribute(a)) for _, a, _, _ in STAGES)


def common_factor(runs):
    """One magnification for all runs: the largest vector of any draws as TARGET_MM."""
    largest = max((largest_displacement(r) for r in runs), default=0.0)
    return nice_factor(TARGET_MM / (largest * MM)) if largest > 0 else 1.0


def draw_vectors(ax, run, stage, factor):
    position, _, contact_stage, _ = stage
    elevation(ax, run, settlement_at(run, contact_stage))
    start = run.data("particles/position_start")[:, [0, 2]] * MM
    d = run.displacement(position)[:, [0, 2]] * MM
    ax.plot(start[:, 0], start[:, 1], ls="", marker=".", ms=1.5, color="0.6", zorder=2)
    ax.quiver(start[:, 0], start[:, 1], d[:, 0] * factor, d[:, 1] * factor, angles="xy",
              scale_units="xy", scale=1.0, width=0.0025, headwidth=3.5, headlength=4,
              color="black", zorder=4)
    # A key: the round displacement that draws at most TARGET_MM at this factor.
    key = nice_below(TARGET_MM / factor)
    x, z = ax.get_xlim()[1] * 0.97, ax.get_ylim()[1] * 0.93
    ax.annotate("", xy=(x, z), xytext=(x - key * factor, z),
                arrowprops=dict(arrowstyle="->", color="black", lw=1.0))
    ax.text(x - 0.5 * key * factor, z * 0.975, f"{key:g} mm", ha="center", va="top",
            fontsize=7)


def displacement_figure(run, out_dir, number, factor, note):
    fig, axes = panels(len(STAGES), f"Displacement vectors, {run.label} (cf. Fig. {number}), "
                       f"front elevation\nx–z components drawn ×{factor:g} {note}")
    paper = paper_values(run).get("displacement_mm")
    for k, (ax, stage) in enumerate(zip(axes, STAGES)):
        draw_vectors(ax, run, stage, factor)
        label = stage[3] + (f" ({peak_load_kn(run):g} kN)" if stage[0] == "peak" else "")
        largest = float(run.attribute(stage[1])) * MM
        ax.set_title(f"({LETTERS[k]}) {label}: max displacement {largest:.3g} mm"
                     + paper_note(paper and (paper[k],), "max {} mm"), fontsize=8)
    return save(fig, out_dir, f"fig{number}_displacements_{run.id}")


def displacements(runs, out_dir, note):
    """Figs 15-17 for every loaded run; returns the paths written. Fig. 17 only for a
    clump run whose own factor (its largest vector drawn as TARGET_MM) exceeds the
    common one, i.e. where another run's larger displacements set Fig. 16's scale."""
    factor = common_factor(runs)
    written = []
    for run in runs:
        number = 16 if run.is_clumps else 15
        written.append(displacement_figure(run, out_dir, number, factor,
                                           "(the same for every run in Figs 15–16)"))
        if not run.is_clumps:
            continue
        own = common_factor([run])
        if own <= factor:
            note(f"Fig. 17 of run '{run.id}' left out: its displacements set the common "
                 f"scale of Fig. 16 (×{factor:g}) themselves")
            continue
        written.append(displacement_figure(
            run, out_dir, 17, own, f"= Fig. 16 magnified ×{own / factor:g} (the paper: ×80)"))
    return written
