#!/usr/bin/python3
"""The runs of a ballast archive side by side, beside Lu & McDowell (2007)'s numbers.

    /usr/bin/python3 scripts/compare.py ARCHIVE.h5 [--runs ID1,ID2] [--json]

First the scale each sample ran at (bodies, balls, peak load); the paper's numbers are
for its full-scale box (1,936 spheres or 1,770 clumps in a 700 mm box, 40 kN), so a
sample run at another scale is said to be NOT comparable and its cells carry no paper
numbers (paper_values.scale_shortfalls). Then one column per run (status ok), one row
per measured quantity; a cell reads "ours (paper)" where the paper gives a number for
the run's sample: the spheres, Table 2 Sample 1 or Sample 2 (Sample 2 has only its
porosity; a run that changes a preset's clump parameters is not the paper's sample and
gets none). Contact counts are ball–ball plus ball–wall, each once; the paper counts
differently (10.7 per sphere, 16 per Sample 1 ball, by a convention it does not give):
"contacts counted both ways" lays out the arithmetic of the conventions that could
reach its counts, where the archive holds the near-contact counts. Then, per loaded
run, the three particles that turned most during loading and the three that turned most
over the cycle, where they sat and what they did after (scripts/largest_rotations.py).

Then the sample-level tables of scripts/compare_samples.py: replicates' means with 95 %
intervals (when a sample has two runs or more), the spheres / clumps ratios, and the
directions in which the top layer moves (archives with zones/). Runs of several load
cycles add the settlement after the first cycle and its growth per decade of cycles
(least squares on log10 N; the permanent settlement row is after the last cycle), and
per whole decade of cycles reached (1–10, 10–100, ...) the settlement at its end, the
decade's own slope and its mean rebound.
Fields that newer archives add (force percentiles, the sleeper's contacts, zones, near contacts) are
rows where present and left out where not. `--json` prints the same numbers,
unrounded, for scripts (keys: docs/FIGURES.md).
"""
import argparse
import json
import math
import sys

from ballast_archive import (ZONES, ArchiveError, add_run_arguments, chosen_runs,
                             open_archive)
from compare_samples import sample_stats, samples_json, samples_markdown, span
from largest_rotations import (largest_rotations, largest_rotations_markdown, turning_back,
                               turning_back_markdown)
from log_fit import log_fit
from paper_values import (FULL_SCALE_SCENES, PHASES, STAGES, comparable, paper_sample,
                          paper_text, paper_values, scale_shortfalls)
from replicates import group_runs, ordered_union

MM = 1e3
STAGE_LABELS = {"before": "before loading", "peak": "at peak load", "after": "after unloading"}

# Attributes of contacts/<stage> that newer archives add: (attribute, key suffix, label,
# format). Forces in N.
CONTACT_EXTRAS = (
    ("force_p50", "force_p50_N", "ball–ball force, median (N)", "{:,.1f}"),
    ("force_p90", "force_p90_N", "ball–ball force, 90th percentile (N)", "{:,.1f}"),
    ("force_p99", "force_p99_N", "ball–ball force, 99th percentile (N)", "{:,.1f}"),
    ("sleeper_contacts", "sleeper_contacts", "ball–sleeper contacts", "{:,.0f}"),
    ("sleeper_bodies", "sleeper_bodies", "bodies touching the sleeper", "{:,.0f}"),
    ("sleeper_force_max", "sleeper_force_max_N", "ball–sleeper force, max (N)", "{:,.0f}"),
    ("sleeper_force_p50", "sleeper_force_p50_N", "ball–sleeper force, median (N)", "{:,.1f}"),
    ("sleeper_force_p90", "sleeper_force_p90_N", "ball–sleeper force, 90th percentile (N)",
     "{:,.1f}"),
    ("sleeper_force_total", "sleeper_force_total_N", "ball–sleeper force, total (N)",
     "{:,.0f}"),
)

