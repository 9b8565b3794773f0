#!/usr/bin/python3
"""Speed against accuracy on the box test: each variant's cost and its error against
the reference, beside the reference's seed-to-seed scatter.

    /usr/bin/python3 scripts/tradeoff_table.py ARCHIVE.h5 [MORE.h5 ...]
        [--reference reference] [--out docs/tradeoffs] [--mark fast=preset-fast]

The archives are studies whose samples are a reference and variants of it, run on
common seeds (`"common_seeds": true`) from one study seed, so that replicate k of
every variant starts from the reference's replicate k, whichever archive holds it
(cases/tradeoff_study.json and cases/tradeoff_extended.json). A sample name may appear
in one archive only. For each variant and each
quantity q of QUANTITIES:

    delta   = mean over the replicates k both have of (q_variant,k - q_reference,k)
    scatter = the sample standard deviation of q over the reference's replicates
    error   = |delta| / scatter

An error below 1 is below what one more seed would change: noise, not a cost of the
variant. With `--scatter pooled` the scatter is every sample's sd pooled instead
(pooled_scatter), a steadier estimate than three seeds of the reference give. `worst` is the largest error over the quantities; a variant is "within the
scatter" when worst <= 1. `noise` is the standard error of delta / scatter, the sample
standard deviation of the paired differences over sqrt(n), the median over the
quantities: how finely n seeds resolve a shift. A variant that changes only the loading
shares the reference's prepared beds and its differences are small and smooth; one that
changes the preparation draws new beds, and its differences are as large as a change of
seed (noise near sqrt(2/n)). Cost is the mean over the variant's replicates of wall
seconds, timesteps and ball-steps (balls x timesteps, summed over the stages), and its
ratio to the reference's; ball-steps are exact, wall seconds depend on the machine's
load. Writes tradeoff.csv (every number), tradeoff.md (the tables docs/TRADEOFFS.md
quotes) and pareto.png (ball-steps against worst error, one point per variant, the --mark
variants starred) into --out, and prints the Markdown.
"""
import argparse
import csv
import math
import os
import sys

from ballast_archive import ArchiveError, open_archive
from compare import quantities
from replicates import summarize

# (key of compare.quantities, label, format)
QUANTITIES = (
    ("settlement_peak_mm", "settlement at peak (mm)", "{:.3g}"),
    ("permanent_settlement_mm", "permanent settlement (mm)", "{:.3g}"),
    ("resilient_settlement_mm", "resilient settlement (mm)", "{:.3g}"),
    ("rotation_loading_mean_deg", "mean rotation, loading (°)", "{:.3g}"),
    ("rotation_loading_max_deg", "max rotation, loading (°)", "{:.3g}"),
    ("max_displacement_peak_mm", "max displacement at peak (mm)", "{:.3g}"),
    ("porosity_grid", "porosity, 5 mm grid", "{:.4f}"),
    ("contacts_peak_mean_force_N", "mean contact force at peak (N)", "{:.4g}"),
)
SHORT = ("settl. peak", "permanent", "resilient", "rot. mean", "rot. max", "max displ.",
         "porosity", "mean force")


def run_cost(run):
    """(wall seconds, timesteps, ball-steps) of one run, over all its stages."""
    stages = run.group["stages"]
    steps = sum(int(stages[s].attrs["steps"]) for s in stages)
    return float(run.attribute("wall_seconds")), steps, steps * int(run.attribute("balls"))


def values(run):
    got = {key: value for key, _, value, _, _ in quantities(run)}
    return {key: got.get(key) for key, _, _ in QUANTITIES}


class Variant:
    def __init__(self, name, runs):
        self.name = name
        self.by_replicate = {int(r.attribute("replicate")): values(r) for r in runs}
        costs = [run_cost(r) for r in runs]
        self.wall, self.steps, self.ball_steps = (math.fsum(c[i] for c in costs) / len(costs)
                                                  for i in range(3))
        self.balls = sum(int(r.attribute("balls")) for r in runs) / len(runs)
        self.runs = len(runs)


