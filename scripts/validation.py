#!/usr/bin/python3
"""The full-scale paper study judged against Lu & McDowell (2007): the tables of
docs/VALIDATION.md, from the archive of `ballast study cases/paper_study.json`.

    /usr/bin/python3 scripts/validation.py paper.h5 [more.h5 ...] [--csv DIR]

Prints, in Markdown,
  1. the goals a researcher checks our tool against (the paper's headline findings
     and its box), each with what we measure over the replicates and whether it holds;
  2. the key quantities per sample: mean ± half-width of the 95 % interval over the
     replicates (scripts/replicates.py), the spread of the runs, the paper's number;
  3. how each run's seating ended (equilibrium, steady creep, step limit) and its
     wall time.
Several archives are read as one study: a study that adds replicates to another
(`"seeds": [4, ...]`, cases/paper_study_ten.json) gives its runs to the same samples;
a run id found twice is refused. `--csv DIR` also writes the key-quantity table as
DIR/paper_study.csv. Every number comes from the archives; the paper's from
scripts/paper_values.py. scripts/compare.py prints every quantity of every run, with
the same statistics.
"""
import argparse
import contextlib
import csv
import datetime
import os
import sys

from ballast_archive import ArchiveError, open_archive
from compare import interior_share, quantities
from paper_values import paper_sample
from replicates import group_runs, ratio_of_means, summarize

KM = 1e-3
# Key quantities: (compare.py key, label, format).
KEY_ROWS = (
    ("porosity_grid", "porosity, 5 mm grid under the sleeper", "{:.3f}"),
    ("porosity_grid_interior", "the same grid one diameter inside walls, base and top",
     "{:.3f}"),
    ("porosity_spheres", "porosity, measurement spheres on the column's axis", "{:.3f}"),
    ("contacts_before_sleeper_bodies", "particles bearing the sleeper, preload", "{:.1f}"),
    ("contacts_peak_sleeper_bodies", "particles bearing the sleeper, 40 kN", "{:.1f}"),
    ("contacts_peak_max_force_N", "largest contact force at 40 kN (N)", "{:,.0f}"),
    ("contacts_peak_force_p50_N", "median ball–ball force at 40 kN (N)", "{:,.0f}"),
    ("rotation_loading_mean_deg", "rotation, loading: mean (°)", "{:.3g}"),
    ("rotation_loading_max_deg", "rotation, loading: max (°)", "{:.3g}"),
    ("rotation_unloading_mean_deg", "rotation, unloading: mean (°)", "{:.3g}"),
    ("rotation_cycle_mean_deg", "rotation, cycle: mean (°)", "{:.3g}"),
    ("rotation_cycle_max_deg", "rotation, cycle: max (°)", "{:.3g}"),
    ("max_displacement_peak_mm", "max displacement at peak (mm)", "{:.3g}"),
    ("max_displacement_after_mm", "max displacement after the cycle (mm)", "{:.3g}"),
    ("settlement_peak_mm", "sleeper settlement at peak (mm)", "{:.3g}"),
    ("permanent_settlement_mm", "permanent settlement (mm)", "{:.3g}"),
    ("resilient_settlement_mm", "resilient settlement (mm)", "{:.3g}"),
    ("zone_beneath_dz_peak_mm", "top layer beneath: dz at peak (mm, up +)", "{:.3g}"),
    ("zone_beneath_dz_unloading_mm", "top layer beneath: dz on unloading (mm)", "{:.3g}"),
    ("zone_beside_dz_peak_mm", "top layer beside: dz at peak (mm)", "{:.3g}"),
    ("zone_beside_dz_unloading_mm", "top layer beside: dz on unloading (mm)", "{:.3g}"),
)
PAPER_POROSITY = {"spheres": 0.37, "sample1": 0.35, "sample2": 0.37}
PAPER_MAX_FORCE_N = 4233.0  # Sample 1 at 40 kN (Fig. 12); spheres 4,050 (Fig. 11)
# "The spheres and Sample 1 were loaded" (section 3): the paper reports no cycle of
# Sample 2, so its loaded goals are ours, with no figure of the paper behind them.
NOT_LOADED_IN_PAPER = {"sample2"}


def name_of(group):
    """The group's name in a goal, marked where the paper did not load the sample."""
    if paper_sample(group.runs[0]) in NOT_LOADED_IN_PAPER:
        return f"{group.name} (not loaded in the paper)"
    return group.name


def table_of(group):
    """{run id: {key: value}} of compare.quantities for the group's runs."""
    return {r.id: {k: v for k, _, v, _, _ in quantities(r)} for r in group.runs}


def stat(group, key):
    t = table_of(group)
    return summarize([t[r.id].get(key) for r in group.runs])


