#!/bin/bash
# Speed against accuracy on the box test in one command (docs/TRADEOFFS.md): the
# studies, then the table, CSV and Pareto plot of Table 2 Sample 1 and of spheres.
#
#   bash scripts/tradeoffs.sh [smoke|full] [DIR]        (make tradeoffs [SCALE=full])
#
# smoke  cases/tradeoff_study.json + tradeoff_presets.json (Sample 1) and
#        tradeoff_spheres.json: 240 particles, 99 runs; tables into docs/tradeoffs and
#        docs/tradeoffs/spheres.
# full   cases/tradeoff_full.json (Sample 1) and tradeoff_full_spheres.json: the paper's
#        box, 57 runs, overnight; tables into docs/tradeoffs/full and
#        docs/tradeoffs/full/spheres.
# The archives go to DIR (default build/tradeoffs/SCALE). A study whose archive is
# there already is resumed, not redone: a night cut short goes on where it stopped.
# BALLAST (default build/study/ballast), JOBS (runs side by side, default 2) and
# DOCS (default docs/tradeoffs) override the defaults. Ends with the wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-smoke}
dir=${2:-build/tradeoffs/$scale}
ballast=${BALLAST:-build/study/ballast}
jobs=${JOBS:-2}
docs=${DOCS:-docs/tradeoffs}
# balanced sets dt_safety 1 and nothing else: its runs are the dt_safety-1 rows.
marks=balanced=dt_safety-1,fast=preset-fast
case "$scale" in
  smoke) clumps=(tradeoff_study tradeoff_presets) spheres=tradeoff_spheres out=$docs ;;
  full) clumps=(tradeoff_full) spheres=tradeoff_full_spheres out=$docs/full ;;
  *) echo "tradeoffs.sh: scale = '$scale' (allowed: smoke or full)" >&2; exit 2 ;;
esac
[ -x "$ballast" ] || { echo "tradeoffs.sh: no binary at $ballast (run make build)" >&2; exit 2; }
mkdir -p "$dir"
start=$SECONDS

study() {  # study NAME: cases/NAME.json into DIR/NAME.h5, resumed if it is there
  local archive=$dir/$1.h5 resume=()
  [ -e "$archive" ] && resume=(--resume)
  echo "== $1 -> $archive"
  # Exit 3: some runs failed (named in the study's table); the others make the table.
  "$ballast" study "cases/$1.json" -o "$archive" --jobs "$jobs" --threads 1 "${resume[@]}" ||
    { local status=$?; [ "$status" -eq 3 ] || exit "$status"; }
}

archives=()
for name in "${clumps[@]}"; do
  study "$name"
  archives+=("$dir/$name.h5")
done
study "$spheres"
/usr/bin/python3 scripts/tradeoff_table.py "${archives[@]}" --out "$out" --mark "$marks"
/usr/bin/python3 scripts/tradeoff_table.py "$dir/$spheres.h5" --out "$out/spheres" --mark "$marks"
minutes=$(( (SECONDS - start + 30) / 60 ))
echo "tradeoffs.sh: $scale scale, $jobs runs side by side: $minutes min of wall time"