# Attributes of zones/<zone>: (attribute, key suffix, label, factor to the printed unit,
# format). Displacements up positive.
ZONE_FIELDS = (
    ("count", "count", "particles", 1.0, "{:,.0f}"),
    ("dz_peak", "dz_peak_mm", "mean vertical displacement at peak (mm, up +)", MM, "{:.3g}"),
    ("dz_end", "dz_end_mm", "mean vertical displacement after the cycle (mm)", MM, "{:.3g}"),
) + tuple((f"rotation_{p}_deg", f"rotation_{p}_deg", f"mean rotation, {p} (°)", 1.0, "{:.3g}")
          for p in PHASES)


def contact_rows(run, stage, p):
    """The rows of contacts/<stage>: count, max and mean force, and what newer archives
    add there."""
    path = f"contacts/{stage}"
    c = lambda name: run.attribute(name, path)  # noqa: E731
    pc = p["contacts"][STAGES.index(stage)] if "contacts" in p else (None, None, None)
    label, key = f"contacts {STAGE_LABELS[stage]}", f"contacts_{stage}"
    rows = [(f"{key}_count", f"{label}: count (ball–ball + ball–wall)",
             int(c("ball_contacts")) + int(c("wall_contacts")), pc[0], "{:,.0f}"),
            (f"{key}_max_force_N", f"{label}: max force (N)", float(c("max_force")), pc[1],
             "{:,.0f}"),
            (f"{key}_mean_force_N", f"{label}: mean force (N)", float(c("mean_force")), pc[2],
             "{:.1f}")]
    for name, suffix, text, fmt in CONTACT_EXTRAS:
        value = run.optional(name, path)
        if value is not None and math.isfinite(value):  # NaN: a percentile of nothing
            rows.append((f"{key}_{suffix}", f"{label}: {text}", float(value), None, fmt))
    return rows


def zone_rows(run):
    """The rows of zones/beneath and zones/beside (newer archives; none otherwise), with
    the change on unloading, dz_end − dz_peak, of each; an empty zone has its count only."""
    rows = []
    for zone in ZONES:
        got = run.zone(zone) or {}
        for name, suffix, text, factor, fmt in ZONE_FIELDS:
            if got.get(name) is not None:
                rows.append((f"zone_{zone}_{suffix}", f"zone {zone} the sleeper: {text}",
                             float(got[name]) * factor, None, fmt))
        if "dz_peak" in got and "dz_end" in got:
            rows.append((f"zone_{zone}_dz_unloading_mm", f"zone {zone} the sleeper: change "
                         "on unloading, after − peak (mm)",
                         (float(got["dz_end"]) - float(got["dz_peak"])) * MM, None, "{:.3g}"))
    return rows


def interior_share(run):
    """The share of the grid's column (under the sleeper, the box's width, base to bed
    top) that its interior grid keeps: one nominal diameter in from the side walls, the
    base and the top (cases/box_test_load.cpp). None where the interior is empty."""
    width = float(run.scene_value("box", "width"))
    d = float(run.scene_value("particles", "diameter"))
    height = float(run.attribute("bed_height"))
    share = (width - 2.0 * d) * (height - 2.0 * d) / (width * height)
    return share if width > 2.0 * d and height > 2.0 * d else None


def wall_layer_porosity(run, whole, interior):
    """The porosity of what the interior grid leaves out (the layers a flat boundary
    loosens): the whole column's void less the interior's, over the volume between.
    Each grid spans its region exactly (engine/porosity.cpp), so the volumes are exact;
    the grids' own sampling error grows by 1 / (1 − share), about 2.6 in the box test."""
    share = interior_share(run)
    if share is None or not math.isfinite(interior):
        return None
    return (whole - share * interior) / (1.0 - share)


