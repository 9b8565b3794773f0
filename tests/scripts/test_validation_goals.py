#!/usr/bin/python3
"""scripts/validation.py's goals on a synthetic full-scale archive: a goal asked of
every replicate says how many meet it, and holds only when all do.

    /usr/bin/python3 tests/scripts/test_validation_goals.py

Needs no build: the archive is written with h5py by synthetic_archive.py.
"""
import contextlib
import io
import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
sys.path.insert(0, HERE)

from ballast_archive import open_archive  # noqa: E402
from replicates import group_runs  # noqa: E402
from synthetic_archive import FULL, run, write_study  # noqa: E402
from validation import goals, main  # noqa: E402


# A sphere column whose whole porosity is the paper's 0.37, made of layers of 0.45
# within one diameter (36.25 mm) of the side walls, base and top of a 0.39 m bed in the
# 0.3 m wide box, and an interior to match: the interior's share of the column is
# (0.3 − 0.0725)(0.39 − 0.0725) / (0.3 × 0.39).
SPHERE_BED, SPHERE_WALLS = 0.39, 0.45
SPHERE_SHARE = (0.3 - 0.0725) * (SPHERE_BED - 0.0725) / (0.3 * SPHERE_BED)
SPHERE_INTERIOR = (0.37 - (1.0 - SPHERE_SHARE) * SPHERE_WALLS) / SPHERE_SHARE


def sample1_runs():
    """Four Sample 1 replicates: the second sinks on unloading (resilient settlement
    < 0), the third's cycle maximum exceeds its loading maximum, the fourth creeps
    under the preload. Two sphere replicates give the rotation ratio its numerator."""
    runs = [run(f"spheres-r{k + 1}", "spheres", "spheres", k + 1, bodies=1936,
                rotation_loading_mean_deg=1.0 + 0.1 * k, bed_height=SPHERE_BED,
                porosity_grid=0.37, porosity_grid_interior=SPHERE_INTERIOR) for k in range(2)]
    resilient = (9e-6, -2e-6, 1.1e-5, 8e-6)
    cycle_max = (0.40, 0.45, 7.70, 2.00)
    seating = ("equilibrium", "equilibrium", "equilibrium", "steady creep")
    for k in range(4):
        runs.append(run(f"T2S1-r{k + 1}", "T2S1", "table2/sample1", k + 1, bodies=1770,
                        seating=seating[k], resilient_settlement=resilient[k],
                        rotation_loading_mean_deg=0.05, rotation_loading_max_deg=1.0 + k,
                        rotation_cycle_max_deg=cycle_max[k]))
    return runs


class Goals(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        path = write_study(os.path.join(cls.tmp.name, "full.h5"), sample1_runs(), scene=FULL)
        with open_archive(path) as archive:
            rows = goals(group_runs(archive.runs()))
        cls.rows = {goal: (measured, holds) for goal, measured, holds in rows}

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def row(self, start):
        found = [v for k, v in self.rows.items() if k.startswith(start)]
        self.assertEqual(len(found), 1, f"one goal starting {start!r} in {list(self.rows)}")
        return found[0]

    def test_rebound_counts_the_replicates_that_rise(self):
        measured, holds = self.row("T2S1: rebounds in every replicate")
        self.assertTrue(measured.startswith("3 of 4 rebound: "), measured)
        self.assertEqual(holds, "no")

    def test_cycle_maximum_counts_the_replicates_below_their_loading_maximum(self):
        # 0.40 < 1, 0.45 < 2, 7.70 > 3, 2.00 < 4: three of four.
        measured, holds = self.row("T2S1: cycle's largest rotation below the loading's")
        self.assertTrue(measured.startswith("3 of 4 below: 0.40 vs 1.00°"), measured)
        self.assertEqual(holds, "no")

    def test_seating_counts_the_beds_at_rest(self):
        measured, holds = self.row("T2S1: at rest under the preload")
        self.assertTrue(measured.startswith("3 of 4 at rest: equilibrium"), measured)
        self.assertEqual(holds, "no")
        measured, holds = self.row("spheres: at rest under the preload")
        self.assertTrue(measured.startswith("2 of 2 at rest: "), measured)
        self.assertEqual(holds, "yes")

    def test_bearing_counts_whole_particles(self):
        # The synthetic contacts put 7 bodies under the sleeper: below 20 in every run.
        measured, holds = self.row("T2S1: sleeper on ≥ 20 particles")
        self.assertTrue(measured.startswith("0 of 4 meet it: 7 / "), measured)
        self.assertEqual(holds, "no")

    def test_porosity_splits_the_column_into_interior_and_wall_layers(self):
        # The whole column is at the paper's 0.37 already: the wall layers come out as
        # built, and the interior the paper's porosity needs is the one the column has.
        measured, holds = self.row("spheres: porosity within ±0.03 of 0.37")
        self.assertTrue(measured.startswith("0.370 ["), measured)
        self.assertIn(f"the layers left out {SPHERE_WALLS:.3f} [", measured)
        self.assertIn(f"0.37 needs an interior of {SPHERE_INTERIOR:.3f} [", measured)
        self.assertEqual(holds, "yes")

    def test_ratio_of_mean_rotations(self):
        # spheres 1.05 over Sample 1 0.05: 21, at or above the goal's 20.
        measured, holds = self.row("spheres / Sample 1 mean rotation")
        self.assertTrue(measured.startswith("21.0 ["), measured)
        self.assertEqual(holds, "yes")


class SeveralArchives(unittest.TestCase):
    """A study that adds replicates to another: validation.py reads both as one."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        runs = sample1_runs()
        first = [r for r in runs if r["id"].endswith(("-r1", "-r2"))]
        more = [r for r in runs if not r["id"].endswith(("-r1", "-r2"))]
        cls.first = write_study(os.path.join(cls.tmp.name, "first.h5"), first, scene=FULL)
        cls.more = write_study(os.path.join(cls.tmp.name, "more.h5"), more, scene=FULL)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def report(self, *archives):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(list(archives))
        return code, out.getvalue(), err.getvalue()

    def test_the_replicates_of_both_archives_make_one_sample(self):
        code, out, _ = self.report(self.first, self.more)
        self.assertEqual(code, 0)
        # Sample 1's r1, r2 in the first archive and r3, r4 in the second: n 4, and
        # the goals count all four (the second sinks on unloading).
        self.assertIn("T2S1 (n 4)", out)
        self.assertIn("| T2S1: rebounds in every replicate (resilient settlement > 0) | 3 of 4",
                      out)
        # The span of one study's runs means nothing across two studies.
        self.assertNotIn("fits in one night", out)

    def test_a_run_given_twice_is_refused_by_its_id(self):
        code, _, err = self.report(self.first, self.first)
        self.assertEqual(code, 1)
        self.assertIn("run spheres-r1 is in", err)


if __name__ == "__main__":
    unittest.main(verbosity=2)
