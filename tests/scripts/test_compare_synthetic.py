#!/usr/bin/python3
"""scripts/compare.py and scripts/figures.py (fig_zones) on synthetic archives: samples
with replicates, the paper's scale and a smoke scale, the newer archive fields and the
older layout without them, and a single-run file.

    /usr/bin/python3 tests/scripts/test_compare_synthetic.py

Needs no build: the archives are written with h5py by synthetic_archive.py (a few
seconds of drawing in all).
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
SCRIPTS = os.path.join(HERE, "..", "..", "scripts")
sys.path.insert(0, SCRIPTS)
sys.path.insert(0, HERE)

from ballast_archive import open_archive  # noqa: E402
from fig_zones import zone_figure  # noqa: E402
from largest_rotations import turn_cosines  # noqa: E402
from synthetic_archive import FULL, run, write_single, write_study  # noqa: E402

T2 = 4.3027  # t(0.975, 2 df)


def smoke_runs():
    """3 sphere and 3 Sample 1 replicates, one Sample 2 run. Spheres beside the sleeper go
    up at peak and (unlike the paper) down on unloading; Sample 1 beneath goes down at
    peak and its change on unloading straddles 0."""
    runs = []
    for k in range(3):
        runs.append(run(f"spheres-r{k + 1}", "spheres", "spheres", k + 1,
                        rotation_loading_mean_deg=0.70 + 0.05 * k,
                        zones={"beneath": (-5e-4, -4e-4),
                               "beside": (2e-4 + 1e-5 * k, (1.5e-4, 1.6e-4, 1.8e-4)[k])}))
    for k in range(3):
        runs.append(run(f"T2S1-r{k + 1}", "T2S1", "table2/sample1", k + 1,
                        rotation_loading_mean_deg=0.060 + 0.005 * k,
                        zones={"beneath": (-1e-4 - 1e-5 * k, (-1.2e-4, -1.0e-4, -1.0e-4)[k]),
                               "beside": (1e-5 * (k - 1), 2e-5)}))
    return runs + [run("T2S2-r1", "T2S2", "table2/sample2")]


def full_runs():
    """Two replicates each of the spheres and Sample 1 at the paper's scale."""
    return [run(f"{name}-r{k + 1}", name, shape, k + 1, bodies=1936,
                rotation_loading_mean_deg=rotation[k], max_displacement_peak=displacement[k])
            for name, shape, rotation, displacement in (
                ("spheres", "spheres", (5.0, 5.2), (3.0e-3, 3.2e-3)),
                ("T2S1", "table2/sample1", (0.061, 0.062), (2.0e-3, 2.1e-3)))
            for k in range(2)]


def script(name, *args):
    return subprocess.run(["/usr/bin/python3", os.path.join(SCRIPTS, name), *args],
                          capture_output=True, text=True, timeout=300)


def is_png(path):
    with open(path, "rb") as f:
        head = f.read(24)
    width, height = struct.unpack(">II", head[16:24])
    return head[:8] == b"\x89PNG\r\n\x1a\n" and width >= 500 and height >= 300


class TurnCosines(unittest.TestCase):
    def test_the_cosine_from_three_angles_is_that_of_the_vectors(self):
        rng = np.random.default_rng(7)
        l, u = rng.normal(size=(50, 3)), rng.normal(size=(50, 3))
        u[0] = -0.3 * l[0]  # turned straight back
        u[1] = 2.0 * l[1]  # went on the same way
        cos = turn_cosines(np.linalg.norm(l, axis=1), np.linalg.norm(u, axis=1),
                           np.linalg.norm(l + u, axis=1))
        expected = np.sum(l * u, axis=1) / (np.linalg.norm(l, axis=1) * np.linalg.norm(u, axis=1))
        np.testing.assert_allclose(cos, expected, atol=1e-9)
        self.assertAlmostEqual(cos[0], -1.0)
        self.assertAlmostEqual(cos[1], 1.0)

    def test_a_particle_that_did_not_turn_has_no_cosine(self):
        cos = turn_cosines([0.0, 1.0], [1.0, 0.0], [1.0, 1.0])
        self.assertTrue(np.all(np.isnan(cos)))