def quantities(run, paper=None):
    """(key, label, ours, paper, format) for every quantity the run has. `paper` is the
    paper's numbers to set beside them (default: those of the run's own sample)."""
    a, p = run.attribute, paper_values(run) if paper is None else paper
    rows = [("porosity_grid", "porosity, 5 mm grid under the sleeper", a("porosity_grid"),
             p.get("porosity"), "{:.3f}")]
    interior = run.optional("porosity_grid_interior")
    if interior is not None and math.isfinite(interior):
        rows.append(("porosity_grid_interior", "porosity, the same grid one diameter inside "
                     "the walls, base and top", interior, p.get("porosity"), "{:.3f}"))
        walls = wall_layer_porosity(run, a("porosity_grid"), interior)
        if walls is not None:
            rows.append(("porosity_grid_walls", "porosity of the layers the interior leaves "
                         "out (walls, base, top)", walls, None, "{:.3f}"))
    if run.has("porosity/sphere_porosity") and len(run.data("porosity/sphere_porosity")):
        rows.append(("porosity_spheres", "porosity, measurement spheres on the column axis "
                     "(mean)", float(run.data("porosity/sphere_porosity").mean()),
                     p.get("porosity"), "{:.3f}"))
    for stage in STAGES:
        if run.has(f"contacts/{stage}"):
            rows += contact_rows(run, stage, p)
    if not run.loaded:
        return rows
    for k, phase in enumerate(PHASES):
        pr = p["rotation"][k] if "rotation" in p else (None, None)
        rows += [(f"rotation_{phase}_mean_deg", f"rotation, {phase}: mean (°)",
                  a(f"rotation_{phase}_mean_deg"), pr[0], "{:.3g}"),
                 (f"rotation_{phase}_max_deg", f"rotation, {phase}: max (°)",
                  a(f"rotation_{phase}_max_deg"), pr[1], "{:.3g}")]
    pd = p.get("displacement_mm", (None, None))
    rows += [("max_displacement_peak_mm", "max displacement at peak load (mm)",
              a("max_displacement_peak") * MM, pd[0], "{:.3g}"),
             ("max_displacement_after_mm", "max displacement after the cycle (mm)",
              a("max_displacement_after") * MM, pd[1], "{:.3g}"),
             ("settlement_peak_mm", "sleeper settlement at peak (mm)",
              a("settlement_peak") * MM, None, "{:.3g}"),
             ("permanent_settlement_mm", "permanent settlement (mm)",
              a("permanent_settlement") * MM, None, "{:.3g}"),
             ("resilient_settlement_mm", "resilient settlement (mm)",
              a("resilient_settlement") * MM, None, "{:.3g}"),
             ("rms_force_error_N", "sleeper force error, rms (N)", a("rms_force_error"), None,
              "{:,.0f}")]
    return rows + cycle_rows(run) + zone_rows(run)


def cycle_rows(run):
    """Runs of two load cycles or more (cycles/ in newer archives): how the permanent
    settlement grows with the number of cycles N. The paper loads once: no paper
    numbers."""
    count = run.optional("count", "cycles")
    if count is None or int(count) < 2:
        return []
    trough = [float(x) for x in run.data("cycles/settlement_trough")]
    rows = [("cycles", "load cycles", int(count), None, "{:,.0f}"),
            ("permanent_settlement_first_mm", "permanent settlement after the first cycle (mm)",
             trough[0] * MM, None, "{:.3g}"),
            ("settlement_log_slope_mm", "permanent settlement per decade of cycles (mm, least "
             "squares on log10 N)", float(run.attribute("settlement_log_slope", "cycles")) * MM,
             None, "{:.3g}")]
    return rows + decade_rows(trough, [float(x) for x in run.data("cycles/resilient_settlement")])