def interval(s, fmt):
    if s.mean is None:
        return "—"
    if s.low is None:
        return f"{fmt.format(s.mean)} (n {s.n})"
    return f"{fmt.format(s.mean)} [{fmt.format(s.low)}, {fmt.format(s.high)}]"


def seating(run):
    """(how the seating ended, its final unbalanced-force ratio)."""
    stages = run.group["stages"]
    name = next((k for k in stages if k.endswith("_preload")), None)
    if name is None:
        return ("not seated", None)
    a = stages[name].attrs
    ended = a["ended_by"]
    return (ended.decode() if isinstance(ended, bytes) else ended, float(a["unbalanced"]))


def every_replicate(flags, what, values):
    """(measured, holds) of a goal asked of every replicate: "k of n <what>: <values>",
    and "yes" only when every flag is."""
    return (f"{sum(bool(f) for f in flags)} of {len(flags)} {what}: {values}",
            "yes" if all(flags) else "no")


def goals(groups):
    """Rows (goal, measured, holds) of the issue's goals."""
    by = {paper_sample(g.runs[0]): g for g in groups}
    rows = []
    spheres, s1 = by.get("spheres"), by.get("sample1")
    clumps = [g for g in groups if g.is_clumps]
    if spheres and s1:
        r = ratio_of_means(stat(spheres, "rotation_loading_mean_deg"),
                           stat(s1, "rotation_loading_mean_deg"))
        text = (f"{r.value:.1f} [{r.low:.1f}, {r.high:.1f}]" if r.low is not None
                else f"{r.value:.1f} ({r.note})")
        rows.append(("spheres / Sample 1 mean rotation during loading ≥ 20 (paper 85)", text,
                     "yes" if r.value >= 20 else "no"))
    for g in clumps:
        t = table_of(g)
        res = [t[x.id]["resilient_settlement_mm"] for x in g.runs]
        rows.append((f"{name_of(g)}: rebounds in every replicate (resilient settlement > 0)",
                     *every_replicate([v > 0 for v in res], "rebound",
                                      ", ".join(f"{v:.3f}" for v in res) + " mm")))
        pairs = [(t[x.id]["rotation_cycle_max_deg"], t[x.id]["rotation_loading_max_deg"])
                 for x in g.runs]
        rows.append((f"{name_of(g)}: cycle's largest rotation below the loading's, every replicate",
                     *every_replicate([c < ld for c, ld in pairs], "below",
                                      ", ".join(f"{c:.2f} vs {ld:.2f}°" for c, ld in pairs))))
        s = stat(g, "zone_beneath_dz_peak_mm")
        rows.append((f"{name_of(g)}: top layer beneath the sleeper sinks at peak",
                     interval(s, "{:.3f}") + " mm",
                     "yes" if s.high is not None and s.high < 0 else
                     "not resolved" if s.mean is not None and s.mean < 0 else "no"))
    if spheres:
        s = stat(spheres, "zone_beside_dz_peak_mm")
        rows.append(("spheres: top layer beside the sleeper rises at peak",
                     interval(s, "{:.3f}") + " mm",
                     "yes" if s.low is not None and s.low > 0 else
                     "not resolved" if s.mean is not None and s.mean > 0 else "no"))
    for g in groups:
        t = table_of(g)
        bodies = [t[x.id].get("contacts_peak_sleeper_bodies") for x in g.runs]
        force = [t[x.id]["contacts_peak_max_force_N"] for x in g.runs]
        each = [b is not None and b >= 20 and PAPER_MAX_FORCE_N / 2 <= f <= 2 * PAPER_MAX_FORCE_N
                for b, f in zip(bodies, force)]
        rows.append((f"{name_of(g)}: sleeper on ≥ 20 particles at 40 kN, largest force within 2× "
                     "of 4.2 kN", *every_replicate(
                         each, "meet it",
                         ", ".join(f"{b:.0f} / {f * KM:.1f} kN" for b, f in zip(bodies, force)))))
        sample = paper_sample(g.runs[0])
        if sample in PAPER_POROSITY:
            s = stat(g, "porosity_grid")
            inner = stat(g, "porosity_grid_interior")
            p = PAPER_POROSITY[sample]
            within = abs(s.mean - p) <= 0.03
            measured = interval(s, "{:.3f}")
            if inner.mean is not None:
                # The paper does not say whether its column kept the layers the walls
                # loosen: the goal is judged on the whole column, the other shown beside.
                measured += f"; one diameter inside the walls {interval(inner, '{:.3f}')}"
            walls = stat(g, "porosity_grid_walls")
            if walls.mean is not None:
                # What the interior would need for the whole column to reach the
                # paper's porosity, with the wall layers as they are.
                t = table_of(g)
                split = [(interior_share(x), t[x.id].get("porosity_grid_walls")) for x in g.runs]
                need = summarize([(p - (1.0 - share) * w) / share for share, w in split
                                  if share is not None and w is not None])
                measured += (f"; the layers left out {interval(walls, '{:.3f}')}, with which "
                             f"{p} needs an interior of {interval(need, '{:.3f}')}")
            rows.append((f"{g.name}: porosity within ±0.03 of {p}", measured,
                         "yes" if within else "no"))
        ends = [seating(x) for x in g.runs]
        rows.append((f"{g.name}: at rest under the preload (seating ended by equilibrium)",
                     *every_replicate([e == "equilibrium" for e, _ in ends], "at rest",
                                      ", ".join(f"{e} ({u:.4f})" if u is not None else e
                                                for e, u in ends))))
    return rows


