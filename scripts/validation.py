#!/usr/bin/python3
"""Our box-test figures beside Lu & McDowell (2007)'s, as a Markdown table.

    /usr/bin/python3 scripts/validation.py spheres=runs/spheres.h5 sample1=runs/sample1.h5

Each argument is NAME=ARCHIVE, NAME one of spheres, sample1, sample2; an archive is
a `ballast run -o` file (group /run) or a study archive's run group given as
ARCHIVE:/runs/ID. The paper's numbers are from its Figs 11-18 and section 3.3
(scripts/paper_values.py); the rows are scripts/compare.py's, one run per table.
"""
import sys

from ballast_archive import ArchiveError, open_archive
from compare import quantities
from paper_values import PAPER, paper_text


def open_run(spec):
    path, _, group = spec.partition(":")
    archive = open_archive(path)
    return archive.run(group.rsplit("/", 1)[-1]) if group else archive.runs()[0]


def row(label, ours, paper, fmt):
    p = "—" if paper is None else paper_text(paper)
    return f"| {label} | {fmt.format(ours)} | {p} |"


def table(name, run):
    a = run.attrs
    lines = [f"### {name} ({int(a['bodies'])} bodies, {int(a['balls'])} balls, "
             f"dt {a['dt'] * 1e6:.3f} µs, {a['wall_seconds'] / 60:.1f} min on the run's machine)",
             "", "| quantity | ours | paper |", "|---|---|---|"]
    lines += [row(label, ours, paper, fmt)
              for _, label, ours, paper, fmt in quantities(run, PAPER[name])]
    return "\n".join(lines)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for arg in sys.argv[1:]:
        name, _, spec = arg.partition("=")
        if name not in PAPER:
            sys.exit(f"unknown sample name '{name}' (allowed: {', '.join(PAPER)})")
        try:
            print(table(name, open_run(spec)))
        except ArchiveError as e:
            sys.exit(f"validation.py: {e}")
        print()


if __name__ == "__main__":
    main()
