#!/usr/bin/python3
"""Many load cycles in the scripts: compare.py's settlement after N cycles and slope per
decade of N with their intervals over replicates, and fig_cycles.png (scripts/
fig_cycles.py), on synthetic archives whose settlement follows a + b·log10 N exactly.

    /usr/bin/python3 tests/scripts/test_cycles_synthetic.py

Needs no build (synthetic_archive.py writes the archives with h5py; a few seconds).
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "scripts")
sys.path.insert(0, SCRIPTS)
sys.path.insert(0, HERE)

import fig_cycles  # noqa: E402
from log_fit import log_fit  # noqa: E402
from synthetic_archive import run, write_study  # noqa: E402

T2 = 4.3027  # t(0.975, 2 df)
N = np.arange(1, 101)


def log_law(first, per_decade, resilient=2e-5):
    """(trough, resilient) over 100 cycles: settlement = first + per_decade·log10 N (m)."""
    return first + per_decade * np.log10(N), np.full(len(N), resilient)


def runs():
    """Spheres settle 0.2, 0.3 and 0.4 mm per decade, Sample 1 0.05, 0.06 and 0.07;
    one run of a single cycle."""
    out = [run(f"spheres-r{k + 1}", "spheres", "spheres", k + 1,
               cycles=log_law(1e-4, (2e-4, 3e-4, 4e-4)[k])) for k in range(3)]
    out += [run(f"T2S1-r{k + 1}", "T2S1", "table2/sample1", k + 1,
                cycles=log_law(5e-5, (5e-5, 6e-5, 7e-5)[k])) for k in range(3)]
    return out + [run("T2S2-r1", "T2S2", "table2/sample2", cycles=([3e-4], [1e-5]))]


def bent_law():
    """(trough, resilient) over 100 cycles that settle 0.1 mm per decade up to cycle 10
    and 0.5 mm per decade after it (continuous at 10), rebounding 0.01 mm a cycle up to
    cycle 10 and 0.03 mm after it."""
    log_n = np.log10(N)
    trough = 1e-4 + np.where(N <= 10, 1e-4 * log_n, 1e-4 + 5e-4 * (log_n - 1.0))
    return trough, np.where(N <= 10, 1e-5, 3e-5)


def script(name, *args):
    return subprocess.run(["/usr/bin/python3", os.path.join(SCRIPTS, name), *args],
                          capture_output=True, text=True, timeout=300)


class Cycles(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.archive = write_study(os.path.join(cls.tmp.name, "cycles.h5"), runs())
        cls.plain = write_study(os.path.join(cls.tmp.name, "plain.h5"),
                                [run("spheres-r1", "spheres", "spheres")])
        cls.bent = write_study(os.path.join(cls.tmp.name, "bent.h5"),
                               [run("T2S1-r1", "T2S1", "table2/sample1", cycles=bent_law())])

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_compare_gives_the_slope_per_decade_with_its_interval(self):
        r = script("compare.py", self.archive, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        samples = {s["name"]: s["quantities"] for s in json.loads(r.stdout)["samples"]}
        slope = samples["spheres"]["settlement_log_slope_mm"]
        self.assertAlmostEqual(slope["mean"], 0.3, places=12)
        self.assertAlmostEqual(slope["sd"], 0.1, places=12)
        self.assertAlmostEqual(slope["ci95"][1] - slope["mean"], T2 * 0.1 / math.sqrt(3),
                               places=12)
        self.assertAlmostEqual(samples["T2S1"]["settlement_log_slope_mm"]["mean"], 0.06,
                               places=12)
        self.assertAlmostEqual(samples["spheres"]["permanent_settlement_first_mm"]["mean"], 0.1,
                               places=12)
        # After 100 cycles: 0.1 + 2 × 0.3 mm.
        self.assertAlmostEqual(samples["spheres"]["permanent_settlement_mm"]["mean"], 0.7,
                               places=12)
        self.assertEqual(samples["spheres"]["cycles"]["mean"], 100)
        # A single cycle has no slope to report.
        self.assertNotIn("settlement_log_slope_mm", samples["T2S2"])

    def test_compare_gives_each_decade_its_own_slope_settlement_and_rebound(self):
        r = script("compare.py", self.bent, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        q = json.loads(r.stdout)["runs"][0]["quantities"]
        value = {k: v["ours"] for k, v in q.items()}
        self.assertAlmostEqual(value["settlement_log_slope_1_10_mm"], 0.1, places=12)
        self.assertAlmostEqual(value["settlement_log_slope_10_100_mm"], 0.5, places=12)
        self.assertAlmostEqual(value["permanent_settlement_after_10_mm"], 0.2, places=12)
        self.assertAlmostEqual(value["permanent_settlement_after_100_mm"], 0.7, places=12)
        # Each decade's cycles, both ends included: cycle 10 is 0.01 mm, 11–100 are 0.03.
        self.assertAlmostEqual(value["rebound_mean_1_10_mm"], 0.01, places=12)
        self.assertAlmostEqual(value["rebound_mean_10_100_mm"], (0.01 + 90 * 0.03) / 91,
                               places=12)
        # No third decade in 100 cycles.
        self.assertNotIn("permanent_settlement_after_1000_mm", value)

    def test_a_run_of_one_cycle_has_no_cycle_rows(self):
        r = script("compare.py", self.plain)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("per decade of cycles", r.stdout)

    def test_band_and_fit(self):
        mean, half = fig_cycles.replicate_band([[1.0, 4.0], [2.0, 4.0], [3.0, 4.0]])
        np.testing.assert_allclose(mean, [2.0, 4.0])
        np.testing.assert_allclose(half, [T2 / math.sqrt(3), 0.0], atol=1e-12)
        self.assertIsNone(fig_cycles.replicate_band([[1.0, 2.0]])[1])
        a, b = log_fit(N, 0.1 + 0.3 * np.log10(N))
        self.assertAlmostEqual(a, 0.1, places=12)
        self.assertAlmostEqual(b, 0.3, places=12)

    def test_figures_draws_fig_cycles_only_where_runs_have_cycles(self):
        out = os.path.join(self.tmp.name, "figs")
        r = script("figures.py", self.archive, "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn(f"wrote {os.path.join(out, 'fig_cycles.png')}", r.stdout)
        out = os.path.join(self.tmp.name, "plain")
        r = script("figures.py", self.plain, "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("fig_cycles", r.stdout)


if __name__ == "__main__":
    unittest.main()
