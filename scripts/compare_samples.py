"""The sample-level tables of scripts/compare.py, in Markdown and JSON: each sample's
replicates summarised, the spheres / clumps ratios, and the directions in which the
top layer moves beneath and beside the sleeper, each beside Lu & McDowell (2007).

- "Replicates" (printed when a sample has two runs or more): one row per quantity of
  compare.quantities, one column per sample, "mean ± half-width (sd s, n)" with the
  95 % interval of the mean, and the paper's number in brackets where it applies.
- "Spheres against clumps": the spheres' mean over each clump sample's for the mean
  rotation during loading and over the cycle, the largest displacement and the
  sleeper settlement at peak, with the delta-method interval, beside the paper's
  ratio (5.18 / 0.061, 7.25 / 0.062, 8.25 / 2.34; the paper gives no settlement). An
  interval wholly below or above the paper's ratio says so; one that holds it reads
  "consistent".
- "Directions" (archives with zones/): the mean vertical displacement of the top layer
  beneath and beside the sleeper at peak and its change on unloading, beside the
  paper's direction (paper_values.DIRECTIONS), "agrees" or "disagrees" by the sign of
  the mean, "not resolved" when the interval holds 0. A direction is a trend, so it is
  set beside the paper's at every scale; numbers only at the paper's scale.

Statistics and grouping: scripts/replicates.py.
"""
from dataclasses import dataclass

from ballast_archive import ZONES
from paper_values import DIRECTIONS, comparable, paper_sample, paper_text, scale_shortfalls
from replicates import (RATIO_KEYS, Group, group_summaries, ordered_union, ratio_of_means,
                        sphere_clump_pairs, verdict)

MM = 1e3


@dataclass
class SampleStats:
    """One group of replicates: a Summary per quantity key, each key's (label, paper's
    number, format) from compare.quantities, and whether the paper's numbers apply to
    every run of it (its sample, at the paper's scale)."""
    group: Group
    summaries: dict
    meta: dict
    comparable: bool

    def paper(self, key):
        """The paper's number for `key` where it applies, else None."""
        return self.meta[key][1] if self.comparable and key in self.meta else None


def sample_stats(groups, rows):
    """SampleStats of each group; rows[run.id] is compare.quantities(run)."""
    out = []
    for g in groups:
        table = {r.id: {key: ours for key, _, ours, _, _ in rows[r.id]} for r in g.runs}
        meta = {}
        for r in g.runs:
            for key, label, _, paper, fmt in rows[r.id]:
                meta.setdefault(key, (label, paper, fmt))
        out.append(SampleStats(g, group_summaries(g, table), meta,
                               all(comparable(r) for r in g.runs)))
    return out


def span(values, fmt):
    """'a' or 'a–b' for the smallest and largest of some numbers."""
    lo, hi = min(values), max(values)
    return fmt.format(lo) if lo == hi else f"{fmt.format(lo)}–{fmt.format(hi)}"


def summary_cell(s, fmt, paper=None, sd=True):
    """'mean ± half-width (sd s, n N) [paper]'; n = 1 says it has no interval. A spread
    below 1e-9 of the mean is rounding (a difference of equal numbers) and reads 0."""
    if s is None or s.mean is None:
        return "—"
    if s.half_width is None:
        text = f"{fmt.format(s.mean)} (n {s.n}, no interval)"
    else:
        def spread(x):
            return fmt.format(0.0 if x <= 1e-9 * abs(s.mean) else x)

        text = (f"{fmt.format(s.mean)} ± {spread(s.half_width)} ("
                + (f"sd {spread(s.sd)}, " if sd else "") + f"n {s.n})")
    return text + ("" if paper is None else f" [{paper_text(paper)}]")


