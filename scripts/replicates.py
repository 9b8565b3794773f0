"""Replicates as the unit of a claim: runs grouped into samples, and the statistics of a
sample's mean and of the ratio of two samples' means.

A study repeats a run with other seeds (`-r1`, `-r2`, ...: docs/STUDY.md); one run's
number says little about the sample, the mean of its replicates and the spread around
it do. Read by scripts/compare.py (the "Replicates" and "Spheres against clumps"
tables) and scripts/fig_zones.py.

Grouping. Runs are replicates when they share the study sample (attribute `sample`)
and every parameter (attribute `params`): a study whose matrix also has axes
(`spheres-dt_safety=0.8-r1`, `spheres-dt_safety=0.4-r1`) has one group per sample and
combination of axis values. A group is named after its sample when the sample has one
group, else after its first run's id without the `-r<k>`; a single-run archive (no
`sample`) is one group named after the run's label.

Mean of one sample, n values x_i:
    mean m = sum(x_i) / n,  sample standard deviation s = sqrt(sum((x_i - m)^2) / (n - 1)),
    95 % interval  m ± t(n - 1) · s / sqrt(n),
t(df) the 0.975 quantile of Student's t with df degrees of freedom (T975 below for df
1..30, 1.96, the normal's, beyond). With n = 1 there is no standard deviation and no
interval (Summary.note says so); none is ever made up.

Ratio of two means, R = m1 / m2 (spheres over clumps), by the delta method on ln R:
    var(ln R) ≈ a + b,  a = s1^2 / (n1 · m1^2),  b = s2^2 / (n2 · m2^2),
degrees of freedom by Welch–Satterthwaite on those two terms,
    df = (a + b)^2 / (a^2 / (n1 - 1) + b^2 / (n2 - 1))   (rounded down, at least 1),
and the 95 % interval  R · exp(± t(df) · sqrt(a + b)), which is never below zero and
not symmetric about R. No interval when either sample has n < 2 or when R is not
positive; no ratio at all when m2 is 0 or a mean is missing.
"""
import json
import math
import re
from dataclasses import dataclass, field
from typing import List, Optional

from ballast_archive import CLUMP_KEYS

# 0.975 quantiles of Student's t, df = 1..30 (tests/scripts/test_replicates.py checks
# them against the integral of t's density).
T975 = (12.7062, 4.3027, 3.1824, 2.7764, 2.5706, 2.4469, 2.3646, 2.3060, 2.2622, 2.2281,
        2.2010, 2.1788, 2.1604, 2.1448, 2.1314, 2.1199, 2.1098, 2.1009, 2.0930, 2.0860,
        2.0796, 2.0739, 2.0687, 2.0639, 2.0595, 2.0555, 2.0518, 2.0484, 2.0452, 2.0423)
Z975 = 1.96

# The quantities (compare.py's keys) whose spheres / clumps ratio is reported.
RATIO_KEYS = ("rotation_loading_mean_deg", "rotation_cycle_mean_deg",
              "max_displacement_peak_mm", "settlement_peak_mm")


def t975(df):
    """The 0.975 quantile of Student's t with `df` degrees of freedom: a fractional df
    is rounded down (the wider interval), df > 30 takes the normal's 1.96."""
    df = int(math.floor(df))
    if df < 1:
        raise ValueError(f"degrees of freedom {df} (at least 1)")
    return T975[df - 1] if df <= len(T975) else Z975


@dataclass
class Summary:
    """Mean, sample standard deviation and 95 % interval of one sample's values.
    sd, half_width, low, high and df are None when there is no interval (note says why);
    mean is None when there are no values."""
    n: int
    mean: Optional[float]
    sd: Optional[float] = None
    df: Optional[int] = None
    half_width: Optional[float] = None
    low: Optional[float] = None
    high: Optional[float] = None
    note: str = ""
    values: List[float] = field(default_factory=list)

    def as_json(self):
        return {"n": self.n, "mean": self.mean, "sd": self.sd, "df": self.df,
                "half_width": self.half_width,
                "ci95": None if self.low is None else [self.low, self.high],
                "note": self.note or None, "values": self.values}


def summarize(values):
    """The Summary of a list of numbers (None entries, runs lacking the quantity, and
    NaN are left out and not counted)."""
    xs = [float(v) for v in values if v is not None and math.isfinite(float(v))]
    n = len(xs)
    if n == 0:
        return Summary(0, None, note="no values")
    mean = math.fsum(xs) / n
    if n == 1:
        return Summary(1, mean, note="n = 1: no interval", values=xs)
    # Equal values have no spread, whatever the rounding of their mean says.
    sd = 0.0 if min(xs) == max(xs) else math.sqrt(math.fsum((x - mean) ** 2 for x in xs)
                                                  / (n - 1))
    half = t975(n - 1) * sd / math.sqrt(n)
    return Summary(n, mean, sd, n - 1, half, mean - half, mean + half, values=xs)