class Compare(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        cls.new = write_study(os.path.join(d, "new.h5"), smoke_runs(), failed=["broken-r1"])
        cls.old = write_study(os.path.join(d, "old.h5"), smoke_runs(), new_fields=False)
        cls.full = write_study(os.path.join(d, "full.h5"), full_runs(), scene=FULL)
        cls.single = write_single(os.path.join(d, "single.h5"), run("x", "", "spheres"))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def compare(self, path, *args):
        r = script("compare.py", path, *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        return json.loads(r.stdout) if "--json" in args else r.stdout

    def test_reduced_scale_is_said_and_the_paper_is_left_out(self):
        out = self.compare(self.new)
        self.assertIn("- spheres (3 runs): 40 bodies, 40 balls, peak load 10 kN", out)
        self.assertIn("- T2S2 (1 run): 40 bodies, 400 balls, peak load 10 kN", out)
        self.assertIn("**spheres, T2S1, T2S2: smoke/reduced-scale results (40 bodies < 1,500; "
                      "peak load 10 kN, not 40; box 350 mm long, not 700), NOT comparable with "
                      "the paper's numbers**", out)
        self.assertIn("cases/paper_study.json", out)
        for paper in ("(0.37)", "[0.37]", "(5.18)", "[0.061]", "10,337", "282,955"):
            self.assertNotIn(paper, out)
        self.assertIn("| spheres / T2S1 | 11.5 | 9.57–13.9 | — | not comparable: not the "
                      "paper's scale |", out)

    def test_replicates_table_reads_mean_half_width_sd_n(self):
        out = self.compare(self.new)
        self.assertIn("| rotation, loading: mean (°) | 0.75 ± 0.124 (sd 0.05, n 3) | "
                      "0.065 ± 0.0124 (sd 0.005, n 3) | 0.5 (n 1, no interval) |", out)
        self.assertIn("| zone beneath the sleeper: particles | 12 ± 0 (sd 0, n 3) |", out)

    def test_directions_agree_disagree_or_are_not_resolved(self):
        out = self.compare(self.new)
        self.assertIn("| spheres | beside | 0.21 ± 0.0248 (n 3) | -0.0467 ± 0.0143 (n 3) | up at "
                      "peak, rising further on unloading | peak: agrees; unloading: disagrees |",
                      out)
        self.assertIn("| T2S1 | beneath | -0.11 ± 0.0248 (n 3) | 0.00333 ± 0.0517 (n 3) | down "
                      "at peak, up on unloading (by less) | peak: agrees; unloading: not "
                      "resolved |", out)
        self.assertIn("| T2S2 | beside | 0.1 (n 1, no interval) | 0.1 (n 1, no interval) | — "
                      "| — |", out)

    def test_json_holds_the_sample_statistics_ratios_and_directions(self):
        d = self.compare(self.new, "--json")
        self.assertEqual(set(d), {"runs", "samples", "ratios", "directions"})
        self.assertEqual([r["id"] for r in d["runs"]][:2], ["spheres-r1", "spheres-r2"])
        s = {x["name"]: x for x in d["samples"]}
        self.assertEqual(s["spheres"]["runs"], ["spheres-r1", "spheres-r2", "spheres-r3"])
        self.assertFalse(s["spheres"]["at_paper_scale"])
        q = s["spheres"]["quantities"]["rotation_loading_mean_deg"]
        self.assertEqual((q["n"], q["df"], q["paper"]), (3, 2, 5.18))
        self.assertAlmostEqual(q["mean"], 0.75)
        self.assertAlmostEqual(q["sd"], 0.05)
        self.assertAlmostEqual(q["ci95"][1] - q["mean"], T2 * 0.05 / math.sqrt(3))
        self.assertIsNone(s["T2S2"]["quantities"]["porosity_grid"]["ci95"])
        ratio = next(r for r in d["ratios"] if r["quantity"] == "rotation_loading_mean_deg"
                     and r["clumps"] == "T2S1")
        a, b = 0.05 ** 2 / (3 * 0.75 ** 2), 0.005 ** 2 / (3 * 0.065 ** 2)
        df = math.floor((a + b) ** 2 / (a * a / 2 + b * b / 2))
        t = {2: 4.3027, 3: 3.1824, 4: 2.7764}[df]
        self.assertAlmostEqual(ratio["ratio"], 0.75 / 0.065)
        self.assertAlmostEqual(ratio["ci95"][0], 0.75 / 0.065 * math.exp(-t * math.sqrt(a + b)))
        self.assertAlmostEqual(ratio["paper"], 5.18 / 0.061)
        self.assertEqual(ratio["verdict"], "not comparable: not the paper's scale")
        self.assertEqual({r["quantity"] for r in d["ratios"]},
                         {"rotation_loading_mean_deg", "rotation_cycle_mean_deg",
                          "max_displacement_peak_mm", "settlement_peak_mm"})
        beside = next(x for x in d["directions"] if x["sample"] == "spheres"
                      and x["zone"] == "beside")
        self.assertEqual(beside["paper"]["peak"], "up")
        self.assertEqual(beside["agreement"], {"peak": "agrees", "unloading": "disagrees"})

    def test_json_runs_gain_scale_new_fields_and_counts_both_ways(self):
        runs = {r["id"]: r for r in self.compare(self.new, "--json")["runs"]}
        t2 = runs["T2S1-r1"]
        self.assertEqual(t2["scale"], {"bodies": 40, "balls": 400, "peak_load_N": 10000.0,
                                       "box_length_m": 0.35})
        self.assertFalse(t2["at_paper_scale"])
        self.assertIn("40 bodies < 1,500", t2["not_at_paper_scale_because"])
        for key in ("contacts_before_force_p50_N", "contacts_peak_force_p99_N",
                    "contacts_peak_sleeper_contacts", "contacts_after_sleeper_bodies",
                    "contacts_peak_sleeper_force_max_N", "contacts_peak_sleeper_force_total_N",
                    "zone_beneath_dz_peak_mm", "zone_beside_dz_end_mm",
                    "zone_beneath_dz_unloading_mm", "zone_beside_rotation_cycle_deg"):
            self.assertIn(key, t2["quantities"])
        self.assertAlmostEqual(t2["quantities"]["zone_beneath_dz_peak_mm"]["ours"], -0.1)
        both = t2["contacts_counted_both_ways"]
        self.assertEqual(both["paper"], 282955)
        self.assertEqual(both["rows"][0], {"gap_m": 0.0, "ball_pairs": 60, "both_ends": 120,
                                           "plus_wall": 132, "plus_intra_clump": 132 + 6400})
        out = self.compare(self.new)
        self.assertIn("| T2S1-r1 | 1 | 120 | 240 | 260 | 6,660 | — |", out)

    def test_largest_rotations_name_the_particle_and_where_it_sat(self):
        for path, has_zones in ((self.new, True), (self.old, False)):
            table = self.compare(path, "--json")
            with h5py.File(path, "r") as f:
                for entry in table["runs"]:
                    g = f["runs"][entry["id"]]
                    scene = json.loads(g.attrs["scene_json"])
                    loading = g["particles/rotation_loading"][()]
                    start = g["particles/position_start"][()]
                    cycle = g["particles/rotation_cycle"][()]
                    rows = entry["largest_rotations"]
                    self.assertEqual([r["body"] for r in rows],
                                     sorted(range(len(loading)), key=lambda i: -loading[i])[:3])
                    by_cycle = entry["largest_cycle_rotations"]
                    self.assertEqual([r["body"] for r in by_cycle],
                                     sorted(range(len(cycle)), key=lambda i: -cycle[i])[:3])
                    self.assertNotEqual([r["body"] for r in rows], [r["body"] for r in by_cycle])
                    unloading = g["particles/rotation_unloading"][()]
                    for r in rows + by_cycle:
                        x, y, z = start[r["body"]]
                        self.assertEqual(r["loading_deg"], loading[r["body"]])
                        l, u, c = loading[r["body"]], unloading[r["body"]], cycle[r["body"]]
                        self.assertAlmostEqual(
                            r["cosine"], max(-1.0, min(1.0, (c * c - l * l - u * u) / (2 * l * u))))
                        self.assertEqual(r["cycle_deg"], g["particles/rotation_cycle"][r["body"]])
                        # Depth below the top, down positive; the nearer side wall.
                        if has_zones:
                            self.assertAlmostEqual(r["depth_mm"],
                                                   (g["zones"].attrs["surface"] - z) * 1e3)
                        else:
                            self.assertIsNone(r["depth_mm"])
                        width = scene["box"]["width"]
                        self.assertAlmostEqual(r["wall_mm"], min(y, width - y) * 1e3)
                        x0 = (scene["box"]["length"] - scene["sleeper"]["length"]) / 2
                        self.assertEqual(r["beneath"],
                                         bool(x0 <= x <= x0 + scene["sleeper"]["length"]))
                    # Turning back: the weighted cosine is Σ l·u / Σ |l||u|, l·u from the
                    # three angles (the cycle's rotation vector is the sum of the other two).
                    back = entry["turning_back"]
                    dots = [(c * c - l * l - u * u) / 2
                            for l, u, c in zip(loading, unloading, cycle)]
                    products = [l * u for l, u in zip(loading, unloading)]
                    clipped = [max(-p, min(p, d)) for d, p in zip(dots, products)]
                    self.assertEqual(back["particles"], len(loading))
                    self.assertAlmostEqual(back["cosine"], sum(clipped) / sum(products))
                    self.assertAlmostEqual(back["turned_back"],
                                           sum(d < 0 for d in dots) / len(loading))
                    self.assertAlmostEqual(back["cycle_over_sum"],
                                           sum(cycle) / (sum(loading) + sum(unloading)))
        out = self.compare(self.new)
        self.assertIn("## Turning back on unloading, per run", out)
        self.assertIn("## The 3 largest rotations during loading, per run", out)
        self.assertIn("## The 3 largest rotations over the cycle, per run", out)

    def test_full_scale_runs_sit_beside_the_paper(self):
        out = self.compare(self.full)
        self.assertNotIn("NOT comparable", out)
        self.assertIn("- T2S1 (2 runs): 1,936 bodies, 19,360 balls, peak load 40 kN", out)
        self.assertIn("(0.37)", out)
        self.assertIn("| rotation, loading: mean (°) | 5.1 ± 1.27 (sd 0.141, n 2) [5.18] | "
                      "0.0615 ± 0.00635 (sd 0.000707, n 2) [0.061] |", out)
        self.assertIn("| rotation, loading: mean (°) | spheres / T2S1 | 82.9 | 63.3–109 | 84.9 "
                      "| consistent |", out)
        self.assertIn("| max displacement at peak load (mm) | spheres / T2S1 | 1.51 |", out)
        self.assertIn("| 3.53 | below the paper's |", out)
        self.assertIn("| sleeper settlement at peak (mm) | spheres / T2S1 | 1 | 1–1 | — | the "
                      "paper has none |", out)
        self.assertIn("| spheres-r1 | 0 | 60 | 120 | 132 | 132 | 10,337 |", out)
        d = self.compare(self.full, "--json")
        self.assertTrue(all(r["at_paper_scale"] for r in d["runs"]))
        verdicts = {r["quantity"]: r["verdict"] for r in d["ratios"]}
        self.assertEqual(verdicts["rotation_loading_mean_deg"], "consistent")
        self.assertEqual(verdicts["max_displacement_peak_mm"], "below the paper's")

    def test_old_archives_without_the_new_fields_still_compare(self):
        out = self.compare(self.old)
        self.assertIn("## Replicates", out)
        self.assertIn("## Spheres against clumps", out)
        for absent in ("## Directions", "Contacts counted both ways", "zone beneath", "median"):
            self.assertNotIn(absent, out)
        d = self.compare(self.old, "--json")
        self.assertEqual(d["directions"], [])
        for r in d["runs"]:
            self.assertNotIn("contacts_counted_both_ways", r)
            self.assertFalse([k for k in r["quantities"]
                              if k.startswith("zone_") or "sleeper_" in k or "_p50" in k])

    def test_an_empty_zone_has_its_count_and_no_means(self):
        path = write_study(os.path.join(self.tmp.name, "empty.h5"), smoke_runs()[:1])
        with h5py.File(path, "a") as f:
            f["runs/spheres-r1/zones/beneath"].attrs["count"] = 0
            f["runs/spheres-r1/zones/beneath"].attrs["dz_peak"] = float("nan")
        q = self.compare(path, "--json")["runs"][0]["quantities"]
        self.assertEqual(q["zone_beneath_count"]["ours"], 0)
        self.assertEqual([k for k in q if k.startswith("zone_beneath_")], ["zone_beneath_count"])
        self.assertIn("zone_beside_dz_peak_mm", q)

    def test_a_single_run_file_is_a_sample_of_one(self):
        out = self.compare(self.single)
        self.assertIn("- smoke-spheres (1 run): 40 bodies, 40 balls, peak load 10 kN", out)
        self.assertNotIn("## Replicates", out)
        d = self.compare(self.single, "--json")
        self.assertEqual([s["name"] for s in d["samples"]], ["smoke-spheres"])
        self.assertEqual(d["ratios"], [])


class ZoneFigure(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        cls.new = write_study(os.path.join(d, "new.h5"), smoke_runs())
        cls.old = write_study(os.path.join(d, "old.h5"), smoke_runs(), new_fields=False)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_figures_draws_fig_zones_from_an_archive_with_zones(self):
        out = os.path.join(self.tmp.name, "new")
        r = script("figures.py", self.new, "--out", out, "--runs",
                   "spheres-r1,spheres-r2,T2S1-r1,T2S1-r2")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn(f"wrote {os.path.join(out, 'fig_zones.png')}", r.stdout)
        self.assertTrue(is_png(os.path.join(out, "fig_zones.png")))
        self.assertNotIn("zones", r.stderr)

    def test_an_old_archive_loses_only_fig_zones(self):
        out = os.path.join(self.tmp.name, "old")
        r = script("figures.py", self.old, "--out", out, "--runs", "spheres-r1,T2S1-r1")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("fig_zones left out: no run holds zones/", r.stderr)
        self.assertFalse(os.path.exists(os.path.join(out, "fig_zones.png")))
        self.assertTrue(os.path.exists(os.path.join(out, "fig18_load_deformation.png")))

    def test_runs_without_zones_are_named_and_the_others_drawn(self):
        notes = []
        with open_archive(self.new) as new, open_archive(self.old) as old:
            runs = [new.run("T2S1-r1"), new.run("T2S1-r2"), old.run("spheres-r1")]
            written = zone_figure(runs, self.tmp.name, notes.append)
        self.assertEqual(len(written), 1)
        self.assertEqual(notes, ["run 'spheres-r1' holds no zones/: left out of fig_zones"])


if __name__ == "__main__":
    unittest.main()
