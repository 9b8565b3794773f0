#!/usr/bin/python3
"""scripts/trials.py on synthetic run archives: each row carries the run's own values
in the table's units, how its seating ended, and a bad argument or a study archive is
refused with exit code 2 and a message naming it.

    /usr/bin/python3 tests/scripts/test_trials.py
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "trials.py")
sys.path.insert(0, HERE)

from synthetic_archive import FULL, run, write_single, write_study  # noqa: E402


def trials(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)


class TrialsTable(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        cls.ref = write_single(os.path.join(d, "ref.h5"), run(
            "ref", "spheres", "spheres", rotation_loading_mean_deg=0.85,
            resilient_settlement=-1.3e-4, settlement_peak=5.9e-4), scene=FULL)
        cls.free = write_single(os.path.join(d, "free.h5"), run(
            "free", "spheres", "spheres", seating="steady creep", rotation_loading_mean_deg=2.4,
            resilient_settlement=2.0e-5, settlement_peak=2.7e-3), scene=FULL)
        cls.study = write_study(os.path.join(d, "study.h5"), [
            run("a-r1", "a", "spheres"), run("a-r2", "a", "spheres", 2)])

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_rows_hold_each_runs_values_in_the_tables_units(self):
        out = os.path.join(self.tmp.name, "t.csv")
        r = trials(f"ref={self.ref}", f"free top={self.free}", "--csv", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stdout.splitlines()
        self.assertEqual(len(lines), 4)  # header, rule, two rows in the order given
        self.assertTrue(lines[2].startswith("| ref | equilibrium (0.0045) |"))
        self.assertTrue(lines[3].startswith("| free top | steady creep (0.0045) |"))
        with open(out) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual([r["trial"] for r in rows], ["ref", "free top"])
        # Settlements in mm, signs kept: a sleeper that sinks on unloading is negative.
        self.assertAlmostEqual(float(rows[0]["resilient_settlement_mm"]), -0.13, places=9)
        self.assertAlmostEqual(float(rows[1]["resilient_settlement_mm"]), 0.02, places=9)
        self.assertAlmostEqual(float(rows[1]["settlement_peak_mm"]), 2.7, places=9)
        self.assertAlmostEqual(float(rows[0]["rotation_loading_mean_deg"]), 0.85, places=12)
        # The CSV keeps the archive's units under the archive's names: N, not kN.
        force = float(rows[0]["contacts_peak_max_force_N"])
        self.assertGreater(force, 10.0)
        cell = lines[2].split("|")[5].strip()
        self.assertAlmostEqual(float(cell), force * 1e-3, delta=0.051)

    def test_bad_arguments_are_refused_with_their_name(self):
        r = trials("no-equals-sign")
        self.assertEqual(r.returncode, 2)
        self.assertIn("'no-equals-sign': expected LABEL=RUN.h5", r.stderr)
        missing = os.path.join(self.tmp.name, "missing.h5")
        r = trials(f"x={missing}")
        self.assertEqual(r.returncode, 2)
        self.assertIn("missing.h5", r.stderr)
        r = trials(f"study={self.study}")
        self.assertEqual(r.returncode, 2)
        self.assertIn("2 runs with status ok; a trial is one run", r.stderr)


if __name__ == "__main__":
    unittest.main(verbosity=2)
