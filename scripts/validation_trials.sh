#!/bin/bash
# The trials behind docs/VALIDATION.md's "What was tried": full-scale box tests of
# seed 1, each changing one thing in the preparation or the loading, one thread each,
# one after another (about 2 hours on one core), then their table.
#
#   bash scripts/validation_trials.sh [DIR]      (default DIR: results/trials)
#
# A trial whose archive is already in DIR is not run again. The table goes to stdout
# and to docs/validation/trials.csv.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-results/trials}
bin=${BALLAST:-$root/build/study/ballast}
cases=$root/cases/box_test
mkdir -p "$dir"

trial() {  # trial NAME SCENE [--set KEY=VALUE ...]
  local name=$1 scene=$2
  shift 2
  [ -f "$dir/$name.h5" ] && return 0
  echo "trial $name: $(basename "$scene") $*" >&2
  "$bin" run "$cases/$scene" --threads 1 -o "$dir/$name.tmp.h5" "$@" > "$dir/$name.log" 2>&1
  mv "$dir/$name.tmp.h5" "$dir/$name.h5"
}

# The scenes as they are: the levelling plate at the preload's pressure, a
# frictionless settling, frictional compaction at 10 g, 1 g, friction 0.5.
trial sph_ref spheres.json
trial s1_ref sample1.json
# No plate: the sleeper goes on the freely settled top (1,936 clumps fill the box
# without a plate's compaction, as the paper's count does).
trial sph_free spheres.json --set /preparation/levelling_pressure=0
trial s1_free sample1.json --set /preparation/levelling_pressure=0 --set /particles/count=1936
# A lighter plate.
trial sph_10kPa spheres.json --set /preparation/levelling_pressure=10000
# Frictional from the start, as the paper compacts its clumps (no frictionless settling).
trial sph_fric spheres.json --set /preparation/frictionless_settling=false
trial s1_fric sample1.json --set /preparation/frictionless_settling=false
# A base 100 times stiffer than the paper's rubber.
trial sph_base100 spheres.json --set /materials/base_stiffness=2.54e8
# The seating without its creep rule: equilibrium or the step limit.
trial sph_nocreep spheres.json --set /preparation/seating_creep_rule=false
# A slower cycle: 1 Hz instead of 3.
trial sph_1Hz spheres.json --set /sleeper/frequency=1

labels=()
for name in sph_ref sph_free sph_10kPa sph_fric sph_base100 sph_nocreep sph_1Hz \
            s1_ref s1_free s1_fric; do
  labels+=("$name=$dir/$name.h5")
done
mkdir -p "$root/docs/validation"
/usr/bin/python3 "$root/scripts/trials.py" "${labels[@]}" --csv "$root/docs/validation/trials.csv"
