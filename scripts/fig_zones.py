"""The top layer beneath and beside the sleeper: which way it moves, per sample, beside
the directions Lu & McDowell (2007) describe (Figs 15-17, section 3.3).

Archives from which the box test stores zones/ (docs/ARCHIVE.md) give, for each run,
the mean vertical displacement (up positive) of the top layer's particles whose centre
lies under the sleeper's footprint (beneath) and of the others (beside), at peak load
and after the cycle, from the start of loading. One panel per sample (replicates
grouped by scripts/replicates.py): a bar per zone and instant at the mean of the
replicates (mm), its 95 % interval as an error bar when the sample has two runs or
more, each run as a dot. A red filled triangle over a peak bar is the paper's
direction at peak; an open one over an after-the-cycle bar is the paper's direction
of the change on unloading (the paper: spheres beside the sleeper go up at peak and
keep rising; Sample 1's clumps beneath it go down at peak and come back up by less).

  fig_zones.png   every sample whose runs hold zones/
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from ballast_archive import ZONES  # noqa: E402
from fig_common import LETTERS, MM, save  # noqa: E402
from paper_values import DIRECTIONS, paper_sample, scale_shortfalls  # noqa: E402
from replicates import group_runs, summarize  # noqa: E402

WHEN = (("dz_peak", "at peak", "0.35"), ("dz_end", "after the cycle", "0.75"))
PAPER_COLOUR = "tab:red"


def zone_values(run, zone, attribute):
    """A run's zone displacement in mm, or None where the run lacks it (or the zone is
    empty)."""
    value = (run.zone(zone) or {}).get(attribute)
    return None if value is None else float(value) * MM


def draw_sample(ax, group, letter):
    """One sample's bars, intervals, replicate dots and the paper's directions."""
    directions = DIRECTIONS.get(paper_sample(group.runs[0]), {})
    ticks, labels = [], []
    for z, zone in enumerate(ZONES):
        paper = directions.get(zone)
        for w, (attribute, words, colour) in enumerate(WHEN):
            x = 2.6 * z + w
            values = [zone_values(r, zone, attribute) for r in group.runs]
            s = summarize(values)
            ticks.append(x)
            labels.append(f"{zone}\n{words}")
            if s.mean is None:
                continue
            ax.bar(x, s.mean, width=0.8, color=colour, edgecolor="black", lw=0.6, zorder=2)
            if s.low is not None:
                ax.errorbar(x, s.mean, yerr=[[s.mean - s.low], [s.high - s.mean]], fmt="none",
                            ecolor="black", capsize=4, lw=1.0, zorder=3)
            dots = [v for v in values if v is not None]
            offsets = [0.0] if len(dots) == 1 else [0.5 * k / (len(dots) - 1) - 0.25
                                                     for k in range(len(dots))]
            ax.plot([x + o for o in offsets], dots, ls="", marker="o", ms=3.5, mfc="white",
                    mec="black", zorder=4)
            if paper is not None:
                sign = paper[w]  # peak: the displacement's sign; after: the change's
                ax.plot(x, 0.93, marker="^" if sign > 0 else "v", ms=9, ls="",
                        transform=ax.get_xaxis_transform(), mec=PAPER_COLOUR,
                        mfc=PAPER_COLOUR if w == 0 else "white", mew=1.5, zorder=5)
    ax.axhline(0.0, color="black", lw=0.8, zorder=1)
    ax.set_xticks(ticks)
    ax.set_xticklabels(labels, fontsize=7)
    ax.set_ylabel("mean vertical displacement (mm, up +)", fontsize=8)
    ax.tick_params(axis="y", labelsize=7)
    ax.grid(True, axis="y", lw=0.3)
    ax.margins(y=0.25)
    run = group.runs[0]
    scale = (f"{int(run.attribute('bodies')):,} bodies, "
             f"{float(run.scene_value('sleeper', 'peak_load')) / 1e3:g} kN"
             + (", reduced scale" if scale_shortfalls(run) else ""))
    said = "; ".join(f"{z}: {p[2]}" for z, p in directions.items())
    ax.set_title(f"({letter}) {group.name}: n {len(group.runs)} ({scale})"
                 + (f"\npaper: {said}" if said else ""), fontsize=8)


def zone_figure(runs, out_dir, note):
    """fig_zones.png for the loaded runs that hold zones/; [] with a note when none does."""
    with_zones = [r for r in runs if r.has("zones")]
    if not with_zones:
        note("fig_zones left out: no run holds zones/ (an archive written before runs "
             "measured them)")
        return []
    for r in runs:
        if r not in with_zones:
            note(f"run '{r.id}' holds no zones/: left out of fig_zones")
    groups = group_runs(with_zones)
    cols = min(len(groups), 3)
    rows = -(-len(groups) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.8 * cols, 4.2 * rows), squeeze=False,
                             layout="constrained")
    axes = list(axes.flat)
    for ax in axes[len(groups):]:
        fig.delaxes(ax)
    for k, (ax, group) in enumerate(zip(axes, groups)):
        draw_sample(ax, group, LETTERS[k % 26])
    key = [Line2D([], [], ls="", marker="s", mfc=c, mec="black", label=f"mean {w}")
           for _, w, c in WHEN]
    key += [Line2D([], [], ls="", marker="o", mfc="white", mec="black", label="one run"),
            Line2D([], [], ls="", marker="^", mfc=PAPER_COLOUR, mec=PAPER_COLOUR,
                   label="paper: direction at peak"),
            Line2D([], [], ls="", marker="^", mfc="white", mec=PAPER_COLOUR,
                   label="paper: direction of the change on unloading")]
    axes[0].legend(handles=key, loc="best", fontsize=6, framealpha=0.9)
    fig.suptitle("Top layer beneath and beside the sleeper: mean vertical displacement from "
                 "the start of loading (cf. Figs 15–17)\nerror bars: 95 % interval of the "
                 "mean over the replicates (n ≥ 2)", fontsize=9)
    return [save(fig, out_dir, "fig_zones")]
