"""Where the particles that turn most sit, and what they do after.

For each loaded run: the k largest rotations during loading, and the k largest over
the whole cycle, each with the particle's place at the start of loading (depth of its
centre below the bed's top, distance to the nearer side wall, beneath the sleeper's
footprint or beside it) and its rotation during loading, on unloading and over the
cycle, and the cosine between its rotations during loading and on unloading; and for
each run, how many particles turned back on unloading (turning_back).

A rotation is Σ ω·dt (PFC's measure, cases/box_test_load.cpp), so the cycle's is the
vector sum of the loading's and the unloading's: |c|² = |l|² + |u|² + 2 l·u, and the
three angles the archive keeps give the cosine exactly. The cycle's angle lies between
|l − u| (cosine −1: the particle turned straight back) and l + u (+1: it went on
turning the same way). scripts/compare.py prints the tables; docs/VALIDATION.md
quotes them.
"""
import numpy as np

MM = 1e3


RANKINGS = ("loading", "cycle")


def turn_cosines(loading, unloading, cycle):
    """The cosine between each particle's rotation vectors during loading and on
    unloading, from the three angles (arrays, any unit); NaN where either is 0. Clipped
    to [-1, 1] against rounding in the angles."""
    loading, unloading, cycle = (np.asarray(a, dtype=float) for a in (loading, unloading, cycle))
    both = loading * unloading
    with np.errstate(divide="ignore", invalid="ignore"):
        cos = (cycle ** 2 - loading ** 2 - unloading ** 2) / (2.0 * both)
    return np.where(both > 0.0, np.clip(cos, -1.0, 1.0), np.nan)


def turning_back(run):
    """How the particles of a loaded run turned on unloading, or None:
    {particles: those that turned both during loading and on unloading, turned_back:
    the share of them whose unloading turned them back (cosine < 0), cosine: the
    mean cosine weighted by |l|·|u| (Σ l·u / Σ |l||u|: −1 if every particle turned
    straight back, +1 if every one went on), cycle_over_sum: the mean cycle rotation
    over the sum of the mean loading and unloading rotations, the measure the paper's
    means allow (its Sample 1 0.66, spheres 0.90)}."""
    if not run.loaded or not run.has("particles/rotation_loading"):
        return None
    loading = run.data("particles/rotation_loading")
    unloading = run.data("particles/rotation_unloading")
    cycle = run.data("particles/rotation_cycle")
    cos = turn_cosines(loading, unloading, cycle)
    turned = ~np.isnan(cos)
    weight = (loading * unloading)[turned]
    total = float(loading.mean() + unloading.mean())
    return {"particles": int(turned.sum()),
            "turned_back": float(np.mean(cos[turned] < 0.0)) if turned.any() else None,
            "cosine": float(np.sum(weight * cos[turned]) / weight.sum()) if turned.any()
            else None,
            "cycle_over_sum": float(cycle.mean()) / total if total > 0 else None}


def largest_rotations(run, k=3, by="loading"):
    """[{body, loading_deg, unloading_deg, cycle_deg, depth_mm, wall_mm, beneath}] of
    the k particles of `run` that turned most during loading (by="loading") or over
    the cycle (by="cycle"), largest first; [] for a run that was not loaded. depth_mm
    is None where the archive has no bed top (zones/surface)."""
    if by not in RANKINGS:
        raise ValueError(f"by = {by!r}: expected one of {RANKINGS}")
    if not run.loaded or not run.has("particles/rotation_loading"):
        return []
    loading = run.data("particles/rotation_loading")
    unloading = run.data("particles/rotation_unloading")
    cycle = run.data("particles/rotation_cycle")
    start = run.data("particles/position_start")
    surface = run.optional("surface", "zones")
    length = float(run.scene_value("box", "length"))
    width = float(run.scene_value("box", "width"))
    x0 = 0.5 * (length - float(run.scene_value("sleeper", "length")))
    x1 = length - x0
    rows = []
    cos = turn_cosines(loading, unloading, cycle)
    # Stable, so that equal rotations keep the bodies' order.
    for i in np.argsort(-(loading if by == "loading" else cycle), kind="stable")[:k]:
        x, y, z = (float(c) for c in start[i])
        rows.append({"body": int(i), "loading_deg": float(loading[i]),
                     "unloading_deg": float(unloading[i]), "cycle_deg": float(cycle[i]),
                     "cosine": None if np.isnan(cos[i]) else float(cos[i]),
                     "depth_mm": None if surface is None else (float(surface) - z) * MM,
                     "wall_mm": min(y, width - y) * MM, "beneath": x0 <= x <= x1})
    return rows


def largest_rotations_markdown(runs, k=3):
    """The tables of largest_rotations, by loading and by cycle, for the loaded runs
    ('' if none)."""
    parts = []
    for by, title in (("loading", "during loading"), ("cycle", "over the cycle")):
        lines = []
        for run in runs:
            for row in largest_rotations(run, k, by):
                depth = "—" if row["depth_mm"] is None else f"{row['depth_mm']:.0f}"
                cos = "—" if row["cosine"] is None else f"{row['cosine']:+.2f}"
                lines.append(f"| {run.label} | {row['body']} | {row['loading_deg']:.3g} | "
                             f"{row['unloading_deg']:.3g} | {row['cycle_deg']:.3g} | {cos} | "
                             f"{depth} | "
                             f"{row['wall_mm']:.0f} | "
                             f"{'beneath' if row['beneath'] else 'beside'} |")
        if lines:
            parts.append("\n".join([
                f"## The {k} largest rotations {title}, per run", "",
                "Rotation (°) during loading, on unloading and over the cycle; cos: the "
                "cosine between the rotations during loading and on unloading (+1 the "
                "particle went on turning the same way, −1 it turned straight back); where "
                "the particle sat when loading started: depth of its centre below the bed's "
                "top, distance to the nearer side wall, beneath the sleeper's footprint or "
                "beside it.", "",
                "| run | body | loading | unloading | cycle | cos | depth (mm) "
                "| to a side wall (mm) | sleeper |",
                "|---|---|---|---|---|---|---|---|---|"] + lines))
    return "\n\n".join(parts)


def turning_back_markdown(runs):
    """The table of turning_back for the loaded runs ('' if none)."""
    back = [(run, turning_back(run)) for run in runs]
    lines = [f"| {run.label} | {t['particles']:,} | {t['turned_back']:.2f} | {t['cosine']:+.2f} "
             f"| {t['cycle_over_sum']:.2f} |" for run, t in back
             if t is not None and t["turned_back"] is not None]
    if not lines:
        return ""
    return "\n".join([
        "## Turning back on unloading, per run", "",
        "Of the particles that turned both during loading and on unloading: the share "
        "whose unloading turned them back, and the cosine between the two rotations "
        "weighted by their sizes (+1: every particle went on the same way, −1: every "
        "one turned straight back). Last, the mean cycle rotation over the sum of the "
        "mean loading and unloading rotations, the only such measure the paper's means "
        "give (Sample 1 0.66, spheres 0.90).", "",
        "| run | particles | turned back | cosine, weighted | cycle / (loading + "
        "unloading), means |", "|---|---|---|---|---|"] + lines)
