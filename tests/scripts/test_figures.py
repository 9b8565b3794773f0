#!/usr/bin/python3
"""scripts/figures.py and scripts/compare.py end to end, on archives made for the test.

Run by ctest with the path of the ballast binary as the only argument:
    /usr/bin/python3 tests/scripts/test_figures.py build/study/ballast

Two tiny box tests (50 spheres, 50 Table 2 Sample 1 clumps in a 200 x 100 mm box,
softer balls so that they settle in few steps: about 10 s together), one single-run
file each, and a study archive assembled from them with h5py (study_fixture.py) with a
third run recorded as failed.
"""
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
SCRIPTS = os.path.join(ROOT, "scripts")
sys.path.insert(0, SCRIPTS)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "cli"))

import binary  # noqa: E402
import fig_displacements  # noqa: E402
import fig_rotations  # noqa: E402
from ballast_archive import open_archive  # noqa: E402
from study_fixture import make_study  # noqa: E402

# 50 particles, softer balls and walls (dt 2 µs instead of 0.6 µs), a 3 kN pulse.
TINY = ["--set", "/particles/count=50", "--set", "/box/length=0.2", "--set", "/box/width=0.1",
        "--set", "/sleeper/length=0.08", "--set", "/sleeper/preload=300",
        "--set", "/sleeper/peak_load=3000", "--set", "/preparation/max_stage_steps=100000",
        "--set", "/materials/ball_stiffness=5.08e8", "--set", "/materials/wall_stiffness=5.08e8"]


def script(name, *args):
    return subprocess.run(["/usr/bin/python3", os.path.join(SCRIPTS, name), *args],
                          capture_output=True, text=True, timeout=300)


def with_zones(path, names):
    """`names` and fig_zones.png when the archive's runs hold zones/ (newer archives)."""
    with h5py.File(path, "r") as f:
        groups = [f["run"]] if "run" in f else list(f["runs"].values())
        return set(names) | ({"fig_zones.png"} if any("zones" in g for g in groups) else set())


def written(result):
    """The file names a figures.py run reports, one per 'wrote PATH' line."""
    return {os.path.basename(line.split(" ", 1)[1]) for line in result.stdout.splitlines()
            if line.startswith("wrote ")}


