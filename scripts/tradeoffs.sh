#!/bin/bash
# Speed against accuracy on the box test in one command (docs/TRADEOFFS.md): the
# studies, then the table, CSV and Pareto plot of Table 2 Sample 1 and of spheres.
#
#   bash scripts/tradeoffs.sh [smoke|extended|full] [DIR]   (make tradeoffs [SCALE=...])
#
# smoke     cases/tradeoff_study.json (Sample 1) and tradeoff_spheres.json: 240
#           particles, one variant per knob and the presets, 72 runs, under half an
#           hour on 2 cores; tables into docs/tradeoffs and docs/tradeoffs/spheres.
# extended  smoke's studies (resumed from smoke's archives) and the variants it leaves
#           out, tradeoff_extended.json and tradeoff_spheres_extended.json: 99 runs;
#           tables into docs/tradeoffs/extended and docs/tradeoffs/extended/spheres.
# full      cases/tradeoff_full.json + tradeoff_full_cycles.json (Sample 1) and
#           tradeoff_full_spheres.json: the paper's box, 63 runs, overnight; tables into
#           docs/tradeoffs/full and docs/tradeoffs/full/spheres.
# The archives go to DIR (default build/tradeoffs/SCALE; extended shares smoke's). A
# study whose archive is there already is resumed, not redone: a night cut short goes
# on where it stopped. BALLAST (default build/study/ballast), JOBS (runs side by side,
# default 2) and DOCS (default docs/tradeoffs) override the defaults. Ends with the
# wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
scale=${1:-smoke}
dir=${2:-build/tradeoffs/${scale/extended/smoke}}
ballast=${BALLAST:-build/study/ballast}
jobs=${JOBS:-2}
docs=${DOCS:-docs/tradeoffs}
# balanced sets dt_safety 1 and nothing else: its runs are the dt_safety-1 rows.
marks=balanced=dt_safety-1,fast=preset-fast
case "$scale" in
  smoke) clumps=(tradeoff_study) spheres=(tradeoff_spheres) out=$docs ;;
  extended)
    clumps=(tradeoff_study tradeoff_extended)
    spheres=(tradeoff_spheres tradeoff_spheres_extended) out=$docs/extended ;;
  full) clumps=(tradeoff_full tradeoff_full_cycles) spheres=(tradeoff_full_spheres) out=$docs/full ;;
  *) echo "tradeoffs.sh: scale = '$scale' (allowed: smoke, extended or full)" >&2; exit 2 ;;
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

studies() {  # studies NAME...: each study, then its archives' paths in $archives
  archives=()
  for name in "$@"; do
    study "$name"
    archives+=("$dir/$name.h5")
  done
}

studies "${clumps[@]}"
clump_archives=("${archives[@]}")
studies "${spheres[@]}"
/usr/bin/python3 scripts/tradeoff_table.py "${clump_archives[@]}" --out "$out" --mark "$marks"
/usr/bin/python3 scripts/tradeoff_table.py "${archives[@]}" --out "$out/spheres" --mark "$marks"
minutes=$(( (SECONDS - start + 30) / 60 ))
echo "tradeoffs.sh: $scale scale, $jobs runs side by side: $minutes min of wall time"