def study_hours(runs):
    """Wall time from the first run's start to the last one's end, h. A run resumed
    from its checkpoint records the start of its last part, and its own wall time
    (wall_seconds) includes the parts before: it started no later than its end less
    that time, which is what counts for it."""
    def when(run, name):
        return datetime.datetime.fromisoformat(str(run.attribute(name)).replace("Z", "+00:00"))

    def start_of(run):
        ran = datetime.timedelta(seconds=float(run.attribute("wall_seconds")))
        return min(when(run, "started"), when(run, "finished") - ran)
    try:
        start = min(start_of(r) for r in runs)
        end = max(when(r, "finished") for r in runs)
    except (ArchiveError, ValueError):
        return None
    return (end - start).total_seconds() / 3600.0


def every_run(archives):
    """The runs of every archive, in order; an ArchiveError naming a run id found
    twice (the same archive given twice, or two studies with a replicate in common)."""
    runs, seen = [], {}
    for archive in archives:
        for r in archive.select():
            if r.id in seen:
                raise ArchiveError(f"run {r.id} is in {seen[r.id]} and in {archive.path}: "
                                   "give each replicate once")
            seen[r.id] = archive.path
            runs.append(r)
    return runs


def key_table(groups):
    """(label, [cell per group]) rows and the CSV rows of the key quantities."""
    md, rows = [], []
    for key, label, fmt in KEY_ROWS:
        cells = []
        for g in groups:
            s = stat(g, key)
            paper = next((p for k, _, _, p, _ in quantities(g.runs[0]) if k == key), None)
            cell = interval(s, fmt)
            if s.values:
                cell += f", runs {fmt.format(min(s.values))}–{fmt.format(max(s.values))}"
            if paper is not None:
                cell += f" (paper {paper:g})"
            cells.append(cell)
            rows.append({"sample": g.name, "quantity": key, "n": s.n, "mean": s.mean,
                         "low": s.low, "high": s.high, "paper": paper})
        md.append(f"| {label} | " + " | ".join(cells) + " |")
    return md, rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("archives", nargs="+", metavar="archive")
    parser.add_argument("--csv", metavar="DIR", help="also write DIR/paper_study.csv")
    args = parser.parse_args(argv)
    try:
        with contextlib.ExitStack() as stack:
            runs = every_run([stack.enter_context(open_archive(a)) for a in args.archives])
            groups = group_runs([r for r in runs if r.loaded])
            print("## Goals\n\n| goal | measured (mean [95 % interval] or per run) | holds |"
                  "\n|---|---|---|")
            for goal, measured, holds in goals(groups):
                print(f"| {goal} | {measured} | {holds} |")
            hours = study_hours(runs) if len(args.archives) == 1 else None
            if hours is not None:
                # The span counts every pause (a resumed study, other work on the
                # cores); the runs' own wall times say what the study needs.
                core = sum(float(r.attribute("wall_seconds")) for r in runs) / 3600.0
                print(f"| the study fits in one night on 2 cores | {hours:.2f} h from first "
                      f"start to last end; its runs {core:.2f} h on one core each, "
                      f"{core / 2:.2f} h two at a time | {'yes' if hours <= 10 else 'no'} |")
            md, rows = key_table(groups)
            print("\n## Key quantities\n\nMean [95 % interval] over the replicates, the "
                  "runs' range, (the paper's number).\n")
            print("| quantity | " + " | ".join(f"{g.name} (n {len(g.runs)})" for g in groups)
                  + " |\n|---|" + "---|" * len(groups))
            print("\n".join(md))
            print("\n## Runs\n\n| run | seating ended by (ratio) | wall time (min) |\n|---|---|---|")
            for r in runs:
                e, u = seating(r)
                ratio = f" ({u:.4f})" if u is not None else ""
                print(f"| {r.id} | {e}{ratio} | {float(r.attribute('wall_seconds')) / 60:.1f} |")
            if args.csv:
                os.makedirs(args.csv, exist_ok=True)
                with open(os.path.join(args.csv, "paper_study.csv"), "w", newline="") as f:
                    w = csv.DictWriter(f, fieldnames=list(rows[0]))
                    w.writeheader()
                    w.writerows(rows)
    except ArchiveError as e:
        print(f"validation.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
