#!/bin/bash
# The trials behind docs/TRIALS.md: full-scale box tests of
# seed 1, each changing one thing in the preparation or the loading, one thread each
# (about 3 hours on one core in all), then their table.
#
#   bash scripts/validation_trials.sh [DIR [NAME ...]]   (default DIR: results/trials)
#
# JOBS=2 runs two trials at a time. NAMEs pick trials (default: all, in the order
# below). A trial whose archive is already in DIR is not run again. The table, of
# every trial whose archive is in DIR, goes to stdout and to
# docs/validation/trials.csv.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-results/trials}
shift || true
bin=${BALLAST:-$root/build/study/ballast}
cases=$root/cases/box_test
jobs=${JOBS:-1}
mkdir -p "$dir"

# name scene [--set KEY=VALUE ...]: one per line, in the table's order.
read -r -d '' trials <<'LIST' || true
sph_ref spheres_settle_400k.json
sph_free spheres_settle_400k.json --set /preparation/levelling_pressure=0
sph_10kPa spheres_settle_400k.json --set /preparation/levelling_pressure=10000
sph_fric spheres_settle_400k.json --set /preparation/frictionless_settling=false
sph_base100 spheres_settle_400k.json --set /materials/base_stiffness=2.54e8
sph_nocreep spheres_settle_400k.json --set /preparation/seating_creep_rule=false
sph_1Hz spheres_settle_400k.json --set /sleeper/frequency=1
sph_edge25 spheres_settle_400k.json --set /sleeper/edge_radius=0.025
sph_seat09 spheres_settle_400k.json --set /preparation/seating_local_damping=0.9
s1_ref sample1_settle_400k.json
s1_free sample1_settle_400k.json --set /preparation/levelling_pressure=0 --set /particles/count=1936
s1_fric sample1_settle_400k.json --set /preparation/frictionless_settling=false
s1_edge25 sample1_settle_400k.json --set /sleeper/edge_radius=0.025
s1_seat09 sample1_settle_400k.json --set /preparation/seating_local_damping=0.9
LIST
# What each changes:
#   ref       the full-scale scenes with the frictionless settling stopped at
#             400,000 steps (box_test/*_settle_400k.json): the levelling plate at the
#             preload's pressure, a frictionless settling, frictional compaction at
#             10 g, 1 g, friction 0.5
#   free      no plate: the sleeper goes on the freely settled top (1,936 clumps fill
#             the box without a plate's compaction, as the paper's count does)
#   10kPa     a lighter plate
#   fric      frictional from the start, as the paper compacts its clumps (no
#             frictionless settling)
#   base100   a base 100 times stiffer than the paper's rubber
#   nocreep   the seating without its creep rule: equilibrium or the step limit
#   1Hz       a slower cycle: 1 Hz instead of 3
#   edge25    a sleeper whose long lower edges are rounded to 25 mm, about a ballast
#             particle's radius, instead of sharp
#   seat09    local damping 0.9 instead of 0.7 while the sleeper seats under the
#             preload (the cycle keeps 0.7)

trial() {  # trial NAME SCENE [--set KEY=VALUE ...]
  local name=$1 scene=$2
  shift 2
  [ -f "$dir/$name.h5" ] && return 0
  echo "trial $name: $scene $*" >&2
  "$bin" run "$cases/$scene" --threads 1 -o "$dir/$name.tmp.h5" "$@" > "$dir/$name.log" 2>&1
  mv "$dir/$name.tmp.h5" "$dir/$name.h5"
}

wanted=" $* "
running=0
while read -r name scene args; do
  [ $# -gt 0 ] && [[ $wanted != *" $name "* ]] && continue
  # shellcheck disable=SC2086  # args are --set KEY=VALUE words
  trial "$name" "$scene" $args &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n
    running=$((running - 1))
  fi
done <<< "$trials"
wait

labels=()
while read -r name _; do
  [ -f "$dir/$name.h5" ] && labels+=("$name=$dir/$name.h5")
done <<< "$trials"
mkdir -p "$root/docs/validation"
/usr/bin/python3 "$root/scripts/trials.py" "${labels[@]}" --csv "$root/docs/validation/trials.csv"
