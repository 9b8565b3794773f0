#!/usr/bin/python3
"""The runs of a ballast archive side by side, beside Lu & McDowell (2007)'s numbers.

    /usr/bin/python3 scripts/compare.py ARCHIVE.h5 [--runs ID1,ID2] [--json]

One column per run (status ok), one row per measured quantity; a cell reads
"ours (paper)" where the paper gives a number for the run's sample: the spheres,
Table 2 Sample 1 or Sample 2 (Sample 2 has only its porosity; a run that changes a
preset's clump parameters is not the paper's sample and gets none). The paper's runs
are full scale at 40 kN: at smoke scale (fewer, smaller particles, a lighter load)
forces, counts and displacements are not expected to match, only the trends between
samples. Contact counts are ball–ball plus ball–wall; the paper's Sample 1 count
includes the overlaps inside clumps (16 per ball). `--json` prints the same numbers,
unrounded, for scripts.
"""
import argparse
import json
import sys

from ballast_archive import ArchiveError, add_run_arguments, chosen_runs, open_archive
from paper_values import PHASES, STAGES, paper_sample, paper_text, paper_values

MM = 1e3
STAGE_LABELS = {"before": "before loading", "peak": "at peak load", "after": "after unloading"}


def quantities(run, paper=None):
    """(key, label, ours, paper, format) for every quantity the run has. `paper` is the
    paper's numbers to set beside them (default: those of the run's own sample)."""
    a, p = run.attribute, paper_values(run) if paper is None else paper
    rows = [("porosity_grid", "porosity, 5 mm grid under the sleeper", a("porosity_grid"),
             p.get("porosity"), "{:.3f}")]
    if run.has("porosity/sphere_porosity") and len(run.data("porosity/sphere_porosity")):
        rows.append(("porosity_spheres", "porosity, measurement spheres on the column axis "
                     "(mean)", float(run.data("porosity/sphere_porosity").mean()),
                     p.get("porosity"), "{:.3f}"))
    for k, stage in enumerate(STAGES):
        if not run.has(f"contacts/{stage}"):
            continue
        c = lambda name: run.attribute(name, f"contacts/{stage}")  # noqa: E731
        pc = p["contacts"][k] if "contacts" in p else (None, None, None)
        label = f"contacts {STAGE_LABELS[stage]}"
        rows += [(f"contacts_{stage}_count", f"{label}: count (ball–ball + ball–wall)",
                  int(c("ball_contacts")) + int(c("wall_contacts")), pc[0], "{:,.0f}"),
                 (f"contacts_{stage}_max_force_N", f"{label}: max force (N)",
                  float(c("max_force")), pc[1], "{:,.0f}"),
                 (f"contacts_{stage}_mean_force_N", f"{label}: mean force (N)",
                  float(c("mean_force")), pc[2], "{:.1f}")]
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
    return rows


def cell(value, paper, fmt):
    if value is None:
        return "—"
    return fmt.format(value) + ("" if paper is None else f" ({paper_text(paper)})")


def scale_row(run):
    return (f"{int(run.attribute('bodies'))} bodies, {int(run.attribute('balls'))} balls, "
            f"{float(run.scene_value('sleeper', 'peak_load')) / 1e3:g} kN")


def markdown(runs):
    """The side-by-side table as Markdown."""
    columns = [{key: (label, ours, paper, fmt) for key, label, ours, paper, fmt
                in quantities(r)} for r in runs]
    keys = []
    for col in columns:  # rows in first-seen order across runs
        keys += [k for k in col if k not in keys]
    head = ["quantity"] + [r.label for r in runs]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head),
             "| paper's sample | " + " | ".join(paper_sample(r) or "—" for r in runs) + " |",
             "| scale | " + " | ".join(scale_row(r) for r in runs) + " |"]
    for key in keys:
        label = next(c[key][0] for c in columns if key in c)
        cells = [cell(*(c[key][1:]) if key in c else (None, None, "")) for c in columns]
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def as_json(runs):
    return {"runs": [{"id": r.id, "label": r.label, "shape": r.shape,
                      "paper_sample": paper_sample(r),
                      "quantities": {key: {"ours": ours, "paper": paper}
                                     for key, _, ours, paper, _ in quantities(r)}}
                     for r in runs]}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_run_arguments(parser)
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    args = parser.parse_args(argv)
    try:
        with open_archive(args.archive) as archive:
            runs = chosen_runs(archive, args.runs, "compare")
            if args.json:
                print(json.dumps(as_json(runs), indent=1))
            else:
                print(f"Runs of {args.archive} beside Lu & McDowell (2007): ours (paper). "
                      "The paper's box: 1,936 spheres or 1,770 clumps, 40 kN.\n")
                print(markdown(runs))
    except ArchiveError as e:
        print(f"compare.py: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
