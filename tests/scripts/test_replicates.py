#!/usr/bin/python3
"""scripts/replicates.py: t quantiles, the interval of a mean, the delta-method interval
of a ratio of means, and the grouping of runs into samples.

    /usr/bin/python3 tests/scripts/test_replicates.py

Needs no build: the archives are synthetic (synthetic_archive.py), the numbers are
textbook values, hand calculations and a seeded Monte Carlo.
"""
import math
import os
import sys
import tempfile
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
sys.path.insert(0, HERE)

import replicates  # noqa: E402
from ballast_archive import open_archive  # noqa: E402
from replicates import (Summary, group_runs, ratio_of_means, sphere_clump_pairs,  # noqa: E402
                        summarize, t975, verdict)
from synthetic_archive import run, write_study  # noqa: E402


def t_cdf(q, df, points=20001):
    """P(T <= q) for Student's t by Simpson's rule on its density over [0, q]."""
    x = np.linspace(0.0, q, points)
    c = math.gamma((df + 1) / 2) / (math.sqrt(df * math.pi) * math.gamma(df / 2))
    y = c * (1.0 + x * x / df) ** (-(df + 1) / 2)
    h = x[1] - x[0]
    return 0.5 + h / 3 * (y[0] + y[-1] + 4 * y[1:-1:2].sum() + 2 * y[2:-1:2].sum())


class Quantiles(unittest.TestCase):
    def test_known_values(self):
        for df, q in ((1, 12.706), (2, 4.303), (4, 2.776), (10, 2.228), (30, 2.042)):
            self.assertAlmostEqual(t975(df), q, places=3)

    def test_every_tabulated_quantile_leaves_2_5_percent_in_the_tail(self):
        for df in range(1, 31):
            with self.subTest(df=df):
                self.assertAlmostEqual(t_cdf(t975(df), df), 0.975, delta=1e-5)

    def test_fractional_df_rounds_down_and_large_df_is_normal(self):
        self.assertEqual(t975(2.94), t975(2))
        self.assertEqual(t975(31), 1.96)
        self.assertEqual(t975(1000), 1.96)
        with self.assertRaises(ValueError):
            t975(0.5)


class MeanInterval(unittest.TestCase):
    def test_textbook_sample(self):
        s = summarize([1, 2, 3, 4, 5])
        self.assertEqual((s.n, s.df), (5, 4))
        self.assertAlmostEqual(s.mean, 3.0)
        self.assertAlmostEqual(s.sd, 1.5811, places=4)
        self.assertAlmostEqual(s.half_width, 2.776 * 1.5811 / math.sqrt(5), places=3)
        self.assertAlmostEqual(s.low, 1.037, places=3)
        self.assertAlmostEqual(s.high, 4.963, places=3)

    def test_one_value_gives_no_interval_and_says_so(self):
        s = summarize([0.064])
        self.assertEqual((s.n, s.mean), (1, 0.064))
        self.assertIsNone(s.sd)
        self.assertIsNone(s.low)
        self.assertIsNone(s.high)
        self.assertIn("no interval", s.note)
        self.assertIsNone(s.as_json()["ci95"])

    def test_missing_values_are_not_counted(self):
        s = summarize([None, 2.0, float("nan"), 4.0])
        self.assertEqual(s.n, 2)
        self.assertAlmostEqual(s.mean, 3.0)
        empty = summarize([None])
        self.assertEqual((empty.n, empty.mean), (0, None))

    def test_equal_values_have_no_spread(self):
        s = summarize([0.1 - 0.3, 0.1 - 0.3, 0.1 - 0.3])
        self.assertEqual((s.sd, s.half_width), (0.0, 0.0))


