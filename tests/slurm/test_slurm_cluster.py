#!/usr/bin/python3
"""scripts/slurm_study.sh against a real Slurm: `make test-slurm` (docs/CLUSTER.md).
Needs the one-node cluster of scripts/slurm_local_cluster.sh (or any Slurm
whose jobs run on this machine), and is not part of ctest:

    bash scripts/slurm_local_cluster.sh start
    /usr/bin/python3 tests/slurm/test_slurm_cluster.py build/study/ballast
    bash scripts/slurm_local_cluster.sh stop

The study is tests/slurm/smoke_study.json: four runs of a few seconds, two per shard,
one after the other (one CPU per task). It is run once here with `ballast study` for
the reference archive, then submitted with `slurm_study.sh STUDY OUT 2 --requeue`.
Once each shard has finished its first run and is in the middle of its second:

- shard 1's task is requeued (`scontrol requeue`, what Slurm does on preemption or a
  node failure): Slurm kills it and runs it again, and `--resume` must keep the
  finished run and run only the abandoned one; the merge job must wait for it;
- shard 2's task is cancelled (`scancel`, as a time limit or a crash would end it):
  the merge job still runs (afterany) and must name the missing run.

Then the same command is submitted again, as docs/CLUSTER.md says to after a failure:
shard 1 has nothing left to do, shard 2 runs only its missing run, the first merge is
moved aside, and the merged archive must equal the reference bit for bit apart from
timings.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
from datetime import datetime, timezone

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(REPO, "tests", "cli"))
import binary  # noqa: E402
from archive_compare import run_differences  # noqa: E402

import h5py  # noqa: E402

STUDY = os.path.join(HERE, "smoke_study.json")
SCRIPT = os.path.join(REPO, "scripts", "slurm_study.sh")
SHARDS = 2
# --open-mode=append: a task run again appends to its log instead of starting it
# afresh, so the logs show every start.
SBATCH_OPTIONS = ["--cpus-per-task=1", "--requeue", "--open-mode=append"]
# slurm_study.sh names the merged archive after the study file.
MERGED_NAME = "smoke_study.h5"
# The cluster's logs, for the report of a failure (scripts/slurm_local_cluster.sh).
SLURM_LOCAL_DIR = os.environ.get("SLURM_LOCAL_DIR", "/var/lib/ballast-slurm")
# Generous: the whole test takes about a minute and a half on 2 cores.
WAIT_SECONDS = 600
POLL_SECONDS = 0.2
# Terminal states of a job (squeue(1), JOB STATE CODES).
ENDED = {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY",
         "BOOT_FAIL", "DEADLINE", "PREEMPTED"}

OUT = None        # the folder slurm_study.sh writes into
REFERENCE = None  # the study run here
SCENARIO = None   # what happened on the cluster: see run_on_the_cluster()
SUBMITTED = []    # the job ids slurm_study.sh printed
FAILED = False    # a test failed: OUT is kept for inspection


def command(*args, timeout=60):
    """Runs a Slurm command; raises with its output unless it exits 0."""
    r = subprocess.run(args, capture_output=True, text=True, timeout=timeout)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} exited {r.returncode}: {r.stdout}{r.stderr}")
    return r.stdout


def job(job_id):
    """`scontrol show job` of one job (of an array task: ARRAY_TASK) as a dict."""
    fields = {}
    for item in command("scontrol", "--oneliner", "show", "job", job_id).split():
        key, _, value = item.partition("=")
        fields[key] = value
    return fields


def read(name):
    path = os.path.join(OUT, name)
    if not os.path.exists(path):
        return ""
    with open(path, errors="replace") as f:
        return f.read()


def shard_log(k):
    return read(f"shard-{k}-of-{SHARDS}.log")


def merged():
    return os.path.join(OUT, MERGED_NAME)


def report():
    """What the queue, the jobs' logs and the daemons' logs say, for a failure message."""
    parts = []
    for args in (["squeue", "--all"], ["sinfo"]):
        r = subprocess.run(args, capture_output=True, text=True)
        parts.append(f"$ {' '.join(args)}\n{r.stdout}{r.stderr}")
    if OUT:
        for name in sorted(os.listdir(OUT)):
            if name.endswith(".log"):
                lines = read(name).splitlines(keepends=True)
                parts.append(f"--- {name} (last 40 lines)\n" + "".join(lines[-40:]))
    for name in ("slurmctld.log", "slurmd.log"):
        path = os.path.join(SLURM_LOCAL_DIR, "log", name)
        if os.path.exists(path):
            with open(path, errors="replace") as f:
                parts.append(f"--- {path} (last 20 lines)\n" + "".join(f.readlines()[-20:]))
    return "\n".join(parts)


def wait_for(what, condition):
    """Polls condition() until it returns something true, and returns that; raises
    with the cluster's report after WAIT_SECONDS."""
    deadline = time.monotonic() + WAIT_SECONDS
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(POLL_SECONDS)
    raise AssertionError(f"gave up after {WAIT_SECONDS} s waiting for {what}\n{report()}")


