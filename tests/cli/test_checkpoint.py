#!/usr/bin/python3
"""Checkpoints of the preparation and the load cycles (cases/box_test_checkpoint.hpp):
a run killed with SIGKILL at several moments, in the preparation or the cycles, and
resumed each time ends with the same archive, bit for bit, as a run never interrupted;
so does a study whose run in flight is killed; and a
checkpoint that is damaged, truncated, of another scene, or left over from a killed
run is refused with a message that says so.

The scene is tests/data/study/tiny.json (40 spheres) loaded for 20 cycles at 100 Hz:
a few seconds a run. Run by ctest with the path of the ballast binary as the only
argument:
    /usr/bin/python3 tests/cli/test_checkpoint.py build/study/ballast
"""
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import binary  # noqa: E402
from archive_compare import differences, run_differences  # noqa: E402
from binary import ballast, succeed  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TINY = os.path.join(HERE, "..", "data", "study", "tiny.json")
CYCLES = ["--set", "/sleeper/cycles=20", "--threads", "1"]
RESUMED = re.compile(r"resumed from checkpoint .*: step (\d+), (\d+) of 20 cycles done")


def run_differences_single(a_path, b_path):
    with h5py.File(a_path, "r") as a, h5py.File(b_path, "r") as b:
        return differences(a["run"], b["run"], "/run")


def kill_after(cmd, checkpoint, delay, writes=1):
    """Starts `cmd`, waits for `checkpoint` to be (re)written `writes` times (as often as
    polling sees it change: at least that many), waits `delay` s more, and kills it with
    SIGKILL. Returns whether it was still running to be killed."""
    before = os.stat(checkpoint).st_mtime_ns if os.path.exists(checkpoint) else None
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 300
    seen = 0
    while time.monotonic() < deadline and p.poll() is None and seen < writes:
        now = os.stat(checkpoint).st_mtime_ns if os.path.exists(checkpoint) else None
        if now is not None and now != before:
            seen, before = seen + 1, now
            continue
        time.sleep(0.005)
    time.sleep(delay)
    running = p.poll() is None
    if running:
        p.send_signal(signal.SIGKILL)
    p.wait()
    return running