def pooled_scatter(variants):
    """{key: (pooled sd, degrees of freedom)}: the sample standard deviations of every
    variant pooled, sqrt(sum((n_i - 1) s_i^2) / sum(n_i - 1)). A check on the
    reference's own sd, which three seeds estimate only to within a factor of about 3
    either way; assumes the variants scatter alike."""
    out = {}
    for key, _, _ in QUANTITIES:
        total, df = 0.0, 0
        for v in variants:
            s = summarize([r[key] for r in v.by_replicate.values()])
            if s.sd is not None:
                total += s.df * s.sd ** 2
                df += s.df
        out[key] = (math.sqrt(total / df) if df else None, df)
    return out


def compare(variant, reference, scatters=None):
    """{key: (variant mean, delta, scatter, error, noise)}; None entries where undefined.
    The scatter is the reference's sd, or scatters[key] when given."""
    out = {}
    common = sorted(set(variant.by_replicate) & set(reference.by_replicate))
    for key, _, _ in QUANTITIES:
        mean = summarize([v[key] for v in variant.by_replicate.values()]).mean
        diffs = [variant.by_replicate[k][key] - reference.by_replicate[k][key] for k in common
                 if variant.by_replicate[k][key] is not None
                 and reference.by_replicate[k][key] is not None]
        delta = math.fsum(diffs) / len(diffs) if diffs else None
        scatter = (scatters[key] if scatters is not None
                   else summarize([v[key] for v in reference.by_replicate.values()]).sd)
        error = (abs(delta) / scatter if delta is not None and scatter else None)
        spread = summarize(diffs).sd
        noise = (spread / math.sqrt(len(diffs)) / scatter
                 if spread is not None and scatter else None)
        out[key] = (mean, delta, scatter, error, noise)
    return out


def worst(errors):
    known = [e[3] for e in errors.values() if e[3] is not None]
    return max(known) if known else None


def load(paths, reference_name):
    variants, where = [], {}
    for path in paths:
        with open_archive(path) as archive:
            if archive.kind != "study":
                raise ArchiveError(f"{path}: a single-run archive; the trade-off needs a study")
            groups = {}
            for run in archive.select():
                groups.setdefault(run.sample or run.id, []).append(run)
            for name, runs in groups.items():
                if name in where:
                    raise ArchiveError(f"{path}: sample '{name}' is also in {where[name]}")
                where[name] = path
                variants.append(Variant(name, runs))
    ref = [v for v in variants if v.name == reference_name]
    if not ref:
        raise ArchiveError(f"{', '.join(paths)}: no sample named '{reference_name}' (samples: "
                           + ", ".join(v.name for v in variants) + ")")
    if ref[0].runs < 2:
        raise ArchiveError(f"{where[reference_name]}: the reference has {ref[0].runs} run: "
                           "its scatter needs 2")
    return ref[0], variants


