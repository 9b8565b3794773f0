#!/usr/bin/python3
"""scripts/tradeoff_table.py on a synthetic study: a variant's error is the mean of its
paired differences from the reference over the replicates both have, divided by the
reference's seed-to-seed standard deviation; costs are ratios to the reference's; a
study without the reference sample is refused with exit code 2.

    /usr/bin/python3 tests/scripts/test_tradeoff_table.py
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "tradeoff_table.py")
sys.path.insert(0, HERE)

from synthetic_archive import run, write_study  # noqa: E402

SHAPE = "table2/sample1"


def runs(sample, settlements_mm, wall=12.0, balls=400, porosity=0.40):
    """One run per settlement (mm at peak), replicates 1, 2, ..."""
    return [run(f"{sample}-r{k + 1}", sample, SHAPE, k + 1, balls=balls, wall_seconds=wall,
                settlement_peak=s * 1e-3, porosity_grid=porosity + 0.01 * k)
            for k, s in enumerate(settlements_mm)]


def table(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)


class TradeoffTable(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        # Reference settlements 1.0, 1.2, 1.4 mm: sd 0.2 mm. "near" is 0.1 mm above on
        # every seed (error 0.5), "far" 0.6 mm below on its two seeds (error 3: the
        # reference's third seed is left out of the pairing), at twice the wall time and
        # half the balls. "wobbly" differs by 0.2, 0 and 0 mm.
        cls.archive = write_study(os.path.join(d, "t.h5"), runs("reference", [1.0, 1.2, 1.4])
                                  + runs("near", [1.1, 1.3, 1.5])
                                  + runs("far", [0.4, 0.6], wall=24.0, balls=200)
                                  + runs("wobbly", [1.2, 1.2, 1.4]))
        cls.out = os.path.join(d, "out")
        cls.result = table(cls.archive, "--out", cls.out, "--mark", "fast=near")
        with open(os.path.join(cls.out, "tradeoff.csv")) as f:
            cls.rows = {r["variant"]: r for r in csv.DictReader(f)}

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_error_is_the_paired_difference_over_the_reference_scatter(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        near, far = self.rows["near"], self.rows["far"]
        self.assertAlmostEqual(float(near["settlement_peak_mm_delta"]), 0.1, places=9)
        self.assertAlmostEqual(float(near["settlement_peak_mm_scatter"]), 0.2, places=9)
        self.assertAlmostEqual(float(near["settlement_peak_mm_error"]), 0.5, places=6)
        # A shift down counts as much as one up: the error is |delta| / scatter.
        self.assertAlmostEqual(float(far["settlement_peak_mm_delta"]), -0.6, places=9)
        self.assertAlmostEqual(float(far["settlement_peak_mm_error"]), 3.0, places=6)
        # Equal values on every seed: no scatter, so no error rather than a division by 0.
        self.assertEqual(near["rotation_loading_mean_deg_error"], "")
        # The reference against itself: no difference at all.
        self.assertAlmostEqual(float(self.rows["reference"]["settlement_peak_mm_error"]), 0.0)

    def test_noise_is_the_standard_error_of_the_paired_differences(self):
        wobbly = self.rows["wobbly"]
        self.assertAlmostEqual(float(wobbly["settlement_peak_mm_delta"]), 0.2 / 3, places=6)
        # sd of (0.2, 0, 0) is 0.2 / sqrt(3); over sqrt(3) seeds and the 0.2 mm scatter: 1/3.
        self.assertAlmostEqual(float(wobbly["settlement_peak_mm_noise"]), 1 / 3, places=6)
        self.assertAlmostEqual(float(self.rows["near"]["settlement_peak_mm_noise"]), 0.0, places=9)

    def test_pooled_scatter_pools_every_samples_variance(self):
        # Settlement sds: reference 0.2 (2 df), near 0.2 (2), far 0.1414 (1), wobbly
        # 0.1155 (2): pooled variance (2*0.04 + 2*0.04 + 0.02 + 2*0.01333) / 7.
        out = os.path.join(self.tmp.name, "pooled_scatter")
        r = table(self.archive, "--out", out, "--scatter", "pooled")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "tradeoff.csv")) as f:
            near = {row["variant"]: row for row in csv.DictReader(f)}["near"]
        pooled = ((2 * 0.04 + 2 * 0.04 + 0.02 + 2 * 0.04 / 3) / 7) ** 0.5
        self.assertAlmostEqual(float(near["settlement_peak_mm_scatter"]), pooled, places=5)
        self.assertAlmostEqual(float(near["settlement_peak_mm_error"]), 0.1 / pooled, places=4)

    def test_costs_are_ratios_to_the_reference(self):
        far = self.rows["far"]
        self.assertAlmostEqual(float(far["wall_vs_ref"]), 2.0, places=9)
        # Same steps per run (two stages of 1000), half the balls.
        self.assertAlmostEqual(float(far["ball_steps_vs_ref"]), 0.5, places=9)
        self.assertEqual(far["runs"], "2")

    def test_markdown_and_plot_are_written(self):
        with open(os.path.join(self.out, "tradeoff.md")) as f:
            md = f.read()
        self.assertIn("| near | 3 | 1.00 | 1.00 |", md)
        self.assertTrue(os.path.getsize(os.path.join(self.out, "pareto.png")) > 1000)

    def test_labels_of_nearby_points_do_not_overlap(self):
        # Three variants a hair apart in cost and error, as frequency-10 and balanced
        # were in the full-scale spheres' plot: every drawn label must clear the others.
        sys.path.insert(0, os.path.dirname(SCRIPT))
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from tradeoff_table import place_labels
        fig, ax = plt.subplots(figsize=(7.5, 5))
        xy = [(0.70, 30.0), (0.72, 31.0), (0.71, 29.5), (0.30, 60.0)]
        ax.scatter(*zip(*xy))
        ax.set_xscale("log")
        ax.set_yscale("log")
        place_labels(ax, [(p, f"variant-{k}") for k, p in enumerate(xy)])
        fig.canvas.draw()
        boxes = [t.get_window_extent() for t in ax.texts]
        plt.close(fig)
        self.assertEqual(len(boxes), 4)
        for i in range(4):
            for j in range(i + 1, 4):
                self.assertFalse(boxes[i].overlaps(boxes[j]), (i, j, boxes[i], boxes[j]))

    def test_a_label_clears_the_hollow_markers_it_is_given(self):
        # A hollow marker (another variant's error in the other scatter) where a label
        # would go, as mass_scale-10's was under mass_scale-10_frequency-10's label in
        # the full-scale plot: given as an obstacle, the label moves off it.
        sys.path.insert(0, os.path.dirname(SCRIPT))
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from tradeoff_table import place_labels

        def label_box(obstacles):
            fig, ax = plt.subplots(figsize=(7.5, 5))
            ax.scatter([0.3, 0.9], [1.0, 60.0])
            ax.set_xscale("log")
            ax.set_yscale("log")
            x0, y0 = ax.transData.transform((0.5, 10.0))
            marker = (x0 + 30, y0 + 8)  # display pixels: on the label's first place
            hollow = tuple(ax.transData.inverted().transform(marker))
            place_labels(ax, [((0.5, 10.0), "a-long-variant-name")],
                         [hollow] if obstacles else [])
            fig.canvas.draw()
            box, half = ax.texts[0].get_window_extent(), 4 * fig.dpi / 72.0
            plt.close(fig)
            mx, my = marker
            return box.x0 < mx + half and mx - half < box.x1 and box.y0 < my + half and \
                my - half < box.y1

        self.assertTrue(label_box(obstacles=False), "the test's marker is not in the way")
        self.assertFalse(label_box(obstacles=True))

    def test_archives_pool_their_samples_and_refuse_a_sample_twice(self):
        extra = write_study(os.path.join(self.tmp.name, "extra.h5"), runs("late", [1.4, 1.6]))
        out = os.path.join(self.tmp.name, "pooled")
        r = table(self.archive, extra, "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "tradeoff.csv")) as f:
            late = {row["variant"]: row for row in csv.DictReader(f)}["late"]
        self.assertAlmostEqual(float(late["settlement_peak_mm_delta"]), 0.4, places=6)
        r = table(self.archive, self.archive)
        self.assertEqual(r.returncode, 2)
        self.assertIn("sample 'reference' is also in", r.stderr)

    def test_a_study_without_the_reference_is_refused(self):
        r = table(self.archive, "--reference", "baseline")
        self.assertEqual(r.returncode, 2)
        self.assertIn("no sample named 'baseline'", r.stderr)
        self.assertIn("reference, near, far, wobbly", r.stderr)


if __name__ == "__main__":
    unittest.main()