@dataclass
class Ratio:
    """R = m1 / m2 with its 95 % interval (low, high; None with `note` when there is
    none); value None when there is no ratio."""
    value: Optional[float]
    low: Optional[float] = None
    high: Optional[float] = None
    df: Optional[int] = None
    note: str = ""

    def as_json(self):
        return {"ratio": self.value, "df": self.df, "note": self.note or None,
                "ci95": None if self.low is None else [self.low, self.high]}


def ratio_of_means(num, den):
    """The ratio of two Summaries' means with the delta-method interval (module doc)."""
    if num.mean is None or den.mean is None:
        return Ratio(None, note="a mean is missing")
    if den.mean == 0:
        return Ratio(None, note="the denominator's mean is 0")
    value = num.mean / den.mean
    if num.n < 2 or den.n < 2:
        return Ratio(value, note=f"n = {min(num.n, den.n)}: no interval")
    if value <= 0:
        return Ratio(value, note="ratio not positive: no interval on ln R")
    a = num.sd ** 2 / (num.n * num.mean ** 2)
    b = den.sd ** 2 / (den.n * den.mean ** 2)
    welch = a ** 2 / (num.n - 1) + b ** 2 / (den.n - 1)
    # Both spreads zero (identical replicates): a zero-width interval on n1 + n2 - 2.
    df = max(1, int(math.floor((a + b) ** 2 / welch))) if welch > 0 else num.n + den.n - 2
    spread = math.exp(t975(df) * math.sqrt(a + b))
    return Ratio(value, value / spread, value * spread, df)


def verdict(low, high, paper):
    """An interval against the paper's number, in words; None without both."""
    if low is None or paper is None:
        return None
    if high < paper:
        return "below the paper's"
    if low > paper:
        return "above the paper's"
    return "consistent"


@dataclass
class Group:
    """The replicates of one sample: its name and runs (scripts/ballast_archive.Run)."""
    name: str
    runs: list

    @property
    def sample(self):
        return self.runs[0].sample

    @property
    def is_clumps(self):
        return all(r.is_clumps for r in self.runs)

    def axis_params(self):
        """The runs' parameters other than the sample's shape and clump keys: equal for
        a sphere group and a clump group that ran the same other settings."""
        return {k: v for k, v in self.runs[0].params.items()
                if k != "shape" and k not in CLUMP_KEYS}


def _key(run):
    if run.archive.kind != "study":
        return ("", run.label)
    return (run.sample, json.dumps(run.params, sort_keys=True))


def group_runs(runs):
    """The runs (ok, in study order) as Groups of replicates, in first-seen order."""
    groups = {}
    for run in runs:
        groups.setdefault(_key(run), []).append(run)
    per_sample = {}
    for sample, _ in groups:
        per_sample[sample] = per_sample.get(sample, 0) + 1
    named = []
    for (sample, _), members in groups.items():
        first = members[0]
        if first.archive.kind != "study":
            name = first.label
        elif sample and per_sample[sample] == 1:
            name = sample
        else:
            name = re.sub(r"(^|-)r\d+$", "", first.id) or sample or first.label
        named.append(Group(name, members))
    return named


def sphere_clump_pairs(groups):
    """(spheres group, clump group) for every clump group: the sphere group that ran the
    same other settings, else the only sphere group; clump groups with neither are
    left out."""
    spheres = [g for g in groups if not g.is_clumps]
    pairs = []
    for clumps in (g for g in groups if g.is_clumps):
        same = [s for s in spheres if s.axis_params() == clumps.axis_params()]
        match = same if len(same) == 1 else spheres if len(spheres) == 1 else []
        if match:
            pairs.append((match[0], clumps))
    return pairs


def ordered_union(mappings):
    """The keys of several dicts, each once, in first-seen order."""
    keys = {}
    for m in mappings:
        keys.update(dict.fromkeys(m))
    return list(keys)


def group_summaries(group, table):
    """{key: Summary} over the group's runs; `table[run.id]` maps a quantity key to its
    value for that run (a key a run lacks is left out of that run's count)."""
    keys = ordered_union(table[r.id] for r in group.runs)
    return {k: summarize([table[r.id].get(k) for r in group.runs]) for k in keys}