def median_noise(errors):
    known = sorted(e[4] for e in errors.values() if e[4] is not None)
    return known[len(known) // 2] if known else None


def fmt_error(e):
    return "–" if e is None else f"{e:.2f}"


def other_scatter(name):
    """The scatter a table is not measured in: "pooled" for "reference" and back."""
    return "pooled" if name == "reference" else "reference"


def markdown(reference, variants, table, pooled, scatter_name, other):
    """`other` is the table in the other scatter, whose worst error gets a column."""
    other_name = other_scatter(scatter_name)
    lines = ["| variant | runs | ball-steps (× ref) | wall (× ref) | "
             + " | ".join(SHORT) + f" | worst | noise | within scatter | worst, {other_name} |",
             "|---" * (len(SHORT) + 8) + "|"]
    for v in variants:
        errors = table[v.name]
        w = worst(errors)
        lines.append(
            f"| {v.name} | {v.runs} | {v.ball_steps / reference.ball_steps:.2f} | "
            f"{v.wall / reference.wall:.2f} | "
            + " | ".join(fmt_error(errors[k][3]) for k, _, _ in QUANTITIES)
            + f" | {fmt_error(w)} | {fmt_error(median_noise(errors))} |"
            f" {'–' if w is None else 'yes' if w <= 1 else 'no'} |"
            f" {fmt_error(worst(other[v.name]))} |")
    lines += ["", f"Errors in units of the {scatter_name} scatter; the last column's in the "
              f"{other_name} scatter.", "",
              "| quantity | reference mean | reference's scatter (sd over seeds) |"
              " every sample's scatter, pooled (degrees of freedom) |", "|---|---|---|---|"]
    for key, label, f in QUANTITIES:
        s = summarize([v[key] for v in reference.by_replicate.values()])
        sd, df = pooled[key]
        lines.append(f"| {label} | {f.format(s.mean)} | {f.format(s.sd)} |"
                     f" {'–' if sd is None else f.format(sd)} ({df}) |")
    lines += ["", f"Reference: {reference.runs} runs, {reference.balls:,.0f} balls, "
              f"{reference.steps:,.0f} timesteps, {reference.ball_steps:.3g} ball-steps, "
              f"{reference.wall:.0f} s of one core on average."]
    return "\n".join(lines)


def write_csv(path, reference, variants, table):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["variant", "runs", "balls", "steps", "ball_steps", "wall_s",
                    "ball_steps_vs_ref", "wall_vs_ref", "worst_error", "noise"]
                   + [f"{k}_{x}" for k, _, _ in QUANTITIES
                      for x in ("mean", "delta", "scatter", "error", "noise")])
        for v in variants:
            errors = table[v.name]
            w.writerow([v.name, v.runs, f"{v.balls:.0f}", f"{v.steps:.0f}",
                        f"{v.ball_steps:.6g}", f"{v.wall:.4g}",
                        f"{v.ball_steps / reference.ball_steps:.4g}",
                        f"{v.wall / reference.wall:.4g}",
                        "" if worst(errors) is None else f"{worst(errors):.4g}",
                        "" if median_noise(errors) is None else f"{median_noise(errors):.4g}"]
                       + ["" if x is None else f"{x:.6g}"
                          for k, _, _ in QUANTITIES for x in errors[k]])


def place_labels(ax, points, obstacles=(), fontsize=7):
    """Each label beside its point, moved down a line at a time until it clears the
    markers (the points' and the `obstacles`, data coordinates) and the labels already
    placed (display pixels, y up; a label's width estimated from its length), so that
    variants of nearly the same cost and error stay readable."""
    px = ax.figure.dpi / 72.0  # pixels per point
    line, char, half = 1.2 * fontsize * px, 0.6 * fontsize * px, 4 * px

    def clear(box, others):
        x0, x1, y0, y1 = box
        return all(x1 <= a0 or a1 <= x0 or y1 <= b0 or b1 <= y0 for a0, a1, b0, b1 in others)

    markers = [xy for xy, _ in points] + list(obstacles)
    taken = [(mx - half, mx + half, my - half, my + half)
             for mx, my in (ax.transData.transform(xy) for xy in markers)]
    for (x, y), text in sorted(points, key=lambda p: (p[0][0], -p[0][1])):
        x0, y0 = ax.transData.transform((x, y))
        dy = 3.0 * px
        box = lambda: (x0 + 4 * px, x0 + 4 * px + len(text) * char, y0 + dy, y0 + dy + line)
        while not clear(box(), taken):
            dy -= line
        taken.append(box())
        ax.annotate(text, (x, y), textcoords="offset points", xytext=(4, dy / px),
                    fontsize=fontsize)