def decade_rows(trough, rebound):
    """Per whole decade of cycles [10^k, 10^(k+1)] the run reached: the permanent
    settlement at its end, its own least-squares slope on log10 N (one slope over all
    cycles hides a growth that is not linear in log N: the fit is dominated by the last
    decade's many cycles) and the mean rebound (resilient settlement) over its cycles.
    Cycle N is trough[N - 1]."""
    rows = []
    lo = 1
    while lo * 10 <= len(trough):
        hi = lo * 10
        ys = trough[lo - 1:hi]
        slope = float(log_fit(range(lo, hi + 1), ys)[1])
        span_text = f"cycles {lo:,}–{hi:,}"
        rows += [(f"permanent_settlement_after_{hi}_mm",
                  f"permanent settlement after {hi:,} cycles (mm)", ys[-1] * MM, None, "{:.3g}"),
                 (f"settlement_log_slope_{lo}_{hi}_mm",
                  f"permanent settlement per decade, {span_text} (mm, least squares on log10 N)",
                  slope * MM, None, "{:.3g}"),
                 (f"rebound_mean_{lo}_{hi}_mm", f"mean rebound, {span_text} (mm)",
                  sum(rebound[lo - 1:hi]) / (hi - lo + 1) * MM, None, "{:.3g}")]
        lo = hi
    return rows


def cell(value, paper, fmt):
    if value is None:
        return "—"
    return fmt.format(value) + ("" if paper is None else f" ({paper_text(paper)})")


def scale_text(runs):
    """'N bodies, B balls, peak load X kN' over some runs (ranges where they differ)."""
    return (f"{span([int(r.attribute('bodies')) for r in runs], '{:,}')} bodies, "
            f"{span([int(r.attribute('balls')) for r in runs], '{:,}')} balls, peak load "
            f"{span([float(r.scene_value('sleeper', 'peak_load')) / 1e3 for r in runs], '{:g}')}"
            " kN")


def scale_lines(groups):
    """The scale of each sample, and a warning for each one that is not the paper's."""
    lines = ["Scale of each sample:"]
    lines += [f"- {g.name} ({len(g.runs)} run{'s' * (len(g.runs) > 1)}): {scale_text(g.runs)}"
              for g in groups]
    reduced = {}  # the samples short of the paper's scale, by how they fall short
    for g in groups:
        why = "; ".join(ordered_union(scale_shortfalls(r) for r in g.runs))
        if why:
            reduced.setdefault(why, []).append(g.name)
    if reduced:
        lines.append("")
        lines += [f"**{', '.join(names)}: smoke/reduced-scale results ({why}), NOT comparable "
                  "with the paper's numbers**, which are left out of their cells."
                  for why, names in reduced.items()]
        lines.append(f"The paper's numbers need the full-scale scenes {FULL_SCALE_SCENES}.")
    return lines


def markdown(runs):
    """The side-by-side table as Markdown; the paper's numbers only in the cells of runs
    comparable with them (the paper's sample, at its scale)."""
    columns = [{key: (label, ours, paper if comparable(r) else None, fmt)
                for key, label, ours, paper, fmt in quantities(r)} for r in runs]
    head = ["quantity"] + [r.label for r in runs]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head),
             "| paper's sample | " + " | ".join(paper_sample(r) or "—" for r in runs) + " |",
             "| scale | " + " | ".join(scale_text([r]) for r in runs) + " |"]
    for key in ordered_union(columns):
        label = next(c[key][0] for c in columns if key in c)
        cells = [cell(*(c[key][1:]) if key in c else (None, None, "")) for c in columns]
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def counted_both_ways(run):
    """The near-contact counts of contacts/before as the paper's kind of count: for each
    gap tolerance, ball–ball pairs once, both ends (2×), + ball–wall pairs, + the overlaps
    inside clumps. [] for an archive without near_pairs. Just the arithmetic."""
    path = "contacts/before"
    if not run.has(f"{path}/near_pairs"):
        return []
    gaps, pairs = run.data(f"{path}/near_gap"), run.data(f"{path}/near_pairs")
    wall = run.data(f"{path}/near_wall") if run.has(f"{path}/near_wall") else None
    intra = run.optional("intra_clump_pairs", path)
    out = []
    for i, gap in enumerate(gaps):
        both = 2 * int(pairs[i])
        plus_wall = None if wall is None else both + int(wall[i])
        out.append({"gap_m": float(gap), "ball_pairs": int(pairs[i]), "both_ends": both,
                    "plus_wall": plus_wall,
                    "plus_intra_clump": None if plus_wall is None or intra is None
                    else plus_wall + int(intra)})
    return out