def oks(log):
    """The runs a log says finished, in order."""
    return re.findall(r"^ok\s+(\S+) in ", log, re.MULTILINE)


def headers(log):
    """The line `ballast study` starts with: one per start of the task."""
    return re.findall(r"^study 'slurm_smoke' .*$", log, re.MULTILINE)


def utc_seconds(stamp):
    text = stamp.decode() if isinstance(stamp, bytes) else stamp
    return datetime.strptime(text, "%Y-%m-%dT%H:%M:%SZ").replace(tzinfo=timezone.utc).timestamp()


def submit():
    """slurm_study.sh STUDY OUT 2 SBATCH_OPTIONS: the array job's and the merge job's ids."""
    r = subprocess.run([SCRIPT, STUDY, OUT, str(SHARDS), *SBATCH_OPTIONS], capture_output=True,
                       text=True, env=dict(os.environ, BALLAST=binary.PATH), timeout=120)
    if r.returncode != 0:
        raise RuntimeError(f"slurm_study.sh exited {r.returncode}:\n{r.stdout}{r.stderr}")
    m = re.search(rf"array job (\d+) \({SHARDS} shards\), merge job (\d+)", r.stdout)
    if not m:
        raise RuntimeError(f"slurm_study.sh printed no job ids:\n{r.stdout}{r.stderr}")
    SUBMITTED.extend(m.groups())
    return m.groups()


def wait_until_ended(job_id):
    return wait_for(f"job {job_id} to end",
                    lambda: job(job_id).get("JobState") in ENDED and job(job_id))