def pareto_plot(path, reference, variants, table, marks, other=None, names=("", "")):
    """Cost against worst error, one point per variant. With `other`, the errors in the
    other scatter, a hollow marker joined to each point gives the variant's worst error
    measured in that one: three seeds of the reference can under- or overstate the
    scatter. `names`: the two scatters' names, the table's first."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    fig, ax = plt.subplots(figsize=(7.5, 5))
    # Variants that give the same bits (a preset that only sets a knob's value) share
    # a point and one label, "a = b", instead of two labels printed over each other.
    points, hollow = {}, []
    for v in variants:
        if v is reference:
            continue
        w = worst(table[v.name])
        if w is None:
            continue
        x, star = v.ball_steps / reference.ball_steps, v.name in marks.values()
        y, color = max(w, 1e-2), "tab:red" if star else "tab:blue"
        ax.scatter([x], [y], marker="*" if star else "o", s=160 if star else 30,
                   color=color, zorder=3)
        w_other = worst(other[v.name]) if other is not None else None
        if w_other is not None:
            ax.plot([x, x], [y, max(w_other, 1e-2)], color=color, lw=0.8, alpha=0.5)
            ax.scatter([x], [max(w_other, 1e-2)], s=30, facecolors="none", edgecolors=color,
                       zorder=3)
            hollow.append((x, max(w_other, 1e-2)))
        label = next((p for p, n in marks.items() if n == v.name), v.name)
        points.setdefault((x, y), []).append(label)
    ax.axhline(1.0, color="grey", ls="--", lw=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    left, right = ax.get_xlim()
    ax.set_xlim(left, right * 1.25)  # room for the rightmost point's label
    ax.text(left, 1.03, " the seed-to-seed scatter", fontsize=7, color="grey",
            va="bottom")
    if other is not None:
        ax.legend(handles=[Line2D([], [], ls="", marker="o", color="tab:blue",
                                  label=f"in the {names[0]} scatter"),
                           Line2D([], [], ls="", marker="o", markerfacecolor="none",
                                  color="tab:blue", label=f"in the {names[1]} scatter")],
                  fontsize=7, loc="lower right")
    ax.set_xlabel("cost: ball-steps per run, relative to the reference "
                  "(exact; wall time in the table)")
    ax.set_ylabel("worst error over the quantities, |Δ| / scatter")
    ax.set_title(f"Speed against accuracy, {reference.balls:,.0f}-ball box test, "
                 f"{reference.runs} common seeds", fontsize=10)
    fig.tight_layout()
    place_labels(ax, [(xy, " = ".join(labels)) for xy, labels in points.items()], hollow)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("archives", nargs="+", metavar="ARCHIVE")
    p.add_argument("--reference", default="reference", help="the reference sample's name")
    p.add_argument("--out", help="folder for tradeoff.csv, tradeoff.md and pareto.png")
    p.add_argument("--scatter", choices=("reference", "pooled"), default="reference",
                   help="the scatter errors are measured in: the reference's sd over its "
                        "seeds (default), or every sample's sd pooled")
    p.add_argument("--mark", default="",
                   help="label=sample pairs, comma-separated: variants to star in the plot")
    a = p.parse_args(argv)
    try:
        marks = dict(m.split("=", 1) for m in a.mark.split(",") if m)
    except ValueError:
        p.error(f"--mark {a.mark!r}: allowed: label=sample pairs separated by commas")
    try:
        reference, variants = load(a.archives, a.reference)
    except ArchiveError as e:
        print(f"tradeoff_table: {e}", file=sys.stderr)
        return 2
    pooled = pooled_scatter(variants)
    pooled_sd = {k: sd for k, (sd, _) in pooled.items()}
    by_reference = {v.name: compare(v, reference) for v in variants}
    by_pooled = {v.name: compare(v, reference, pooled_sd) for v in variants}
    table, other = ((by_pooled, by_reference) if a.scatter == "pooled"
                    else (by_reference, by_pooled))
    text = markdown(reference, variants, table, pooled, a.scatter, other)
    print(text)
    if a.out:
        os.makedirs(a.out, exist_ok=True)
        with open(os.path.join(a.out, "tradeoff.md"), "w") as f:
            f.write(text + "\n")
        write_csv(os.path.join(a.out, "tradeoff.csv"), reference, variants, table)
        spoken = {"reference": "reference's", "pooled": "pooled"}
        pareto_plot(os.path.join(a.out, "pareto.png"), reference, variants, table, marks,
                    other, (spoken[a.scatter], spoken[other_scatter(a.scatter)]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
