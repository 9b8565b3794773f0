"""The numbers Lu & McDowell (2007) report for the box test, in one place.

Read by scripts/compare.py, scripts/figures.py and scripts/validation.py. Sources:
section 3.3 (porosity on the 5 mm grid under the sleeper), the captions of Figs 11-12
(contacts: count, max and mean force before loading, at 40 kN, after unloading to
3 kN), Figs 13-14 (particle rotations, mean and max, degrees) and Figs 15-16 (largest
particle displacement, mm). Fig. 12's count, 282,955 at every stage, is 16 per ball:
PFC evidently counted the overlaps between balls of one clump; ours never does.
The paper loaded only the spheres and Sample 1, so Sample 2 has a porosity only.
Figs 15-17 and section 3.3 also say, in words, which way the top of the bed moves
(DIRECTIONS). Every number is for the paper's full-scale box (PAPER_SCALE): a run at
another scale is not comparable with them (scale_shortfalls).
"""
import math

# Sample name -> porosity, contacts [(count, max N, mean N)] before / peak / after,
# rotations [(mean deg, max deg)] loading / unloading / cycle, max displacement (mm)
# at peak / after the cycle.
PAPER = {
    "spheres": {
        "porosity": 0.37,
        "contacts": [(10337, 482, 29.9), (10323, 4050, 336.2), (10328, 1012, 42.7)],
        "rotation": [(5.18, 48.3), (2.92, 26.5), (7.25, 63.2)],
        "displacement_mm": (8.25, 11.79),
    },
    "sample1": {
        "porosity": 0.35,
        "contacts": [(282955, 374, 15.4), (282955, 4233, 164.1), (282955, 1354, 34.4)],
        "rotation": [(0.061, 8.89), (0.033, 3.15), (0.062, 3.31)],
        "displacement_mm": (2.34, 2.32),
    },
    "sample2": {"porosity": 0.37},
}

# The particle shape of each sample with the paper's numbers (scene `particles/shape`).
SAMPLE_OF_SHAPE = {"spheres": "spheres", "table2/sample1": "sample1",
                   "table2/sample2": "sample2"}

# The paper's figure numbers per sample: contact networks (Figs 11-12), rotations
# (13-14), displacements at the common scale (15-16).
FIGURE_OF_SAMPLE = {"spheres": {"contacts": 11, "rotations": 13, "displacements": 15},
                    "sample1": {"contacts": 12, "rotations": 14, "displacements": 16}}

# Rotation classes of Figs 13-14 (deg): grey circles from `grey` to `black`, solid
# black circles above `black`.
ROTATION_CLASSES = {"spheres": (10.0, 20.0), "clumps": (0.1, 1.0)}

# Fig. 17 redraws Fig. 16's clump displacements magnified by this factor.
CLUMP_MAGNIFICATION = 80.0

# Which way the top layer moves (Figs 15-17, section 3.3), per sample and zone (the
# zones of docs/ARCHIVE.md, `zones/beneath` and `zones/beside`): the sign of the mean
# vertical displacement at peak load and of its change on unloading (+1 up, -1 down),
# and the paper's words. The spheres beside the sleeper flow up at peak and keep
# rising on unloading; Sample 1's clumps beneath it go down at peak and come back up
# on unloading, by less than they went down. The paper says nothing of the other zones.
DIRECTIONS = {
    "spheres": {"beside": (+1, +1, "up at peak, rising further on unloading")},
    "sample1": {"beneath": (-1, +1, "down at peak, up on unloading (by less)")},
}

# The paper's box test: 1,936 spheres or 1,770 clumps in a 700 mm box,
# the sleeper loaded to 40 kN. A run with fewer bodies than MIN_BODIES, another peak
# load or another box length is a smoke or reduced-scale run.
PAPER_SCALE = {"min_bodies": 1500, "peak_load": 40000.0, "box_length": 0.7}
FULL_SCALE_SCENES = "cases/box_test/{spheres,sample1,sample2}.json or cases/paper_study.json"

STAGES = ("before", "peak", "after")
PHASES = ("loading", "unloading", "cycle")


def paper_text(value):
    """A paper's number as the paper prints it: 10,337; 0.37; 11.79."""
    return f"{value:,}" if isinstance(value, int) else f"{value:g}"


def paper_sample(run):
    """The paper's sample a run (scripts/ballast_archive.Run) reproduces, or None: a
    shape the paper did not test, or a preset whose clump parameters the run changed."""
    if run.clump_overrides:
        return None
    return SAMPLE_OF_SHAPE.get(run.shape)


def paper_values(run):
    """The paper's numbers for the run's sample ({} when there are none)."""
    return PAPER.get(paper_sample(run), {})


def scale_shortfalls(run):
    """How a run (scripts/ballast_archive.Run) differs from the paper's scale, in words
    (mm, kN); an empty list for a run at the paper's scale."""
    bodies = int(run.attribute("bodies"))
    load = float(run.scene_value("sleeper", "peak_load"))
    length = float(run.scene_value("box", "length"))
    out = []
    if bodies < PAPER_SCALE["min_bodies"]:
        out.append(f"{bodies:,} bodies < {PAPER_SCALE['min_bodies']:,}")
    if not math.isclose(load, PAPER_SCALE["peak_load"], rel_tol=1e-9):
        out.append(f"peak load {load / 1e3:g} kN, not {PAPER_SCALE['peak_load'] / 1e3:g}")
    if not math.isclose(length, PAPER_SCALE["box_length"], rel_tol=1e-9):
        out.append(f"box {length * 1e3:g} mm long, not {PAPER_SCALE['box_length'] * 1e3:g}")
    return out


def comparable(run):
    """Whether the paper's numbers apply to the run: its sample and its scale."""
    return paper_sample(run) is not None and not scale_shortfalls(run)
