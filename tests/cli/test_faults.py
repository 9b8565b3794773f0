#!/usr/bin/python3
"""Faults of the machine, not of the input (issue 29): a disk that fills, a file system
that is read-only. Each ends with a message naming the path and the cause, never a
crash; finished runs are kept and `--resume` completes the study once there is room.

The small disks are tmpfs mounts the test makes itself (it needs root, as CI and a
fresh Debian machine have; elsewhere it says so and skips). Run by ctest with the path
of the ballast binary as the only argument:
    /usr/bin/python3 tests/cli/test_faults.py build/study/ballast
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import binary  # noqa: E402
from archive_compare import differences, run_differences  # noqa: E402
from binary import ballast, succeed  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "data", "study")
IDS = ["spheres-r1", "huge-r1", "spheres_dt-r1", "T2S1-r1"]


class SmallDisk:
    """A tmpfs of `kib` KiB at `where`, read-only if asked, unmounted on exit."""

    def __init__(self, where, kib, read_only=False):
        self.where = where
        os.makedirs(where, exist_ok=True)
        options = f"size={kib}k" + (",ro" if read_only else "")
        r = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", where],
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise unittest.SkipTest(f"cannot mount a small tmpfs (needs root): {r.stderr}")

    def grow(self, kib):
        subprocess.run(["mount", "-o", f"remount,size={kib}k", self.where], check=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        subprocess.run(["umount", self.where], check=True)


class Faults(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        for name in ("mixed.json", "tiny.json"):
            shutil.copy(os.path.join(DATA, name), self.tmp)
        self.study = os.path.join(self.tmp, "mixed.json")
        self.scene = os.path.join(self.tmp, "tiny.json")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def disk(self, kib, read_only=False):
        return SmallDisk(os.path.join(self.tmp, "disk"), kib, read_only)

    def assert_clean_failure(self, r, code, *words):
        """Exit `code` (not a signal: a crash is negative or 128+), the message on
        stderr with each of `words`."""
        self.assertEqual(r.returncode, code, r.stdout[-2000:] + r.stderr)
        self.assertIn("error:", r.stderr)
        for w in words:
            self.assertIn(w, r.stderr)

    def test_a_full_disk_stops_the_study_and_resume_completes_it(self):
        # mixed.json's four runs write parts of 6-100 KiB; 200 KiB holds a few, not all.
        reference = os.path.join(self.tmp, "reference.h5")
        r = ballast("study", self.study, "-o", reference, "--jobs", "1", "--threads", "1",
                    "--progress", "plain")
        self.assertEqual(r.returncode, 3, r.stderr)  # huge-r1 blows up, by design
        with self.disk(200) as d:
            archive = os.path.join(d.where, "m.h5")
            args = ("study", self.study, "-o", archive, "--jobs", "1", "--threads", "1",
                    "--progress", "plain")
            r = ballast(*args)
            self.assert_clean_failure(r, 1, "No space left on device", d.where, "--resume")
            parts = os.listdir(archive + ".parts")
            self.assertFalse([p for p in parts if p.endswith(".tmp")], parts)
            kept = [p for p in parts if p.endswith(".h5")]
            self.assertGreaterEqual(len(kept), 1, r.stdout)
            # Room again: --resume appends the kept runs and redoes only the lost one.
            d.grow(20000)
            r = ballast(*args, "--resume")
            self.assertEqual(r.returncode, 3, r.stdout[-2000:] + r.stderr)
            self.assertIn(f"{len(kept)} in the archive", r.stdout)
            self.assertEqual(run_differences(reference, archive), [])
            with h5py.File(archive, "r") as f:
                self.assertEqual(sorted(f["runs"]), sorted(IDS))

    def test_a_run_that_cannot_write_its_output_says_why_and_resumes(self):
        reference = os.path.join(self.tmp, "reference.h5")
        succeed("run", self.scene, "-o", reference, "--threads", "1")
        with self.disk(40) as d:
            out = os.path.join(d.where, "r.h5")
            args = ("run", self.scene, "-o", out, "--threads", "1")
            r = ballast(*args)
            self.assert_clean_failure(r, 1, f"cannot write {out}: No space left on device")
            # The checkpoints that did not fit were said, and the run went on to the end
            # (the output is what it could not write).
            self.assertIn(f"warning: cannot write checkpoint {out}.checkpoint.tmp: No space "
                          "left on device; the run goes on without it", r.stdout)
            # Left behind: nothing half written; at most the last checkpoint that fitted
            # (one of the first, in the preparation), whole, named, with how to resume.
            left = os.listdir(d.where)
            self.assertIn(left, ([], ["r.h5.checkpoint"]))
            if left:
                self.assertIn(f"last checkpoint, {out}.checkpoint, is kept", r.stderr)
                self.assertIn("--resume", r.stderr)
            # Room again: --resume goes on from it (or starts again without one) and
            # ends with the run an uninterrupted one gives, bit for bit.
            d.grow(4000)
            r = ballast(*args, "--resume")
            self.assertEqual(r.returncode, 0, r.stdout[-2000:] + r.stderr)
            with h5py.File(out, "r") as a, h5py.File(reference, "r") as b:
                self.assertEqual(differences(a["run"], b["run"], "/run"), [])
            self.assertEqual(os.listdir(d.where), ["r.h5"])

    def test_a_read_only_output_is_refused_before_anything_runs(self):
        with self.disk(1000, read_only=True) as d:
            for args in (("run", self.scene, "-o", os.path.join(d.where, "r.h5")),
                         ("study", self.study, "-o", os.path.join(d.where, "m.h5")),
                         ("study", self.study, "-o", os.path.join(d.where, "sub", "m.h5"))):
                r = ballast(*args)
                self.assert_clean_failure(r, 2, "Read-only file system", d.where)
                self.assertNotIn("stage 1", r.stdout + r.stderr, args)

    def test_huge_box_and_sleeper_heights_run_to_finite_results(self):
        # test_input_mutations.py lets these through --dry-run: the lid and the
        # sleeper's top are positions only, and a run takes them. JSON has no inf or
        # NaN (they come out as null), so the run's nulls must be the plain run's.
        def numbers_and_nulls(*sets):
            r = succeed("run", self.scene, *sets, "--json", "--threads", "1")
            numbers, nulls = [], set()

            def walk(v, path):
                if isinstance(v, dict):
                    for k, x in v.items():
                        walk(x, f"{path}/{k}")
                elif isinstance(v, list):
                    for i, x in enumerate(v):
                        walk(x, f"{path}/{i}")
                elif v is None:
                    nulls.add(path)
                elif isinstance(v, float):
                    numbers.append(v)
            walk(json.loads(r.stdout), "")
            return numbers, nulls

        _, plain_nulls = numbers_and_nulls()
        for key in ("/box/height", "/sleeper/height"):
            numbers, nulls = numbers_and_nulls("--set", f"{key}=1e308")
            self.assertTrue(numbers, key)
            self.assertTrue(all(math.isfinite(v) for v in numbers), key)
            self.assertEqual(nulls, plain_nulls, key)

if __name__ == "__main__":
    binary.main()
