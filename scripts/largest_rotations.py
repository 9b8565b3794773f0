"""Where the particles that turn most sit, and what they do after.

For each loaded run: the k largest rotations during loading, and the k largest over
the whole cycle, each with the particle's place at the start of loading (depth of its
centre below the bed's top, distance to the nearer side wall, beneath the sleeper's
footprint or beside it) and its rotation during loading, on unloading and over the
cycle. The paper's Sample 1 clump that turned most during loading (8.89°) had turned
back to 3.31° by the end of the cycle. Rotations are angles, so the cycle's lies
between |loading − unloading| (the particle turned back) and loading + unloading (it
went on turning the same way). scripts/compare.py prints both tables;
docs/VALIDATION.md quotes them.
"""
import numpy as np

MM = 1e3


RANKINGS = ("loading", "cycle")


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
    # Stable, so that equal rotations keep the bodies' order.
    for i in np.argsort(-(loading if by == "loading" else cycle), kind="stable")[:k]:
        x, y, z = (float(c) for c in start[i])
        rows.append({"body": int(i), "loading_deg": float(loading[i]),
                     "unloading_deg": float(unloading[i]), "cycle_deg": float(cycle[i]),
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
                lines.append(f"| {run.label} | {row['body']} | {row['loading_deg']:.3g} | "
                             f"{row['unloading_deg']:.3g} | {row['cycle_deg']:.3g} | {depth} | "
                             f"{row['wall_mm']:.0f} | "
                             f"{'beneath' if row['beneath'] else 'beside'} |")
        if lines:
            parts.append("\n".join([
                f"## The {k} largest rotations {title}, per run", "",
                "Rotation (°) during loading, on unloading and over the cycle; where the "
                "particle sat when loading started: depth of its centre below the bed's "
                "top, distance to the nearer side wall, beneath the sleeper's footprint or "
                "beside it. A cycle's rotation near loading + unloading: the particle went "
                "on turning the same way; near their difference: it turned back.", "",
                "| run | body | loading | unloading | cycle | depth (mm) | to a side wall (mm) "
                "| sleeper |", "|---|---|---|---|---|---|---|---|"] + lines))
    return "\n\n".join(parts)