class RatioInterval(unittest.TestCase):
    def test_hand_calculation(self):
        # m1 5, s1 1, m2 2, s2 0.2, n 3 each: a = 1/75, b = 1/300, var = 1/60,
        # df = (1/60)^2 / ((1/75)^2/2 + (1/300)^2/2) = 50/17 = 2.94 -> 2, t 4.3027,
        # R = 2.5, exp(4.3027 sqrt(1/60)) = exp(0.55548) = 1.74277, interval [1.4345, 4.3569].
        r = ratio_of_means(summarize([4, 5, 6]), summarize([1.8, 2.0, 2.2]))
        self.assertAlmostEqual(r.value, 2.5)
        self.assertEqual(r.df, 2)
        self.assertAlmostEqual(r.low, 1.4345, places=4)
        self.assertAlmostEqual(r.high, 4.3569, places=4)
        self.assertAlmostEqual(r.low * r.high, r.value ** 2)  # symmetric in ln R

    def test_delta_method_variance_matches_monte_carlo(self):
        rng = np.random.default_rng(7)
        mu1, sd1, n1, mu2, sd2, n2 = 5.18, 0.5, 4, 0.061, 0.008, 6
        m1 = rng.normal(mu1, sd1, (200000, n1)).mean(axis=1)
        m2 = rng.normal(mu2, sd2, (200000, n2)).mean(axis=1)
        predicted = sd1 ** 2 / (n1 * mu1 ** 2) + sd2 ** 2 / (n2 * mu2 ** 2)
        self.assertAlmostEqual(np.log(m1 / m2).var() / predicted, 1.0, delta=0.03)

    def test_interval_covers_the_true_ratio_about_95_percent_of_the_time(self):
        rng = np.random.default_rng(2007)
        mu1, mu2, trials = 7.25, 0.062, 4000
        covered = 0
        for _ in range(trials):
            r = ratio_of_means(summarize(rng.normal(mu1, 0.7, 5)),
                               summarize(rng.normal(mu2, 0.006, 5)))
            covered += r.low <= mu1 / mu2 <= r.high
        # Rounding Welch's df down makes it slightly conservative.
        self.assertTrue(0.93 <= covered / trials <= 0.985, covered / trials)

    def test_zero_or_missing_mean_gives_no_ratio_or_no_interval(self):
        zero = ratio_of_means(summarize([1.0, 2.0]), summarize([-1.0, 1.0]))
        self.assertIsNone(zero.value)
        self.assertIsNone(zero.low)
        self.assertIn("0", zero.note)
        missing = ratio_of_means(summarize([1.0, 2.0]), Summary(0, None))
        self.assertIsNone(missing.value)
        self.assertIsNone(missing.low)
        top_zero = ratio_of_means(summarize([-1.0, 1.0]), summarize([1.0, 2.0]))
        self.assertEqual(top_zero.value, 0.0)
        self.assertIsNone(top_zero.low)
        single = ratio_of_means(summarize([4.0]), summarize([1.0, 2.0]))
        self.assertAlmostEqual(single.value, 4.0 / 1.5)
        self.assertIsNone(single.low)
        self.assertIn("no interval", single.note)

    def test_identical_replicates_give_a_zero_width_interval(self):
        r = ratio_of_means(summarize([2.0, 2.0]), summarize([1.0, 1.0]))
        self.assertEqual((r.value, r.low, r.high, r.df), (2.0, 2.0, 2.0, 2))

    def test_verdict_words(self):
        self.assertEqual(verdict(10.0, 20.0, 85.0), "below the paper's")
        self.assertEqual(verdict(90.0, 120.0, 85.0), "above the paper's")
        self.assertEqual(verdict(60.0, 120.0, 85.0), "consistent")
        self.assertIsNone(verdict(None, None, 85.0))
        self.assertIsNone(verdict(60.0, 120.0, None))


class Grouping(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def test_replicates_of_a_sample_form_one_group(self):
        path = write_study(os.path.join(self.tmp.name, "s.h5"), [
            run("spheres-r1", "spheres", "spheres", 1), run("T2S1-r1", "T2S1", "table2/sample1", 1),
            run("spheres-r2", "spheres", "spheres", 2), run("T2S1-r2", "T2S1", "table2/sample1", 2),
            run("T2S2-r1", "T2S2", "table2/sample2", 1)])
        with open_archive(path) as a:
            groups = group_runs(a.select())
            self.assertEqual([(g.name, [r.id for r in g.runs]) for g in groups],
                             [("spheres", ["spheres-r1", "spheres-r2"]),
                              ("T2S1", ["T2S1-r1", "T2S1-r2"]), ("T2S2", ["T2S2-r1"])])
            self.assertEqual([(s.name, c.name) for s, c in sphere_clump_pairs(groups)],
                             [("spheres", "T2S1"), ("spheres", "T2S2")])

    def test_runs_with_other_parameters_are_not_replicates(self):
        import h5py
        path = write_study(os.path.join(self.tmp.name, "axes.h5"), [
            run(f"spheres-dt_safety={dt}-r{k}", "spheres", "spheres", k)
            for dt in (0.8, 0.4) for k in (1, 2)])
        with h5py.File(path, "a") as f:
            for name, g in f["runs"].items():
                dt = name.split("=")[1].split("-")[0]
                g.attrs["params"] = f'{{"dt_safety":{dt},"shape":"spheres"}}'
        with open_archive(path) as a:
            groups = group_runs(a.select())
        self.assertEqual([(g.name, len(g.runs)) for g in groups],
                         [("spheres-dt_safety=0.8", 2), ("spheres-dt_safety=0.4", 2)])

    def test_ordered_union_keeps_first_seen_order(self):
        self.assertEqual(replicates.ordered_union([{"b": 1, "a": 2}, ["c", "a"], {"d": 0}]),
                         ["b", "a", "c", "d"])


if __name__ == "__main__":
    unittest.main()