class Checkpoints(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.reference = os.path.join(cls.tmp.name, "reference.h5")
        cls.reference_log = succeed("run", TINY, *CYCLES, "--checkpoint-minutes", "0", "-o",
                                    cls.reference).stdout

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.tmp.name, name)

    def test_the_last_cycle_is_logged_with_the_archives_settlement_and_rebound(self):
        # A run of many cycles logs its progress about once a minute and always after
        # its last cycle, in mm, to 4 significant digits.
        m = re.search(r"cycle 20 of 20: permanent settlement (\S+) mm, rebound (\S+) mm; "
                      r"(\S+) s a cycle\n", self.reference_log)
        self.assertIsNotNone(m, self.reference_log[-2000:])
        with h5py.File(self.reference, "r") as f:
            trough = f["run/cycles/settlement_trough"][-1] * 1e3
            peak = f["run/cycles/settlement_peak"][-1] * 1e3
        self.assertNotAlmostEqual(trough, 0.0, places=3)
        self.assertAlmostEqual(float(m.group(1)) / trough, 1.0, delta=1e-3)
        self.assertAlmostEqual(float(m.group(2)) / (peak - trough), 1.0, delta=1e-3)
        self.assertGreater(float(m.group(3)), 0.0)

    def test_killed_three_times_then_resumed_gives_the_same_archive(self):
        out = self.path("killed.h5")
        checkpoint = out + ".checkpoint"
        cmd = [binary.PATH, "run", TINY, *CYCLES, "--checkpoint-cycles", "1", "-o", out]
        # A kill right after a checkpoint lands (the first, in the preparation), one a
        # little later, one later still, after more checkpoints than the preparation
        # and the start of loading write (6 for this scene): inside a cycle, while the
        # next checkpoint may be being written.
        kills = sum(kill_after(cmd + (["--resume"] if k else []), checkpoint, delay, writes)
                    for k, (delay, writes) in enumerate(((0.0, 1), (0.15, 1), (0.1, 9))))
        self.assertGreaterEqual(kills, 2, "the runs ended before they could be killed")
        self.assertTrue(os.path.exists(checkpoint))
        self.assertFalse(os.path.exists(out))
        r = succeed("run", TINY, *CYCLES, "--checkpoint-cycles", "1", "-o", out, "--resume")
        done = [int(m.group(2)) for m in RESUMED.finditer(r.stdout)]
        self.assertEqual(len(done), 1, r.stdout[-2000:])
        self.assertGreater(done[0], 0, "the last resume started from the start of loading")
        self.assertEqual(run_differences_single(out, self.reference), [])
        self.assertFalse(os.path.exists(checkpoint), "a finished run removes its checkpoint")

    def test_killed_in_the_preparation_then_resumed_gives_the_same_archive(self):
        # A checkpoint lands at every point between two stages of the preparation:
        # killed just after the first, the run goes on from there, with the plate's
        # servo pressing as before, not from a new preparation.
        out = self.path("prepare.h5")
        cmd = [binary.PATH, "run", TINY, *CYCLES, "-o", out]
        self.assertTrue(kill_after(cmd, out + ".checkpoint", 0.0))
        r = succeed("run", TINY, *CYCLES, "-o", out, "--resume")
        resumed = re.search(r"resumed from checkpoint .*: step (\d+), in the preparation after "
                            r"its stage '([^']+)'", r.stdout)
        self.assertIsNotNone(resumed, r.stdout[-2000:])
        self.assertGreater(int(resumed.group(1)), 0)
        self.assertEqual(run_differences_single(out, self.reference), [])
        self.assertFalse(os.path.exists(out + ".checkpoint"))

    def test_resumed_on_two_threads_gives_the_same_archive(self):
        out = self.path("two.h5")
        cmd = [binary.PATH, "run", TINY, *CYCLES, "--checkpoint-cycles", "5", "-o", out]
        self.assertTrue(kill_after(cmd, out + ".checkpoint", 0.3))
        succeed("run", TINY, "--set", "/sleeper/cycles=20", "--threads", "2",
                "--checkpoint-cycles", "5", "-o", out, "--resume")
        self.assertEqual(run_differences_single(out, self.reference), [])

    def test_a_left_over_checkpoint_is_kept_and_named(self):
        out = self.path("left.h5")
        cmd = [binary.PATH, "run", TINY, *CYCLES, "--checkpoint-cycles", "2", "-o", out]
        self.assertTrue(kill_after(cmd, out + ".checkpoint", 0.0))
        before = open(out + ".checkpoint", "rb").read()
        r = ballast("run", TINY, *CYCLES, "-o", out)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn(f"{out}.checkpoint exists", r.stderr)
        self.assertIn("--resume continues it", r.stderr)
        self.assertEqual(open(out + ".checkpoint", "rb").read(), before)

    def refused(self, name, damage, *extra):
        """A checkpoint of a killed run, damaged by `damage(bytes) -> bytes`, then
        --resume: exit 2 and the message."""
        out = self.path(name)
        cmd = [binary.PATH, "run", TINY, *CYCLES, "--checkpoint-cycles", "2", "-o", out]
        self.assertTrue(kill_after(cmd, out + ".checkpoint", 0.0))
        with open(out + ".checkpoint", "rb") as f:
            data = f.read()
        with open(out + ".checkpoint", "wb") as f:
            f.write(damage(data))
        r = ballast("run", TINY, *CYCLES, *extra, "-o", out, "--resume")
        self.assertEqual(r.returncode, 2, r.stdout[-1000:] + r.stderr)
        self.assertFalse(os.path.exists(out))
        return r.stderr

    def test_a_flipped_byte_is_refused(self):
        def flip(data):
            k = len(data) * 2 // 3
            return data[:k] + bytes([data[k] ^ 0x10]) + data[k + 1:]
        self.assertIn("is damaged (its hash does not match)", self.refused("flip.h5", flip))

    def test_a_truncated_checkpoint_is_refused(self):
        self.assertIn("is truncated", self.refused("truncated.h5", lambda d: d[:len(d) // 2]))

    def test_another_scenes_checkpoint_is_refused(self):
        message = self.refused("other.h5", lambda d: d, "--set", "/sleeper/peak_load=2500")
        self.assertIn("was written for another scene", message)

    def test_a_study_resumes_its_run_in_flight(self):
        study = self.path("study.json")
        with open(study, "w") as f:
            json.dump({"name": "cycles", "scene": os.path.abspath(TINY), "seed": 5,
                       "matrix": {"samples": [{"name": "spheres", "shape": "spheres"}],
                                  "axes": {"cycles": [20]}, "replicates": 2}}, f)
        whole, cut = self.path("whole.h5"), self.path("cut.h5")
        common = ["--jobs", "1", "--threads", "1", "--progress", "plain"]
        succeed("study", study, "-o", whole, *common)
        cmd = [binary.PATH, "study", study, "-o", cut, *common, "--checkpoint-cycles", "3"]
        self.assertTrue(kill_after(cmd, cut + ".parts/000000.checkpoint", 0.2))
        r = succeed("study", study, "-o", cut, *common, "--checkpoint-cycles", "3", "--resume")
        self.assertIn("resumed from checkpoint", r.stdout)
        self.assertEqual(run_differences(cut, whole), [])
        self.assertFalse(os.path.exists(cut + ".parts"))


if __name__ == "__main__":
    binary.main()
