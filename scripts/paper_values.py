"""The numbers Lu & McDowell (2007) report for the box test, in one place.

Read by scripts/compare.py, scripts/figures.py and scripts/validation.py. Sources:
section 3.3 (porosity on the 5 mm grid under the sleeper), the captions of Figs 11-12
(contacts: count, max and mean force before loading, at 40 kN, after unloading to
3 kN), Figs 13-14 (particle rotations, mean and max, degrees) and Figs 15-16 (largest
particle displacement, mm). Fig. 12's count, 282,955 at every stage, is 16 per ball:
PFC evidently counted the overlaps between balls of one clump; ours never does.
The paper loaded only the spheres and Sample 1, so Sample 2 has a porosity only.
"""

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