def replicates_markdown(stats):
    head = ["quantity"] + [s.group.name for s in stats]
    lines = ["## Replicates", "", "Each sample's runs with other seeds: mean ± half-width of "
             "the 95 % interval of the mean (Student's t, n − 1 degrees of freedom), sample "
             "standard deviation and number of runs; [the paper's number] where it applies.",
             "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for key in ordered_union(s.summaries for s in stats):
        label, _, fmt = next(s.meta[key] for s in stats if key in s.meta)
        cells = [summary_cell(s.summaries.get(key), fmt, s.paper(key)) for s in stats]
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


@dataclass
class RatioRow:
    """One quantity's spheres / clumps ratio, and the paper's where it has one."""
    key: str
    label: str
    spheres: SampleStats
    clumps: SampleStats
    ratio: object  # replicates.Ratio
    paper: object  # the paper's ratio, whatever the runs' scale (None: the paper has none)

    @property
    def judged(self):
        """The interval against the paper's ratio, in words."""
        if self.paper is None:
            return "the paper has none"
        if not (self.spheres.comparable and self.clumps.comparable):
            return "not comparable: not the paper's scale"
        return verdict(self.ratio.low, self.ratio.high, self.paper) or self.ratio.note


def ratio_rows(stats):
    """A RatioRow for each RATIO_KEYS quantity of each (spheres, clumps) pair."""
    by_group = {id(s.group): s for s in stats}
    rows = []
    for sg, cg in sphere_clump_pairs([s.group for s in stats]):
        sp, cl = by_group[id(sg)], by_group[id(cg)]
        for key in RATIO_KEYS:
            if key not in sp.summaries or key not in cl.summaries:
                continue
            ps, pc = sp.meta[key][1], cl.meta[key][1]
            paper = ps / pc if ps is not None and pc else None
            rows.append(RatioRow(key, sp.meta[key][0], sp, cl,
                                 ratio_of_means(sp.summaries[key], cl.summaries[key]), paper))
    return rows


def ratios_markdown(rows):
    def number(x):
        return "—" if x is None else f"{x:.3g}"

    lines = ["## Spheres against clumps", "", "The spheres' mean over the clumps' mean, with "
             "the 95 % interval of the delta method on the log of the ratio (Welch–"
             "Satterthwaite degrees of freedom).", "",
             "| quantity | samples | ratio | 95 % interval | paper | against the paper |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        interval = (r.ratio.note or "—" if r.ratio.low is None
                    else f"{number(r.ratio.low)}–{number(r.ratio.high)}")
        shown = r.paper if r.spheres.comparable and r.clumps.comparable else None
        lines.append(f"| {r.label} | {r.spheres.group.name} / {r.clumps.group.name} | "
                     f"{number(r.ratio.value)} | {interval} | {number(shown)} | "
                     f"{r.judged} |")
    return "\n".join(lines)


def agreement(s, sign):
    """A measured Summary's sign against the paper's (+1 up, -1 down), in words."""
    if s is None or s.mean is None:
        return "no value"
    if s.mean == 0 or (s.low is not None and s.low <= 0 <= s.high):
        return "not resolved"
    word = "agrees" if (s.mean > 0) == (sign > 0) else "disagrees"
    return word if s.low is not None else f"{word} (n = 1, no interval)"


def direction_rows(stats):
    """(stats, zone, Summary at peak, Summary of the change on unloading, the paper's
    (peak sign, unloading sign, words) or None) for every zone a sample has."""
    rows = []
    for s in stats:
        paper = DIRECTIONS.get(paper_sample(s.group.runs[0]), {})
        for zone in ZONES:
            peak = s.summaries.get(f"zone_{zone}_dz_peak_mm")
            if peak is not None:
                rows.append((s, zone, peak, s.summaries.get(f"zone_{zone}_dz_unloading_mm"),
                             paper.get(zone)))
    return rows


def directions_markdown(rows):
    runs = [r for s, *_ in rows for r in s.group.runs]
    depth = [float(d) * MM for d in (r.optional("layer_depth", "zones") for r in runs)
             if d is not None]
    layer = f"centres within {span(depth, '{:g}')} mm" if depth else "centres"
    lines = ["## Directions", "", f"Mean vertical displacement (mm, up positive) of the top "
             f"layer's particles ({layer} of the bed top at the start of loading), beneath "
             "the sleeper's footprint and beside it: at peak load, and its change on "
             "unloading (after the cycle − at peak); ± the 95 % half-width when n ≥ 2. "
             "Agreement by the sign of the mean; 'not resolved' where the interval holds 0. "
             "A direction is a trend: it is set beside the paper's at any scale.",
             "", "| sample | zone | at peak | change on unloading | paper | agreement |",
             "|---|---|---|---|---|---|"]
    for s, zone, peak, change, paper in rows:
        words = "—" if paper is None else paper[2]
        agree = "—" if paper is None else (f"peak: {agreement(peak, paper[0])}; unloading: "
                                           f"{agreement(change, paper[1])}")
        lines.append(f"| {s.group.name} | {zone} | {summary_cell(peak, '{:.3g}', sd=False)} | "
                     f"{summary_cell(change, '{:.3g}', sd=False)} | {words} | {agree} |")
    return "\n".join(lines)


def samples_markdown(stats):
    """The sample-level sections that apply, as Markdown ('' when none does)."""
    parts = []
    if any(len(s.group.runs) >= 2 for s in stats):
        parts.append(replicates_markdown(stats))
    ratios, directions = ratio_rows(stats), direction_rows(stats)
    if ratios:
        parts.append(ratios_markdown(ratios))
    if directions:
        parts.append(directions_markdown(directions))
    return "\n\n".join(parts)


def samples_json(stats):
    """{"samples": [...], "ratios": [...], "directions": [...]}: the same numbers,
    unrounded, the paper's whatever the scale (with the flags that say if it applies)."""
    def sign(x):
        return None if x is None else ("up" if x > 0 else "down")

    samples = [{"name": s.group.name, "sample": s.group.sample,
                "runs": [r.id for r in s.group.runs],
                "paper_sample": paper_sample(s.group.runs[0]),
                "at_paper_scale": not any(scale_shortfalls(r) for r in s.group.runs),
                "comparable_with_paper": s.comparable,
                "quantities": {k: dict(v.as_json(), paper=s.meta[k][1])
                               for k, v in s.summaries.items()}} for s in stats]
    ratios = [dict(r.ratio.as_json(), quantity=r.key, spheres=r.spheres.group.name,
                   clumps=r.clumps.group.name, paper=r.paper, verdict=r.judged)
              for r in ratio_rows(stats)]
    directions = [{"sample": s.group.name, "zone": zone, "dz_peak_mm": peak.as_json(),
                   "dz_unloading_mm": None if change is None else change.as_json(),
                   "paper": None if paper is None else {
                       "peak": sign(paper[0]), "unloading": sign(paper[1]), "words": paper[2]},
                   "agreement": None if paper is None else {
                       "peak": agreement(peak, paper[0]),
                       "unloading": agreement(change, paper[1])}}
                  for s, zone, peak, change, paper in direction_rows(stats)]
    return {"samples": samples, "ratios": ratios, "directions": directions}