def counted_both_ways_markdown(runs):
    """The table of counted_both_ways for every run that has the counts ('' if none)."""
    lines = []
    for run in runs:
        paper = paper_values(run).get("contacts", [(None,)])[0][0] if comparable(run) else None
        for row in counted_both_ways(run):
            lines.append(f"| {run.label} | {row['gap_m'] * MM:g} | {row['ball_pairs']:,} | "
                         f"{row['both_ends']:,} | " + " | ".join(
                             "—" if row[k] is None else f"{row[k]:,}"
                             for k in ("plus_wall", "plus_intra_clump"))
                         + f" | {'—' if paper is None else paper_text(paper)} |")
    if not lines:
        return ""
    return "\n".join(["## Contacts counted both ways (before loading)", "",
                      "Ball pairs of different bodies within the gap, once; both ends "
                      "counted; plus ball–wall pairs within the gap; plus the overlapping "
                      "ball pairs inside clumps. The arithmetic only.", "",
                      "| run | gap (mm) | ball–ball pairs | both ends (2×) | + ball–wall "
                      "| + inside clumps | paper |", "|---|---|---|---|---|---|---|"] + lines)


def run_json(run, rows):
    entry = {"id": run.id, "label": run.label, "shape": run.shape,
             "paper_sample": paper_sample(run),
             "scale": {"bodies": int(run.attribute("bodies")),
                       "balls": int(run.attribute("balls")),
                       "peak_load_N": float(run.scene_value("sleeper", "peak_load")),
                       "box_length_m": float(run.scene_value("box", "length"))},
             "at_paper_scale": not scale_shortfalls(run),
             "not_at_paper_scale_because": scale_shortfalls(run),
             "quantities": {key: {"ours": ours, "paper": paper}
                            for key, _, ours, paper, _ in rows}}
    turned = largest_rotations(run)
    if turned:
        entry["largest_rotations"] = turned
        entry["largest_cycle_rotations"] = largest_rotations(run, by="cycle")
        entry["turning_back"] = turning_back(run)
    both = counted_both_ways(run)
    if both:
        paper = paper_values(run).get("contacts", [(None,)])[0][0]
        entry["contacts_counted_both_ways"] = {"rows": both, "paper": paper}
    return entry


def as_json(runs, rows, stats):
    return dict({"runs": [run_json(r, rows[r.id]) for r in runs]}, **samples_json(stats))


def report(path, runs, stats):
    """The whole Markdown printout."""
    parts = [f"Runs of {path} beside Lu & McDowell (2007): ours (paper). The paper's box: "
             "1,936 spheres or 1,770 clumps, 700 mm long, 40 kN.\n",
             "\n".join(scale_lines([s.group for s in stats])), "", markdown(runs)]
    for extra in (counted_both_ways_markdown(runs), largest_rotations_markdown(runs),
                  turning_back_markdown(runs), samples_markdown(stats)):
        if extra:
            parts += ["", extra]
    return "\n".join(parts)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_run_arguments(parser)
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    args = parser.parse_args(argv)
    try:
        with open_archive(args.archive) as archive:
            runs = chosen_runs(archive, args.runs, "compare")
            rows = {r.id: quantities(r) for r in runs}
            stats = sample_stats(group_runs(runs), rows)
            if args.json:
                print(json.dumps(as_json(runs, rows, stats), indent=1))
            else:
                print(report(args.archive, runs, stats))
    except ArchiveError as e:
        print(f"compare.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
