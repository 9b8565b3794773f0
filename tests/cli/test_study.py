#!/usr/bin/python3
"""End-to-end checks of `ballast study` and `ballast merge` (docs/ARCHIVE.md).

Run by ctest with the path of the ballast binary as the only argument:
    /usr/bin/python3 tests/cli/test_study.py build/study/ballast

Every study here is tests/data/study/mixed.json (four runs of about a second each on
tiny.json, one of which blows up) or a variant of it. One uninterrupted run of it, on
2 jobs x 1 thread, is the reference every other way of running it must equal, bit for
bit apart from timings.
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import binary  # noqa: E402
from archive_compare import differences, run_differences  # noqa: E402
from binary import ballast  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "data", "study")
CASES = os.path.join(HERE, "..", "..", "cases")
MIXED = os.path.join(DATA, "mixed.json")
TINY = os.path.join(DATA, "tiny.json")
IDS = ["spheres-r1", "huge-r1", "spheres_dt-r1", "T2S1-r1"]
TMP = None
REFERENCE = None  # (archive path, completed process)


def study(*args):
    return ballast("study", *args, "--progress", "plain")


def text(value):
    return value.decode() if isinstance(value, bytes) else value


def setUpModule():
    global TMP, REFERENCE
    TMP = tempfile.TemporaryDirectory()
    path = os.path.join(TMP.name, "reference.h5")
    REFERENCE = (path, study(MIXED, "-o", path, "--jobs", "2", "--threads", "1"))


def tearDownModule():
    TMP.cleanup()


def scratch():
    return tempfile.mkdtemp(dir=TMP.name)


def write_study(folder, change):
    """mixed.json with `change` applied to its JSON, next to a copy of tiny.json."""
    with open(MIXED) as f:
        s = json.load(f)
    change(s)
    shutil.copy(TINY, os.path.join(folder, "tiny.json"))
    path = os.path.join(folder, "study.json")
    with open(path, "w") as f:
        json.dump(s, f)
    return path


class Archive(unittest.TestCase):
    """What one uninterrupted study leaves."""

    def setUp(self):
        self.path, self.result = REFERENCE

    def test_some_runs_failed_so_exit_code_is_3_and_the_summary_lists_them(self):
        self.assertEqual(self.result.returncode, 3, self.result.stderr)
        out = self.result.stdout
        for run in IDS:
            self.assertIn(run, out)
        self.assertIn("failed runs:", out)
        self.assertIn("huge-r1: blew up", out)
        self.assertIn("4 of 4 runs of the study, 1 failed", out)

    def test_root_says_which_study_and_program_made_it(self):
        with h5py.File(self.path, "r") as f:
            a = f.attrs
            self.assertEqual(text(a["format"]), "ballast-study")
            self.assertEqual(a["format_version"], 1)
            self.assertEqual(text(a["study_name"]), "mixed")
            with open(MIXED, "rb") as s:
                self.assertEqual(a["study_json"], s.read())  # verbatim
            with open(TINY, "rb") as s:
                self.assertEqual(a["scene_json"], s.read())
            self.assertEqual(text(a["scene_path"]), "tiny.json")
            self.assertEqual(a["study_seed"], 11)
            self.assertEqual(a["run_count"], 4)
            self.assertEqual((a["shard_index"], a["shard_count"]), (1, 1))
            self.assertRegex(text(a["fingerprint"]), r"^[0-9a-f]{16}$")
            self.assertRegex(text(a["git_revision"]), r"^([0-9a-f]{40}(-dirty)?|unknown)$")
            self.assertRegex(text(a["program_version"]), r"^\d+\.\d+")
            runs = json.loads(f["study_runs"][()])
            self.assertEqual([r["id"] for r in runs], IDS)
            for r in runs:
                g = f["runs"][r["id"]]
                self.assertEqual(int(g.attrs["seed"]), int(r["seed"]))  # full 64 bits
                self.assertEqual(g.attrs["index"], r["index"])
                self.assertEqual(json.loads(g.attrs["params"]), r["params"])

    def test_a_run_that_blows_up_is_recorded_as_failed_and_the_study_goes_on(self):
        with h5py.File(self.path, "r") as f:
            g = f["runs/huge-r1"]
            self.assertEqual(text(g.attrs["status"]), "failed")
            self.assertIn("blew up", text(g.attrs["message"]))
            self.assertIn("exceeds max_speed", text(g.attrs["message"]))
            self.assertNotIn("particles", g)
            self.assertIn("dt = 5e-06 s", text(g.attrs["message"]))
            self.assertIn("stage 1:", text(g["log"][()]))
            # The runs after it (indices 2 and 3) ran and are ok.
            for run in ("spheres_dt-r1", "T2S1-r1"):
                self.assertEqual(text(f["runs"][run].attrs["status"]), "ok")
                self.assertEqual(text(f["runs"][run].attrs["message"]), "")

    def test_an_ok_run_holds_the_measurements_and_displacements(self):
        with h5py.File(self.path, "r") as f:
            g = f["runs/spheres-r1"]
            self.assertEqual(g.attrs["loaded"], 1)
            p = g["particles"]
            start = p["position_start"][:]
            self.assertEqual(start.shape, (40, 3))
            np.testing.assert_array_equal(p["displacement_end"][:], p["position_end"][:] - start)
            np.testing.assert_array_equal(p["displacement_peak"][:], p["position_peak"][:] - start)
            self.assertEqual(text(p["displacement_end"].attrs["units"]), "m")
            n = len(g["series/time"])
            self.assertGreater(n, 5)
            for s in ("target_force", "sleeper_force", "settlement"):
                self.assertEqual(len(g["series"][s]), n)
            for c in ("before", "peak", "after"):
                self.assertIn("force", g["contacts"][c])
            self.assertNotIn("clumps", g)  # spheres: no clumps group
            self.assertIn("stage 4:", text(g["log"][()]))

    def test_a_clump_run_holds_the_templates_ballast_clump_generates_with_its_seed(self):
        with h5py.File(self.path, "r") as f:
            g = f["runs/T2S1-r1"]
            seed = int(g.attrs["seed"])
            c = g["clumps"]
            self.assertEqual(text(c.attrs["format"]), "ballast-clumps")
            self.assertEqual(int(c["clumps/ball_count"][:].sum()), g.attrs["balls"])
            self.assertEqual(len(c["clumps/first_ball"]), g.attrs["bodies"])
            np.testing.assert_array_equal(g["particles/shape_index"][:], np.arange(40))
            made = os.path.join(scratch(), "clumps.h5")
            r = ballast("clump", "--preset", "table2/sample1", "--count", "40", "--seed",
                        str(seed), "--mass", "paper", "--threads", "1", "-o", made)
            self.assertEqual(r.returncode, 0, r.stderr)
            with h5py.File(made, "r") as m:
                # Same datasets, same numbers; the attributes name their sources.
                self.assertEqual(differences(m, c, skip_attributes=set(m.attrs) | set(c.attrs)),
                                 [])

    def test_a_run_group_equals_ballast_run_of_the_scene_it_records(self):
        single = os.path.join(scratch(), "single.h5")
        with h5py.File(self.path, "r") as f:
            scene = os.path.join(os.path.dirname(single), "scene.json")
            with open(scene, "wb") as s:
                s.write(f["runs/T2S1-r1"].attrs["scene_json"])
        r = ballast("run", scene, "-o", single, "--threads", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        study_only = {"id", "index", "sample", "params", "seed", "replicate", "status",
                      "message", "git_revision", "scene_json"}
        with h5py.File(self.path, "r") as f, h5py.File(single, "r") as s:
            self.assertEqual(differences(f["runs/T2S1-r1"], s["run"], skip_attributes=study_only),
                             [])

    @unittest.skipUnless(shutil.which("h5dump"), "h5dump (hdf5-tools) not installed")
    def test_h5dump_reads_the_archive(self):
        r = subprocess.run(["h5dump", "-a", "/runs/huge-r1/status", self.path],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn('"failed"', r.stdout)


class Parallelism(unittest.TestCase):
    def test_results_do_not_depend_on_jobs_or_threads(self):
        path = os.path.join(scratch(), "serial.h5")
        # Passive waiting: on a machine busy with other work, threads spinning at the
        # engine's barriers slow a 2-thread run a hundredfold (the results are the same).
        r = subprocess.run([binary.PATH, "study", MIXED, "-o", path, "--jobs", "1", "--threads", "2",
                            "--progress", "plain"], capture_output=True, text=True, timeout=300,
                           env=dict(os.environ, OMP_WAIT_POLICY="passive"))
        self.assertEqual(r.returncode, 3, r.stderr)
        self.assertIn("1 side by side x 2 thread(s)", r.stdout)
        self.assertEqual(run_differences(REFERENCE[0], path), [])
        with h5py.File(path, "r") as f:
            self.assertEqual(f["runs/T2S1-r1"].attrs["threads"], 2)


class Interruption(unittest.TestCase):
    """A study stopped part-way, then completed with --resume, equals the reference.
    Runs start dearest first (study_runner.cpp), so the tests read which run a progress
    line names instead of assuming the study order."""

    def start(self, path, wait_for):
        """Starts the study on one job; returns it once a line starting with `wait_for`
        has been printed."""
        p = subprocess.Popen([binary.PATH, "study", MIXED, "-o", path, "--jobs", "1", "--threads",
                              "1", "--progress", "plain"], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
        lines = []
        for line in p.stdout:
            lines.append(line)
            if line.startswith(wait_for):
                break
        return p, lines

    @staticmethod
    def run_named(line):
        """The run id of a progress line ("ok     ID in ...", "start  ID (...)")."""
        return line.split()[1]

    def resume_and_compare(self, path):
        r = study(MIXED, "-o", path, "--resume", "--jobs", "2", "--threads", "1")
        self.assertEqual(r.returncode, 3, r.stdout + r.stderr)
        self.assertEqual(run_differences(REFERENCE[0], path), [])
        self.assertFalse(os.path.exists(path + ".parts"))  # complete: parts removed
        return r

    def test_sigkill_loses_only_the_run_in_flight_and_resume_completes_the_study(self):
        path = os.path.join(scratch(), "killed.h5")
        p, lines = self.start(path, "ok ")
        p.kill()
        p.communicate()
        # The archive is closed between writes: readable at once, with the finished runs.
        with h5py.File(path, "r") as f:
            done = list(f["runs"])
        self.assertIn(self.run_named(lines[-1]), done)
        self.assertLess(len(done), 4)
        r = self.resume_and_compare(path)
        self.assertIn(f"{len(done)} in the archive, {4 - len(done)} to run", r.stdout)

    def test_a_damaged_archive_is_moved_aside_and_rebuilt_from_the_parts(self):
        path = os.path.join(scratch(), "damaged.h5")
        p, _ = self.start(path, "ok ")
        p.kill()
        p.communicate()
        # As if killed in the middle of a write: the file is cut short.
        size = os.path.getsize(path)
        with open(path, "r+b") as f:
            f.truncate(size // 2)
        r = self.resume_and_compare(path)
        self.assertIn("is damaged", r.stdout)
        self.assertIn("moved to " + path + ".damaged", r.stdout)
        self.assertIn("truncated file", r.stdout)  # HDF5's reason, not an empty one
        self.assertEqual(os.path.getsize(path + ".damaged"), size // 2)  # kept, untouched

    def test_a_half_written_part_is_removed_and_the_study_completes(self):
        # A part cut short while it was being written (killed between the copy and its
        # rename) is named *.tmp; --resume removes it and redoes nothing it held.
        path = os.path.join(scratch(), "cut.h5")
        p, _ = self.start(path, "ok ")
        p.kill()
        p.communicate()
        parts = path + ".parts"
        os.makedirs(parts, exist_ok=True)
        cut = os.path.join(parts, "spheres-r1.h5.tmp")
        with open(cut, "wb") as f:
            f.write(b"\x89HDF half")
        self.resume_and_compare(path)
        self.assertFalse(os.path.exists(cut))

    def test_retry_failed_runs_the_failed_run_again_and_no_other(self):
        folder = scratch()
        path = os.path.join(folder, "retry.h5")
        shutil.copy(REFERENCE[0], path)
        r = study(MIXED, "-o", path, "--resume", "--retry-failed", "--jobs", "1",
                  "--threads", "1")
        # huge-r1 blows up again: status 3, and it is the only run started.
        self.assertEqual(r.returncode, 3, r.stdout + r.stderr)
        started = [l.split()[1] for l in r.stdout.splitlines() if l.startswith("start")]
        self.assertEqual(started, ["huge-r1"])
        self.assertEqual(run_differences(REFERENCE[0], path), [])
        # Without --resume the flag is refused, naming both flags.
        r = study(MIXED, "-o", os.path.join(folder, "other.h5"), "--retry-failed")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("--retry-failed without --resume", r.stderr)

    def test_sigterm_abandons_the_run_in_flight_and_says_how_to_finish(self):
        path = os.path.join(scratch(), "term.h5")
        p, lines = self.start(path, "ok ")
        p.send_signal(signal.SIGTERM)
        out, _ = p.communicate()
        self.assertEqual(p.returncode, 128 + signal.SIGTERM)
        self.assertIn("--resume", out)
        with h5py.File(path, "r") as f:
            self.assertIn(self.run_named(lines[-1]), f["runs"])
        self.resume_and_compare(path)

    def test_sigint_lets_the_run_in_flight_finish_and_starts_no_other(self):
        path = os.path.join(scratch(), "int.h5")
        p, lines = self.start(path, "start ")
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate()
        self.assertEqual(p.returncode, 128 + signal.SIGINT, out)
        self.assertIn("--resume", out)
        first = self.run_named(lines[-1])
        # Dearest first: a clump run (about ten balls a body) before the sphere runs.
        self.assertIn(first, ("huge-r1", "T2S1-r1"))
        with h5py.File(path, "r") as f, h5py.File(REFERENCE[0], "r") as ref:
            # Only the run in flight, finished as it finishes in the uninterrupted study.
            self.assertEqual(list(f["runs"]), [first])
            self.assertEqual(text(f[f"runs/{first}"].attrs["status"]),
                             text(ref[f"runs/{first}"].attrs["status"]))
        self.resume_and_compare(path)

    def test_a_second_sigint_abandons_the_run_in_flight(self):
        path = os.path.join(scratch(), "int2.h5")
        # huge-r1 (dearest) fails in milliseconds; T2S1-r1 takes about two seconds.
        p, _ = self.start(path, "start  T2S1-r1")
        p.send_signal(signal.SIGINT)
        for line in p.stdout:
            if line.startswith("interrupted (SIGINT): no new run starts"):
                break
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate()
        self.assertEqual(p.returncode, 128 + signal.SIGINT, out)
        self.assertIn("abandoning the 1 runs in flight", out)
        with h5py.File(path, "r") as f:
            self.assertEqual(list(f["runs"]), ["huge-r1"])  # T2S1-r1 was abandoned
        self.resume_and_compare(path)

    def test_a_reader_holding_the_archive_is_waited_for(self):
        # h5py holds HDF5's file lock while the archive is open; the study waits for it
        # (up to 10 s, study/archive/study_store.cpp) instead of leaving the run in its part.
        # With one attempt only, the "cannot open ... to append" note would show.
        path = os.path.join(scratch(), "locked.h5")
        parts = path + ".parts"
        p = subprocess.Popen([binary.PATH, "study", MIXED, "-o", path, "--jobs", "1",
                              "--threads", "1", "--progress", "plain"],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        reader = None
        while reader is None:
            try:
                reader = h5py.File(path, "r")
            except OSError:  # not created yet, or the study has it open
                time.sleep(0.01)
        while not (os.path.isdir(parts) and any(n.endswith(".h5") for n in os.listdir(parts))):
            time.sleep(0.01)
        time.sleep(3.0)  # the first finished run now waits for the reader
        self.assertEqual(list(reader["runs"]), [])
        reader.close()
        out, _ = p.communicate(timeout=300)
        self.assertEqual(p.returncode, 3, out)
        self.assertNotIn("cannot open", out)
        self.assertEqual(run_differences(REFERENCE[0], path), [])

    def test_a_reader_that_stays_keeps_the_run_in_its_part_for_resume(self):
        # The reader holds the archive through the study (only huge-r1 runs again): the
        # run stays in its part, the study says why and how to finish (exit 1), and
        # --resume, once the reader is gone, appends it.
        folder = scratch()
        path = os.path.join(folder, "held.h5")
        shutil.copy(REFERENCE[0], path)
        with h5py.File(path, "r"):
            r = study(MIXED, "-o", path, "--resume", "--retry-failed", "--jobs", "1",
                      "--threads", "1")
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("cannot open " + path + " to append (unable to lock file", r.stdout)
        self.assertIn("1 finished runs could not be appended", r.stderr)
        self.assertIn("--resume", r.stderr)
        parts = [n for n in os.listdir(path + ".parts") if n.endswith(".h5")]
        self.assertEqual(len(parts), 1, parts)  # huge-r1's, kept
        r = study(MIXED, "-o", path, "--resume", "--jobs", "1", "--threads", "1")
        self.assertEqual(r.returncode, 3, r.stdout + r.stderr)
        self.assertNotIn("start ", r.stdout)  # nothing ran again
        self.assertEqual(run_differences(REFERENCE[0], path), [])
        self.assertFalse(os.path.exists(path + ".parts"))


class LiveProgress(unittest.TestCase):
    """--progress live redraws a block of lines (one per run in flight, then the counts)
    in place with ANSI "cursor up n lines" and "clear to the end" codes."""

    @staticmethod
    def screen(raw, test):
        """What a terminal shows after `raw`: each ESC[nF ESC[J removes the last n
        lines, which must all be the board's (indented two spaces)."""
        lines, erased_blocks = [], 0
        pieces = re.split("\033\\[(\\d+)F\033\\[J", raw)  # text, count, text, ...
        for k, piece in enumerate(pieces):
            if k % 2:
                n = int(piece)
                test.assertGreaterEqual(len(lines), n)
                for line in lines[-n:]:
                    test.assertTrue(line.startswith("  "), f"erased a result line: {line!r}")
                del lines[-n:]
                erased_blocks += 1
            else:
                test.assertNotIn("\033", piece)  # no other escape code
                lines.extend(piece.splitlines())
        return lines, erased_blocks

    def test_the_board_is_drawn_then_erased_leaving_one_line_per_run(self):
        path = os.path.join(scratch(), "live.h5")
        r = ballast("study", MIXED, "-o", path, "--jobs", "2", "--threads", "1",
                    "--progress", "live")
        self.assertEqual(r.returncode, 3, r.stderr)
        # The board was drawn: a run in flight with its stage, and the counts line.
        self.assertRegex(r.stdout, r"\n  \S+-r1 +\d+:\d\d  stage ")
        self.assertIn(" running, ", r.stdout)
        self.assertNotIn(" | stage", r.stdout)  # the run logs are for plain output
        lines, erased = self.screen(r.stdout, self)
        self.assertGreater(erased, 4)  # at least once per start and finish
        # Nothing of the board is left; each run has its one result line.
        self.assertFalse([l for l in lines if " running, " in l or "  stage " in l], lines)
        results = sorted(l.split()[1] for l in lines if l.startswith(("ok ", "FAILED ")))
        self.assertEqual(results, sorted(IDS))
        self.assertEqual(run_differences(REFERENCE[0], path), [])


class Refusals(unittest.TestCase):
    """An archive in the way is reported, never overwritten (exit 2)."""

    def copy_of_reference(self):
        path = os.path.join(scratch(), "copy.h5")
        shutil.copy(REFERENCE[0], path)
        with open(path, "rb") as f:
            return path, f.read()

    def assert_refused(self, r, path, before, *phrases):
        self.assertEqual(r.returncode, 2, r.stdout + r.stderr)
        for phrase in phrases:
            self.assertIn(phrase, r.stderr)
        with open(path, "rb") as f:
            self.assertEqual(f.read(), before)

    def test_dry_run_lists_every_run_with_its_seed_and_writes_nothing(self):
        path = os.path.join(scratch(), "dry.h5")
        r = study(MIXED, "-o", path, "--dry-run")
        self.assertEqual(r.returncode, 0, r.stderr)
        with h5py.File(REFERENCE[0], "r") as f:
            seeds = {k: int(f["runs"][k].attrs["seed"]) for k in f["runs"]}
        for run_id in IDS:
            line = next(l for l in r.stdout.splitlines() if f"  {run_id}  " in l)
            self.assertIn(f"seed {seeds[run_id]}", line)
        self.assertIn("nothing run or written", r.stdout)
        self.assertFalse(os.path.exists(path))
        self.assertFalse(os.path.exists(path + ".parts"))

    def test_every_shipped_study_passes_its_dry_run(self):
        studies = sorted(f for f in os.listdir(CASES) if f.endswith(".json"))
        self.assertIn("default_study.json", studies)
        for name in studies:
            with self.subTest(study=name):
                r = study(os.path.join(CASES, name), "-o", os.path.join(scratch(), "dry.h5"),
                          "--dry-run")
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertIn("nothing run or written", r.stdout)

    def test_a_trade_companion_study_runs_on_its_references_seeds(self):
        # scripts/tradeoff_table.py compares replicate k of a variant in the companion
        # study with replicate k of the reference in the main one: the same bed only
        # if both studies give replicate k the same seed.
        def seeds(name):
            r = study(os.path.join(CASES, name), "-o", os.path.join(scratch(), "d.h5"),
                      "--dry-run")
            self.assertEqual(r.returncode, 0, r.stderr)
            return dict(re.findall(r"^\s+\d+\s+(\S+)\s+seed (\d+)", r.stdout, re.M))

        for companion, main in [("tradeoff_extended.json", "tradeoff_study.json"),
                                ("tradeoff_spheres_extended.json", "tradeoff_spheres.json"),
                                ("tradeoff_full_cycles.json", "tradeoff_full.json")]:
            with self.subTest(companion=companion):
                reference, variants = seeds(main), seeds(companion)
                self.assertTrue(variants)
                for run_id, seed in variants.items():
                    replicate = run_id.rsplit("-", 1)[1]
                    self.assertEqual(seed, reference[f"reference-{replicate}"], run_id)

    def test_an_existing_archive_without_resume(self):
        path, before = self.copy_of_reference()
        self.assert_refused(study(MIXED, "-o", path), path, before, "already exists",
                            "--resume")

    def test_resuming_into_another_studys_archive(self):
        path, before = self.copy_of_reference()
        other = write_study(scratch(), lambda s: s.update(seed=12))
        self.assert_refused(study(other, "-o", path, "--resume"), path, before, "another study")

    def test_resuming_another_shard(self):
        path, before = self.copy_of_reference()
        self.assert_refused(study(MIXED, "-o", path, "--resume", "--shard", "1/2"), path, before,
                            "holds shard 1/1", "--shard 1/1")


class Shards(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = scratch()
        cls.shards = [os.path.join(cls.dir, f"shard{k}.h5") for k in (1, 2)]
        for k, path in zip((1, 2), cls.shards):
            r = study(MIXED, "-o", path, "--shard", f"{k}/2", "--jobs", "1")
            assert r.returncode in (0, 3), r.stderr

    def test_a_shard_holds_the_runs_whose_index_modulo_n_is_k_minus_1(self):
        with h5py.File(self.shards[0], "r") as f:
            self.assertEqual(sorted(f["runs"]), sorted(["spheres-r1", "spheres_dt-r1"]))
            self.assertEqual((f.attrs["shard_index"], f.attrs["shard_count"]), (1, 2))
            self.assertEqual(f.attrs["run_count"], 4)

    def test_merged_shards_equal_the_unsharded_study(self):
        out = os.path.join(scratch(), "merged.h5")
        r = ballast("merge", *self.shards, "-o", out)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertEqual(run_differences(REFERENCE[0], out), [])
        with h5py.File(out, "r") as f, h5py.File(REFERENCE[0], "r") as ref:
            self.assertEqual((f.attrs["shard_index"], f.attrs["shard_count"]), (1, 1))
            self.assertEqual(text(f.attrs["merged_from"]).split(), self.shards)
            self.assertEqual(f.attrs["fingerprint"], ref.attrs["fingerprint"])

    def test_an_incomplete_merge_names_the_missing_runs_and_resume_completes_it(self):
        out = os.path.join(scratch(), "half.h5")
        r = ballast("merge", self.shards[1], "-o", out)
        self.assertEqual(r.returncode, 4, r.stdout + r.stderr)
        self.assertIn("2 runs missing: spheres-r1 spheres_dt-r1", r.stdout)
        self.resume = study(MIXED, "-o", out, "--resume", "--jobs", "1")
        self.assertEqual(self.resume.returncode, 3, self.resume.stdout + self.resume.stderr)
        self.assertEqual(run_differences(REFERENCE[0], out), [])

    def test_merge_refuses_shards_of_another_study(self):
        d = scratch()
        other = write_study(d, lambda s: s.update(seed=12))
        path = os.path.join(d, "other.h5")
        study(other, "-o", path, "--shard", "1/4")
        out = os.path.join(d, "merged.h5")
        r = ballast("merge", self.shards[0], path, "-o", out)
        self.assertEqual(r.returncode, 2)
        self.assertIn("holds another study", r.stderr)
        self.assertFalse(os.path.exists(out))

    def test_merge_refuses_a_run_given_twice(self):
        out = os.path.join(scratch(), "twice.h5")
        r = ballast("merge", self.shards[0], self.shards[0], "-o", out)
        self.assertEqual(r.returncode, 2)
        self.assertIn("is in both", r.stderr)
        self.assertFalse(os.path.exists(out))

    def test_slurm_script_runs_the_shards_then_merges_them(self):
        d = scratch()
        env = dict(os.environ, PATH=os.path.join(HERE, "fake_slurm") + os.pathsep + os.environ["PATH"],
                   FAKE_SBATCH_LOG=os.path.join(d, "sbatch.log"), BALLAST=binary.PATH)
        script = os.path.join(HERE, "..", "..", "scripts", "slurm_study.sh")
        r = subprocess.run([script, MIXED, d, "2", "--cpus-per-task=1"], capture_output=True,
                           text=True, env=env, timeout=300)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        with open(os.path.join(d, "sbatch.log")) as f:
            jobs = f.read().splitlines()
        self.assertIn("--array=1-2", jobs[0])
        self.assertIn("--dependency=afterany:1001", jobs[1])
        self.assertEqual(run_differences(REFERENCE[0], os.path.join(d, "mixed.h5")), [])


class BadInput(unittest.TestCase):
    """Refused before anything runs: exit 2, the JSON path, the value, what is allowed,
    and no archive."""

    def assert_refused(self, study_file, *phrases, extra=()):
        d = os.path.dirname(study_file)
        out = os.path.join(d, "out.h5")
        r = study(study_file, "-o", out, *extra)
        self.assertEqual(r.returncode, 2, r.stdout + r.stderr)
        for phrase in phrases:
            self.assertIn(phrase, r.stderr)
        self.assertFalse(os.path.exists(out))
        self.assertFalse(os.path.exists(out + ".parts"))

    def test_unknown_key_in_the_study(self):
        f = write_study(scratch(), lambda s: s.update(sede=1))
        self.assert_refused(f, "at /sede", 'unknown key "sede"', "allowed: name, scene")

    def test_wrong_type_in_the_study(self):
        f = write_study(scratch(), lambda s: s.update(seed="eleven"))
        self.assert_refused(f, "at /seed", 'seed = "eleven"', "an unsigned integer")

    def test_out_of_range_value_in_the_study(self):
        f = write_study(scratch(),
                        lambda s: s["matrix"].update(axes={"local_damping": [0.5, 1.5]}))
        self.assert_refused(f, "at /matrix/axes/local_damping/1", "local_damping = 1.5",
                            "a number in [0, 1)")

    def test_value_the_scene_refuses_once_a_run_applies_it(self):
        # The study allows any count >= 1; the scene refuses more than its box holds.
        f = write_study(scratch(),
                        lambda s: s["matrix"].update(axes={"count": [40, 100000]}))
        self.assert_refused(f, "run 'spheres-count=100000-r1'",
                            "/particles/count = 100000", "1.8 box heights")

    def test_unknown_key_in_the_base_scene(self):
        d = scratch()
        f = write_study(d, lambda s: None)
        with open(os.path.join(d, "tiny.json")) as t:
            scene = json.load(t)
        scene["sleeper"]["lenght"] = 0.1
        with open(os.path.join(d, "tiny.json"), "w") as t:
            json.dump(scene, t)
        self.assert_refused(f, "at /scene", "unknown key /sleeper/lenght")

    def test_missing_scene_file(self):
        f = write_study(scratch(), lambda s: s.update(scene="nowhere.json"))
        self.assert_refused(f, 'scene = "nowhere.json" cannot be read')

    def test_bad_shard(self):
        self.assert_refused(write_study(scratch(), lambda s: None), '--shard = "3/2"',
                            "1 <= K <= N", extra=("--shard", "3/2"))

    def test_missing_output(self):
        r = study(MIXED)
        self.assertEqual(r.returncode, 2)
        self.assertIn("missing -o", r.stderr)


if __name__ == "__main__":
    binary.main()
