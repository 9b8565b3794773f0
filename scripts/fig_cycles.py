"""Settlement against the number of load cycles N, per sample, replicates as a band.

Runs of two load cycles or more store cycles/ (docs/ARCHIVE.md): the sleeper's
settlement at every cycle's peak and end. Panel (a): the permanent settlement after
cycle N (at the preload, from the start of loading) against N on a log axis; a line
per sample at the mean of its replicates, the band its 95 % interval (Student's t over
the replicates, cycle by cycle), the dashed line the least-squares fit a + b·log10 N
through the mean, b in the legend. Panel (b): the resilient settlement of each cycle
(settlement at peak less that at the cycle's end), the same way. Replicates are grouped
by scripts/replicates.py; a sample of one run is a line without a band.

  fig_cycles.png   every sample whose runs hold two cycles or more
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from fig_common import MM, save  # noqa: E402
from log_fit import log_fit  # noqa: E402
from replicates import group_runs, t975  # noqa: E402


def cycle_count(run):
    count = run.optional("count", "cycles")
    return 0 if count is None else int(count)


def replicate_band(rows):
    """Mean and 95 % half-width, cycle by cycle, of equal-length rows (one per run);
    half-width None for a single run."""
    values = np.asarray(rows, dtype=float)
    mean = values.mean(axis=0)
    if len(values) < 2:
        return mean, None
    sd = values.std(axis=0, ddof=1)
    return mean, t975(len(values) - 1) * sd / np.sqrt(len(values))


def draw(ax, group, colour, values, fit):
    # Replicates of unequal length (a run given more cycles) are cut to the shortest.
    n = min(len(v) for v in values)
    cycles = np.arange(1, n + 1)
    mean, half = replicate_band([v[:n] for v in values])
    label = f"{group.name} (n = {len(values)})"
    if fit and n >= 2:
        a, b = log_fit(cycles, mean)
        ax.plot(cycles, a + b * np.log10(cycles), ls="--", lw=0.9, color=colour)
        label += f": {b:.3g} mm per decade"
    ax.plot(cycles, mean, lw=1.4, color=colour, label=label)
    if half is not None:
        ax.fill_between(cycles, mean - half, mean + half, color=colour, alpha=0.25, lw=0)


def cycles_figure(runs, out_dir):
    """fig_cycles.png, or nothing when no run holds two cycles or more."""
    groups = group_runs([r for r in runs if cycle_count(r) >= 2])
    if not groups:
        return []
    fig, (ax_perm, ax_res) = plt.subplots(1, 2, figsize=(11.2, 4.6), layout="constrained")
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, g in enumerate(groups):
        colour = colours[k % len(colours)]
        trough = [r.data("cycles/settlement_trough") * MM for r in g.runs]
        peak = [r.data("cycles/settlement_peak") * MM for r in g.runs]
        draw(ax_perm, g, colour, trough, fit=True)
        draw(ax_res, g, colour, [p - t for p, t in zip(peak, trough)], fit=False)
    for ax, what in ((ax_perm, "(a) permanent settlement after cycle N (mm)"),
                     (ax_res, "(b) resilient settlement of cycle N (mm)")):
        ax.set_xscale("log")
        ax.set_xlabel("load cycle N")
        ax.set_ylabel(what[4:])
        ax.set_title(what, fontsize=9)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=7)
    scale = runs[0].scene_value("sleeper", "peak_load") / 1e3
    fig.suptitle(f"Sleeper settlement over the load cycles ({scale:g} kN peak): mean over "
                 "replicates, band = 95 % interval, dashed = fit on log10 N", fontsize=10)
    return [save(fig, out_dir, "fig_cycles")]