class Figures(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        cls.spheres = os.path.join(d, "spheres.h5")
        cls.clumps = os.path.join(d, "t2s1.h5")
        cls.templates = os.path.join(d, "templates.h5")
        cls.study = os.path.join(d, "study.h5")
        scene = os.path.join(ROOT, "cases", "box_test", "smoke.json")
        for path, extra in ((cls.spheres, []),
                            (cls.clumps, ["--set", "/particles/shape=table2/sample1"])):
            binary.succeed("run", scene, *TINY, *extra, "--threads", "1", "-o", path)
        binary.succeed("clump", "--preset", "table2/sample1", "--count", "50", "--seed", "1",
                       "-o", cls.templates)
        with h5py.File(cls.spheres, "r") as f:
            base_scene = f.attrs["scene_json"]
        make_study(cls.study, base_scene, [
            {"id": "spheres-r1", "run_file": cls.spheres, "sample": "spheres",
             "params": {"shape": "spheres"}},
            {"id": "T2S1-r1", "run_file": cls.clumps, "sample": "T2S1",
             "params": {"shape": "table2/sample1"}, "templates": cls.templates},
        ], failed=[{"id": "broken-r1", "sample": "broken", "params": {"shape": "spheres"},
                    "message": "body 12 left the box at step 345"}])

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def out_dir(self, name):
        return os.path.join(self.tmp.name, name)

    def assert_png(self, path):
        """A real PNG of a readable size, neither blank nor solid."""
        with open(path, "rb") as f:
            head = f.read(24)
        self.assertEqual(head[:8], b"\x89PNG\r\n\x1a\n", path)
        width, height = struct.unpack(">II", head[16:24])
        self.assertTrue(500 <= width <= 6000 and 300 <= height <= 4000, (path, width, height))
        import matplotlib.pyplot as plt
        grey = plt.imread(path)[:, :, :3].mean(axis=2)
        dark = float((grey < 0.5).mean())
        self.assertTrue(0.002 < dark < 0.6, (path, dark))

    def expect_fig17(self):
        """Fig. 17 is drawn when the clump run alone would be drawn at a larger 1-2-5
        factor (its largest vector up to 40 mm) than the common one of Fig. 16."""
        def largest(path):
            with h5py.File(path, "r") as f:
                a = f["run"].attrs
                return 1e3 * max(a["max_displacement_peak"], a["max_displacement_after"])

        def factor(mm):
            return max([m * 10.0 ** k for k in range(0, 8) for m in (1, 2, 5)
                        if m * 10.0 ** k <= 40.0 / mm] + [1.0])

        return factor(largest(self.clumps)) > factor(max(largest(self.spheres),
                                                         largest(self.clumps)))

    def test_single_sphere_run_gives_figures_10_11_13_15_18(self):
        r = script("figures.py", self.spheres, "--out", self.out_dir("single"))
        self.assertEqual(r.returncode, 0, r.stderr)
        names = written(r)
        self.assertEqual(names, with_zones(self.spheres, {
            "fig10_contacts_before.png", "fig11_contacts_smoke-spheres.png",
            "fig13_rotations_smoke-spheres.png", "fig15_displacements_smoke-spheres.png",
            "fig18_load_deformation.png"}))
        for n in names:
            self.assert_png(os.path.join(self.out_dir("single"), n))

    def test_single_clump_run_draws_fig7_from_its_own_templates(self):
        r = script("figures.py", self.clumps, "--out", self.out_dir("clump"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("holds no clump templates", r.stderr)
        # Alone, the clump run sets the common scale itself: Fig. 17 would repeat Fig. 16.
        self.assertIn("Fig. 17 of run 'smoke-table2_sample1' left out: its displacements set",
                      r.stderr)
        self.assertEqual(written(r), with_zones(self.clumps, {
            "fig07_clumps.png", "fig10_contacts_before.png",
            "fig12_contacts_smoke-table2_sample1.png", "fig14_rotations_smoke-table2_sample1.png",
            "fig16_displacements_smoke-table2_sample1.png", "fig18_load_deformation.png"}))

    def test_study_gives_every_figure_and_skips_the_failed_run(self):
        out = self.out_dir("study")
        r = script("figures.py", self.study, "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("skipping run 'broken-r1': status failed (body 12 left the box", r.stderr)
        expected = with_zones(self.study, {
            "fig07_clumps.png", "fig10_contacts_before.png", "fig11_contacts_spheres-r1.png",
            "fig12_contacts_T2S1-r1.png", "fig13_rotations_spheres-r1.png",
            "fig14_rotations_T2S1-r1.png", "fig15_displacements_spheres-r1.png",
            "fig16_displacements_T2S1-r1.png", "fig18_load_deformation.png"})
        if self.expect_fig17():
            expected.add("fig17_displacements_T2S1-r1.png")
        self.assertEqual(written(r), expected)
        self.assertEqual(set(os.listdir(out)), expected)
        for n in expected:
            self.assert_png(os.path.join(out, n))

    def test_runs_option_draws_only_the_named_runs(self):
        r = script("figures.py", self.study, "--out", self.out_dir("one"), "--runs", "T2S1-r1")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("broken-r1", r.stderr)  # not asked for, so not reported
        self.assertTrue(all("spheres" not in n for n in written(r)), written(r))
        self.assertIn("fig12_contacts_T2S1-r1.png", written(r))
        r = script("figures.py", self.study, "--out", self.out_dir("none"), "--runs", "nope")
        self.assertEqual(r.returncode, 1)
        self.assertIn("no run 'nope' (runs: spheres-r1, T2S1-r1, broken-r1)", r.stderr)
        self.assertFalse(os.path.exists(self.out_dir("none")))

    def test_compare_prints_the_archive_numbers_beside_the_paper(self):
        r = script("compare.py", self.study, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        table = {run["id"]: run for run in json.loads(r.stdout)["runs"]}
        self.assertEqual(set(table), {"spheres-r1", "T2S1-r1"})
        self.assertEqual(table["spheres-r1"]["paper_sample"], "spheres")
        self.assertEqual(table["T2S1-r1"]["paper_sample"], "sample1")
        with h5py.File(self.study, "r") as f:
            for run_id, run in table.items():
                a, q = f["runs"][run_id].attrs, run["quantities"]
                self.assertEqual(q["porosity_grid"]["ours"], a["porosity_grid"])
                for stage in ("before", "peak", "after"):
                    c = f["runs"][run_id]["contacts"][stage].attrs
                    self.assertEqual(q[f"contacts_{stage}_count"]["ours"],
                                     c["ball_contacts"] + c["wall_contacts"])
                    self.assertEqual(q[f"contacts_{stage}_max_force_N"]["ours"], c["max_force"])
                    self.assertEqual(q[f"contacts_{stage}_mean_force_N"]["ours"], c["mean_force"])
                for phase in ("loading", "unloading", "cycle"):
                    for s in ("mean", "max"):
                        key = f"rotation_{phase}_{s}_deg"
                        self.assertEqual(q[key]["ours"], a[key])
                for key, attr in (("max_displacement_peak_mm", "max_displacement_peak"),
                                  ("max_displacement_after_mm", "max_displacement_after"),
                                  ("settlement_peak_mm", "settlement_peak"),
                                  ("permanent_settlement_mm", "permanent_settlement")):
                    self.assertTrue(math.isclose(q[key]["ours"], 1e3 * a[attr], rel_tol=1e-12))
        # The paper's numbers: porosity 0.37 / 0.35, Fig. 12b's 4,233 N, Fig. 14a's 0.061°.
        self.assertEqual(table["spheres-r1"]["quantities"]["porosity_grid"]["paper"], 0.37)
        t2 = table["T2S1-r1"]["quantities"]
        self.assertEqual(t2["porosity_grid"]["paper"], 0.35)
        self.assertEqual(t2["contacts_peak_max_force_N"]["paper"], 4233)
        self.assertEqual(t2["rotation_loading_mean_deg"]["paper"], 0.061)
        self.assertIsNone(t2["settlement_peak_mm"]["paper"])
        # The text table shows the same numbers, rounded; these tiny runs are not at the
        # paper's scale, so it says so and sets no paper numbers beside them.
        self.assertFalse(table["T2S1-r1"]["at_paper_scale"])
        r = script("compare.py", self.study)
        self.assertEqual(r.returncode, 0, r.stderr)
        porosity = table["T2S1-r1"]["quantities"]["porosity_grid"]["ours"]
        self.assertIn("| porosity, 5 mm grid under the sleeper | ", r.stdout)
        self.assertIn(f" {porosity:.3f} |", r.stdout)
        self.assertNotIn("(0.35)", r.stdout)
        self.assertIn("NOT comparable with the paper's numbers", r.stdout)
        self.assertIn("| quantity | spheres-r1 | T2S1-r1 |", r.stdout)

    def test_a_file_that_is_not_an_archive_is_refused_clearly(self):
        text = os.path.join(self.tmp.name, "notes.h5")
        with open(text, "w") as f:
            f.write("not HDF5\n")
        cases = ((text, "not a ballast archive: not an HDF5 file"),
                 (self.templates, "not a ballast archive: root attribute format = "
                                  "'ballast-clumps'"),
                 (os.path.join(self.tmp.name, "missing.h5"), "no such file"))
        for path, message in cases:
            for name in ("figures.py", "compare.py"):
                with self.subTest(path=os.path.basename(path), script=name):
                    args = ["--out", self.out_dir("refused")] if name == "figures.py" else []
                    r = script(name, path, *args)
                    self.assertEqual(r.returncode, 1)
                    self.assertIn(f"{path}: {message}", r.stderr)
                    self.assertFalse(os.path.exists(self.out_dir("refused")))

    def test_a_damaged_run_loses_only_the_figures_that_need_the_missing_data(self):
        damaged = os.path.join(self.tmp.name, "damaged.h5")
        with h5py.File(self.clumps, "r") as f:
            scene = f.attrs["scene_json"]
        make_study(damaged, scene, [{"id": "T2S1-r1", "run_file": self.clumps, "sample": "T2S1",
                                     "params": {"shape": "table2/sample1"}}])
        with h5py.File(damaged, "a") as f:
            del f["runs/T2S1-r1/particles/rotation_unloading"]
        r = script("figures.py", damaged, "--out", self.out_dir("damaged"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("Figs 13-14 of run 'T2S1-r1' not drawn: " + damaged
                      + ": run 'T2S1-r1' has no dataset particles/rotation_unloading", r.stderr)
        self.assertNotIn("fig14_rotations_T2S1-r1.png", written(r))
        self.assertIn("fig12_contacts_T2S1-r1.png", written(r))
        self.assertIn("fig18_load_deformation.png", written(r))

    def test_study_displacements_equal_the_single_run_positions(self):
        with open_archive(self.study) as study, open_archive(self.clumps) as single:
            for stage in ("peak", "end"):
                np.testing.assert_array_equal(study.run("T2S1-r1").displacement(stage),
                                              single.runs()[0].displacement(stage))
            self.assertTrue(study.run("T2S1-r1").is_clumps)
            self.assertFalse(study.run("spheres-r1").is_clumps)


class Scales(unittest.TestCase):
    def test_rotation_classes_follow_the_paper(self):
        # Spheres: grey 10°-20° inclusive, black above 20° (Figs 13-14).
        c = fig_rotations.rotation_classes(np.array([9.99, 10.0, 20.0, 20.01]), 10.0, 20.0)
        self.assertEqual([list(c[k]) for k in ("open", "grey", "black")], [[0], [1, 2], [3]])

    def test_common_displacement_scale_draws_the_largest_vector_near_40_mm(self):
        for largest_mm in (0.013, 0.26, 0.88, 8.25, 11.79):
            factor = fig_displacements.nice_factor(40.0 / largest_mm)
            drawn = largest_mm * factor
            # A 1-2-5 factor below the ideal one draws between 40/2.5 = 16 and 40 mm.
            self.assertTrue(16.0 - 1e-9 <= drawn <= 40.0 + 1e-9, (largest_mm, factor))
        self.assertEqual(fig_displacements.nice_below(0.037), 0.02)
        self.assertEqual(fig_displacements.nice_below(50.0), 50.0)
        self.assertEqual(fig_displacements.nice_factor(0.5), 1.0)


if __name__ == "__main__":
    binary.main()