def run_on_the_cluster():
    """Submits the study, interrupts both shards in their second run (requeue, cancel),
    waits for the merge, submits again and waits for that merge. Returns what the tests
    look at."""
    array, merge = submit()
    tasks = {k: f"{array}_{k}" for k in range(1, SHARDS + 1)}

    # A shard's task is in the middle of its second run once its log says the first
    # finished and the task still runs (each run takes seconds; this polls every 0.2 s).
    def in_second_run(k):
        log = shard_log(k)
        return len(oks(log)) == 1 and job(tasks[k]).get("JobState") == "RUNNING"

    interrupted = {}  # shard -> (the run finished before, when)
    actions = {1: ("scontrol", "requeue"), 2: ("scancel",)}

    def interrupt_each_in_its_second_run():
        for k, action in actions.items():
            if k not in interrupted and len(oks(shard_log(k))) > 1:
                raise AssertionError(f"shard {k} finished both runs before the test could "
                                     f"interrupt the second (its runs too short here?)\n{report()}")
            if k not in interrupted and in_second_run(k):
                interrupted[k] = (oks(shard_log(k))[0], time.time())
                command(*action, tasks[k])
        return len(interrupted) == len(actions)
    wait_for("each shard to finish its first run", interrupt_each_in_its_second_run)

    # Slurm makes a requeued job wait about two minutes before it may start again
    # (its EligibleTime). Nothing is being tested by that wait, but the task may not
    # start within the second its first start was killed in: slurmd revoked that
    # start's credential then and refuses every credential of the job created no
    # later, in whole seconds (slurm_cred.c), which fails the task (FAILED 1:0,
    # nothing logged). slurmd revokes before it signals, so once the log shows the
    # SIGTERM, a start two seconds on is safe.
    wait_for(f"{tasks[1]} to be pending again after the requeue, its first start "
             "interrupted",
             lambda: job(tasks[1]).get("JobState") == "PENDING"
             and "interrupted (SIGTERM)" in shard_log(1))
    command("scontrol", "update", f"JobId={tasks[1]}", "StartTime=now+2")
    first_merge = wait_until_ended(merge)
    first = {"tasks": {k: job(t) for k, t in tasks.items()}, "merge": first_merge,
             "merge_log": read("merge.log"),
             "logs": {k: shard_log(k) for k in tasks}}

    # As after any failure: the same command again.
    resubmitted_at = time.time()
    array2, merge2 = submit()
    second_merge = wait_until_ended(merge2)
    second = {"tasks": {k: job(f"{array2}_{k}") for k in tasks}, "merge": second_merge}
    return {"first": first, "second": second, "interrupted": interrupted,
            "resubmitted_at": resubmitted_at, "merge_job": merge2,
            "logs": {k: shard_log(k) for k in tasks}, "merge_log": read("merge.log")}


def setUpModule():
    global OUT, REFERENCE, SCENARIO
    r = subprocess.run(["sinfo", "--noheader", "--format=%T"], capture_output=True, text=True)
    if r.returncode != 0 or "idle" not in r.stdout.split():
        raise RuntimeError("no idle Slurm node (sinfo: "
                           f"{(r.stdout + r.stderr).strip() or 'nothing'}); start one with "
                           "`bash scripts/slurm_local_cluster.sh start`")
    OUT = tempfile.mkdtemp(prefix="ballast-slurm-")
    REFERENCE = os.path.join(OUT, "reference.h5")
    try:
        binary.succeed("study", STUDY, "-o", REFERENCE, "--progress", "plain")
        SCENARIO = run_on_the_cluster()
    except BaseException:
        # Jobs left in the queue would go on writing into OUT.
        if SUBMITTED:
            subprocess.run(["scancel", *SUBMITTED], capture_output=True)
        print(f"\nkept {OUT} for inspection", file=sys.stderr)
        raise


def tearDownModule():
    # A test that failed may leave a task running (a merge that did not wait for it).
    subprocess.run(["scancel", *SUBMITTED], capture_output=True)
    if FAILED:
        print(f"\nkept {OUT} for inspection", file=sys.stderr)
    else:
        shutil.rmtree(OUT, ignore_errors=True)


