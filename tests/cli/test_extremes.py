#!/usr/bin/python3
"""Knobs at their extremes (issue 29): each run either ends with finite results and a
load cycle whose energy budget closes (docs/ACCURACY.md), or fails with a message
naming the step and the knob; never a crash or a non-finite number.

On tests/data/study/tiny.json (40 spheres or clumps, about a second a run). Run by
ctest with the path of the ballast binary as the only argument:
    /usr/bin/python3 tests/cli/test_extremes.py build/study/ballast
"""
import json
import math
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import binary  # noqa: E402
from binary import ballast  # noqa: E402

TINY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "study",
                    "tiny.json")
CLUMPS = ("/particles/shape=table2/sample1",)

# (what, --set values): each runs to the end.
RUNS = [
    ("dt_safety 0.05", ("/numerics/dt_safety=0.05",)),
    ("dt_safety 1", ("/numerics/dt_safety=1",)),
    ("ks/kn 0.1", ("/materials/ball_ks=5.08e8",)),
    ("ks/kn 10", ("/materials/ball_ks=5.08e10",)),
    ("friction 0", ("/materials/friction_compaction=0", "/materials/friction_loading=0")),
    ("friction 10", ("/materials/friction_compaction=10", "/materials/friction_loading=10")),
    ("1 MN at 100 Hz", ("/sleeper/peak_load=1e6",)),
    ("clumps, p = 0", CLUMPS + ("/particles/clump/p=0",)),
    ("clumps, p = 1", CLUMPS + ("/particles/clump/p=1",)),
    ("clumps, no edge balls", CLUMPS + ("/particles/clump/edge_balls=0",)),
    ("clumps, c = 0", CLUMPS + ("/particles/clump/c=0",)),
    ("clumps, c = 0.99", CLUMPS + ("/particles/clump/c=0.99",)),
    ("clumps, D3 = 0.05", CLUMPS + ("/particles/clump/d3=0.05",)),
    ("clumps, D3 = 9.5 (the largest allowed)", CLUMPS + ("/particles/clump/d3=9.5",)),
    ("clumps, full rotation", CLUMPS + ("/numerics/rotation=full",)),
    ("Hertz-Mindlin", ("/materials/contact_law=hertz_mindlin",)),
]


def floats(v):
    if isinstance(v, dict):
        for x in v.values():
            yield from floats(x)
    elif isinstance(v, list):
        for x in v:
            yield from floats(x)
    elif isinstance(v, float):
        yield v


def run(*sets):
    args = ["run", TINY, "--json", "--threads", "1"]
    for s in sets:
        args += ["--set", s]
    return ballast(*args, timeout=600)


class Extremes(unittest.TestCase):
    def assert_closed_budget(self, r, what):
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        d = json.loads(r.stdout)
        self.assertTrue(all(math.isfinite(x) for x in floats(d)))
        cycle = next(s for s in d["stages"] if s["name"] == "cycle")
        scale = max(abs(cycle["energy_in_J"]), cycle["energy_dissipated_J"])
        error = abs(cycle["energy_error_J"]) / scale
        print(f"  {what}: load cycle's energy error {100 * error:.3f} % of "
              f"{scale:.3g} J")  # the figures docs/ACCURACY.md quotes
        # Measured at most 0.98 % (c = 0.99); the run refuses above 5 %.
        self.assertLess(error, 0.05)

    def assert_blow_up_named(self, r):
        self.assertEqual(r.returncode, 1, r.stderr[-2000:])
        self.assertRegex(r.stderr, r"step \d+: body \d+")
        self.assertIn("critical estimate", r.stderr)

    def test_each_extreme_runs_with_a_closed_budget(self):
        for what, sets in RUNS:
            with self.subTest(what):
                self.assert_closed_budget(run(*sets), what)

    def test_twice_the_critical_timestep_fails_naming_dt_and_the_step(self):
        # At 2.4e-6 s (about twice the critical estimate) tiny.json does not blow up:
        # it runs to the end with a load cycle whose budget is off by 56 %. That run
        # is refused, not recorded as data.
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "r.h5")
            r = ballast("run", TINY, "--json", "--threads", "1", "--set", "/numerics/dt=2.4e-6",
                        "-o", out, timeout=600)
            self.assertEqual(r.returncode, 1, r.stderr[-2000:])
            self.assertIn("energy budget", r.stderr)
            self.assertRegex(r.stderr, r"step \d+")
            self.assertIn("/numerics/dt", r.stderr)
            self.assertIn("x the critical estimate", r.stderr)
            # A failed run is the run's answer, not an interruption: it leaves nothing,
            # not even the checkpoints its preparation wrote (resumed, it would fail
            # again), so the next run with this -o starts without being told to delete.
            self.assertEqual(os.listdir(d), [])

    def test_values_past_a_bound_are_refused_at_parsing(self):
        # A billion spheres in a square kilometre: a bed the box holds, but no machine's
        # memory (about 1 kB a ball): refused before anything is computed.
        huge = ("/box/length=1000", "/box/width=1000", "/particles/count=1000000000")
        for sets, field in (((*CLUMPS, "/particles/clump/c=1"), "/particles/clump/c = 1"),
                            (("/particles/count=1",), "/particles/count = 1"),
                            (huge, "/particles/count = 1000000000")):
            with self.subTest(field):
                r = run(*sets)
                self.assertEqual(r.returncode, 2, r.stderr[-2000:])
                self.assertIn(field, r.stderr)
                self.assertIn("allowed", r.stderr)
        r = run(*huge)
        self.assertIn("GiB is available", r.stderr)

    def test_clumps_of_tiny_balls_are_refused_before_the_run(self):
        # D3 = 100 makes balls of 0.3 % of the particle: uncapped, the neighbour grid
        # took gigabytes; capped, the growth had not ended after 5 minutes.
        r = run(*CLUMPS, "/particles/clump/d3=100")
        self.assertEqual(r.returncode, 2, r.stderr[-2000:])
        self.assertIn("/particles/clump/d3 = 100", r.stderr)
        self.assertIn("<= 9.5", r.stderr)

    def test_nearly_coincident_clump_balls_run_or_blow_up_naming_the_step(self):
        # D3 = 0.01: every clump's balls nearly coincide with its central ball.
        # At 0.8 of the critical estimate some realisations blow up in preparation
        # (seeds 2 and 4 of 1-6), the others run with a closed budget (docs/ACCURACY.md,
        # "Where each knob breaks"): either ending is allowed, nothing else.
        for seed in (1, 2):
            with self.subTest(seed=seed):
                r = run(*CLUMPS, "/particles/clump/d3=0.01", f"/particles/seed={seed}")
                if r.returncode == 0:
                    self.assert_closed_budget(r, f"clumps, D3 = 0.01, seed {seed}")
                else:
                    self.assert_blow_up_named(r)

    def test_far_above_critical_blows_up_at_once_naming_the_step(self):
        self.assert_blow_up_named(run("/numerics/dt=1e-4"))


if __name__ == "__main__":
    binary.main()
