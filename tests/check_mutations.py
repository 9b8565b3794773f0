#!/usr/bin/python3
"""Shows that the verification tests can fail: applies each one-line mutation listed
in tests/mutations.tsv to the engine, rebuilds the test that guards it, runs that
test and expects it to FAIL, then restores the file. A mutation the test survives
is a test that could not catch the bug it is named for.

    python3 tests/check_mutations.py [--build build] [--only TEXT]

Columns of mutations.tsv (tab-separated, '#' starts a comment line):
    test target, gtest filter, source file, text before, text after, what it breaks
"before" must occur exactly once in the file. Writes a markdown table to stdout
(docs/TESTING.md keeps the last one); exit status 1 when any mutation survives.
Needs a configured build directory; takes a few minutes (one rebuild per row).
"""
import argparse
import os
import pathlib
import signal
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent


def read_rows(path):
    rows = []
    for n, line in enumerate(path.read_text().splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        cols = line.split("\t")
        if len(cols) != 6:
            sys.exit(f"{path}:{n}: expected 6 tab-separated columns, found {len(cols)}")
        rows.append(dict(zip(["target", "filter", "file", "before", "after", "breaks"], cols)))
    return rows


def build(build_dir, target):
    r = subprocess.run(["cmake", "--build", str(build_dir), "--target", target, "-j2"],
                       capture_output=True, text=True)
    return r.returncode == 0, r.stdout + r.stderr


def run_test(build_dir, target, gtest_filter):
    exe = build_dir / "tests" / target
    env = dict(os.environ, OMP_NUM_THREADS="1")
    r = subprocess.run([str(exe), f"--gtest_filter={gtest_filter}"], capture_output=True,
                       text=True, env=env, timeout=900)
    return r.returncode == 0


def stop(signum, frame):
    # A plain kill would leave the file mutated, or a build finishing after it was
    # restored would leave objects newer than the restored source (make would then
    # keep the mutated ones): raise instead, so that subprocess.run stops its child
    # first and the `finally` below restores the file after it.
    raise KeyboardInterrupt


def main():
    signal.signal(signal.SIGTERM, stop)
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--only", default="", help="rows whose filter or file contain TEXT")
    ap.add_argument("--table", default=str(ROOT / "tests" / "mutations.tsv"))
    args = ap.parse_args()
    build_dir = pathlib.Path(args.build).resolve()
    rows = [r for r in read_rows(pathlib.Path(args.table))
            if args.only in r["filter"] or args.only in r["file"]]
    survived = 0
    print("| test | file | mutation | breaks | result |")
    print("|---|---|---|---|---|")
    for r in rows:
        src = ROOT / r["file"]
        original = src.read_text()
        if original.count(r["before"]) != 1:
            sys.exit(f"{r['file']}: '{r['before']}' occurs {original.count(r['before'])} times "
                     "(allowed: exactly once)")
        try:
            src.write_text(original.replace(r["before"], r["after"]))
            ok, log = build(build_dir, r["target"])
            if not ok:
                result = "killed (does not compile)"
            else:
                result = "survived" if run_test(build_dir, r["target"], r["filter"]) else "killed"
        finally:
            src.write_text(original)  # written after any build: newer than its objects
        survived += result == "survived"
        print(f"| {r['filter']} | {r['file']} | `{r['before']}` → `{r['after']}` | "
              f"{r['breaks']} | {result} |", flush=True)
    # Leave the build as the sources are.
    for target in sorted({r["target"] for r in rows}):
        build(build_dir, target)
    return 1 if survived else 0


if __name__ == "__main__":
    sys.exit(main())