class SlurmStudy(unittest.TestCase):

    def run(self, result=None):
        result = super().run(result)
        if result is not None and not result.wasSuccessful():
            global FAILED
            FAILED = True
        return result

    def shard_runs(self, k):
        """The ids of shard k's runs (index % SHARDS == k - 1), from the reference."""
        with h5py.File(REFERENCE, "r") as f:
            return [r["id"] for r in json.loads(f["study_runs"][()])
                    if r["index"] % SHARDS == k - 1]

    def interrupted_run(self, k):
        """The run shard k had in flight when it was interrupted."""
        before, _ = SCENARIO["interrupted"][k]
        after, = [r for r in self.shard_runs(k) if r != before]
        return after

    def assert_state(self, j, state, exit_code, what):
        self.assertEqual((j["JobState"], j["ExitCode"]), (state, exit_code),
                         f"{what} (job {j['JobId']})\n{report()}")

    def test_the_requeued_task_ran_again_and_finished(self):
        t = SCENARIO["first"]["tasks"][1]
        self.assertEqual(t["Restarts"], "1", report())
        self.assert_state(t, "COMPLETED", "0:0", "shard 1, requeued")

    def test_the_cancelled_task_stayed_cancelled(self):
        t = SCENARIO["first"]["tasks"][2]
        self.assertEqual(t["Restarts"], "0", report())
        self.assert_state(t, "CANCELLED", "0:15", "shard 2, cancelled")  # by SIGTERM

    def test_the_requeued_task_resumed_its_shard(self):
        log = SCENARIO["first"]["logs"][1]
        starts = headers(log)
        self.assertEqual(len(starts), 2, log)
        self.assertIn("0 in the archive, 2 to run", starts[0])
        self.assertIn("1 in the archive, 1 to run", starts[1])  # --resume kept the first run
        self.assertIn("DUE TO JOB REQUEUE", log)
        self.assertIn("interrupted (SIGTERM)", log)
        # Each run finished once: the one done before the requeue was not run again.
        self.assertEqual(sorted(oks(log)), sorted(self.shard_runs(1)), log)

    def test_the_merge_waited_for_the_requeued_task_and_named_the_cancelled_run(self):
        first = SCENARIO["first"]
        # It ended after the requeued task, whose runs it has, and says what is missing.
        self.assertGreaterEqual(first["merge"]["EndTime"], first["tasks"][1]["EndTime"])
        self.assert_state(first["merge"], "FAILED", "4:0", "the first merge (a run missing)")
        self.assertRegex(first["merge_log"], rf"\b1 runs? missing: {self.interrupted_run(2)}\n")
        with h5py.File(os.path.join(OUT, f"{MERGED_NAME}.before-job-{SCENARIO['merge_job']}"),
                       "r") as f:
            self.assertEqual(sorted(f["runs"]), sorted(self.shard_runs(1) +
                                                       [SCENARIO["interrupted"][2][0]]))

    def test_the_second_submission_ran_only_the_missing_run(self):
        for k, t in SCENARIO["second"]["tasks"].items():
            self.assert_state(t, "COMPLETED", "0:0", f"shard {k}, second submission")
        self.assert_state(SCENARIO["second"]["merge"], "COMPLETED", "0:0", "the second merge")
        starts = {k: headers(log) for k, log in SCENARIO["logs"].items()}
        self.assertEqual(len(starts[1]), 3, SCENARIO["logs"][1])
        self.assertIn("2 in the archive, 0 to run", starts[1][2])
        self.assertEqual(len(starts[2]), 2, SCENARIO["logs"][2])
        self.assertIn("1 in the archive, 1 to run", starts[2][1])
        self.assertEqual(oks(SCENARIO["logs"][2]),
                         [SCENARIO["interrupted"][2][0], self.interrupted_run(2)])
        self.assertIn("moved the earlier merge aside", SCENARIO["merge_log"])

    def test_each_interrupted_run_was_run_again_and_only_it(self):
        with h5py.File(merged(), "r") as f:
            runs = f["runs"]
            for k, since in ((1, SCENARIO["interrupted"][1][1]), (2, SCENARIO["resubmitted_at"])):
                before, at = SCENARIO["interrupted"][k]
                # Stamps are whole seconds: a run finished before the interruption
                # carries the second it finished in, at most the interruption's.
                self.assertLessEqual(utc_seconds(runs[before].attrs["finished"]), at, before)
                self.assertGreaterEqual(utc_seconds(runs[self.interrupted_run(k)].attrs["started"]),
                                        int(since), self.interrupted_run(k))

    def test_the_merged_archive_equals_the_study_run_here(self):
        with h5py.File(merged(), "r") as f:
            self.assertEqual(f.attrs["run_count"], 4)
            self.assertEqual(sorted(f["runs"]), ["T2S1-r1", "T2S1-r2", "T2S1-r3", "T2S1-r4"])
        self.assertEqual(run_differences(REFERENCE, merged()), [])


if __name__ == "__main__":
    binary.main()
