#!/usr/bin/python3
"""Shared beds in `ballast study` (docs/STUDY.md, "Shared beds"): runs whose scenes
differ only in their loading start from the bed one of them prepared, and end bit for
bit as if each had prepared its own; a bed that cannot be read is reported and the run
prepares its own.

Run by ctest with the path of the ballast binary as the only argument:
    /usr/bin/python3 tests/cli/test_shared_beds.py build/study/ballast

The studies load tests/data/study/tiny.json at two loading rates on common seeds (a
second or two a run).
"""
import json
import os
import signal
import subprocess
import sys
import tempfile
import unittest

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import binary  # noqa: E402
from archive_compare import differences  # noqa: E402
from binary import succeed  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TINY = os.path.join(HERE, "..", "data", "study", "tiny.json")
SLOW = {"name": "slow", "frequency": 50, "cycles": 10}  # changes only the loading
TMP = None


def write_study(name, samples, replicates):
    path = os.path.join(TMP.name, name + ".json")
    with open(path, "w") as f:
        json.dump({"name": name, "scene": os.path.abspath(TINY), "seed": 5,
                   "matrix": {"samples": samples, "replicates": replicates,
                              "common_seeds": True}}, f)
    return path


def log_of(archive, run_id):
    with h5py.File(archive, "r") as f:
        value = f["runs"][run_id]["log"][()]
    return value.decode() if isinstance(value, bytes) else str(value)


def same_runs(test, archive_a, archive_b, ids):
    with h5py.File(archive_a, "r") as a, h5py.File(archive_b, "r") as b:
        for run_id in ids:
            # The index is the run's place in its own study; the log has timings.
            test.assertEqual(differences(a["runs"][run_id], b["runs"][run_id],
                                         skip_attributes=("index",)), [], run_id)


def setUpModule():
    global TMP
    TMP = tempfile.TemporaryDirectory()


def tearDownModule():
    TMP.cleanup()


class SharedBeds(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # The slow runs alone: each prepares its own bed.
        cls.alone = os.path.join(TMP.name, "alone.h5")
        succeed("study", write_study("alone", [SLOW], 2), "-o", cls.alone, "--jobs", "1",
                "--threads", "1", "--progress", "plain")

    def test_runs_that_differ_in_their_loading_share_the_bed_and_its_bits(self):
        out = os.path.join(TMP.name, "shared.h5")
        study = write_study("shared", [{"name": "fast", "frequency": 100}, SLOW], 2)
        # One at a time, so that each bed is written before its other run starts (side
        # by side, a run whose bed is still being prepared prepares its own).
        r = succeed("study", study, "-o", out, "--jobs", "1", "--threads", "1",
                    "--progress", "plain")
        self.assertIn("shared beds: 2 runs may start from 2 beds", r.stdout)
        for run_id in ("fast-r1", "fast-r2"):
            self.assertNotIn("prepared bed from", log_of(out, run_id))
        for run_id in ("slow-r1", "slow-r2"):
            self.assertIn("prepared bed from", log_of(out, run_id))
        same_runs(self, out, self.alone, ["slow-r1", "slow-r2"])
        self.assertFalse(os.path.exists(out + ".parts"), "the beds outlived the study")

    def test_a_damaged_bed_is_reported_and_the_run_prepares_its_own(self):
        out = os.path.join(TMP.name, "damaged.h5")
        study = write_study("damaged", [{"name": "fast", "frequency": 100}, SLOW], 1)
        # Stopped once the first run has written the bed and ended; the second is
        # abandoned in flight (SIGTERM), so the bed stays for it in the parts folder.
        p = subprocess.Popen([binary.PATH, "study", study, "-o", out, "--jobs", "1",
                              "--threads", "1", "--progress", "plain"],
                             stdout=subprocess.PIPE, text=True)
        for line in p.stdout:
            if line.startswith("ok     fast-r1"):
                p.send_signal(signal.SIGTERM)
                break
        p.communicate(timeout=120)
        parts = os.listdir(out + ".parts")
        beds = [n for n in parts if n.startswith("bed-")]
        self.assertEqual(len(beds), 1, parts)
        # The signal is seen within 0.1 s: a fast machine may have loaded the bed into
        # the second run and checkpointed it by then. Without that checkpoint the run
        # starts over and must read the bed again.
        for name in parts:
            if name.endswith(".checkpoint") and not name.startswith("bed-"):
                os.remove(os.path.join(out + ".parts", name))
        with open(os.path.join(out + ".parts", beds[0]), "r+b") as f:
            f.seek(-100, os.SEEK_END)  # in the state, before the final hash
            f.write(b"\xff" * 8)
        succeed("study", study, "-o", out, "--resume", "--jobs", "1", "--threads", "1",
                "--progress", "plain")
        log = log_of(out, "slow-r1")
        self.assertIn("is damaged", log)
        self.assertIn("this run prepares its own bed", log)
        self.assertNotIn("prepared bed from", log)
        same_runs(self, out, self.alone, ["slow-r1"])


if __name__ == "__main__":
    binary.main()
