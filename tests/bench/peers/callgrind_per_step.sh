#!/bin/bash
# Instructions per ball-step of our engine and of LAMMPS on the cached sphere bed
# (docs/PERFORMANCE.md, "Peers"), counted by callgrind: each code runs N1 and N2 steps
# from the same packing and the difference of the two totals, over (N2 - N1) × balls,
# leaves set-up and output out. Needs `make bench-peers` run once (the bed and the
# LAMMPS input it writes; without that input, ours alone is counted) and valgrind.
# One thread / one process; a few minutes. Valgrind runs no AVX-512: it counts the
# AVX2 kernel.
#
#   tests/bench/peers/callgrind_per_step.sh [N1 N2]
#   BALLAST=build/revisions/REV/build/study/ballast tests/bench/peers/callgrind_per_step.sh
#     (another build of ours, e.g. one compare_revisions.py made)
set -euo pipefail
cd "$(dirname "$0")/../../.."
n1=${1:-500}
n2=${2:-1500}
ballast=${BALLAST:-build/study/ballast}
bed=build/peers/spheres.txt
lammps_in=build/peers/runs/spheres_lammps_1
[ -f "$bed" ] || { echo "run make bench-peers once first" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
balls=$(grep -cv '^\s*#' "$bed")

instructions() {  # total Ir of a callgrind run of "$@"
  valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" "$@" > /dev/null 2>&1
  callgrind_annotate "$work/cg.out" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}'
}

ours() {
  OMP_NUM_THREADS=1 instructions "$ballast" bench-bed "$bed" --steps "$1" --threads 1 \
    --json --stiffness 5.08e9 --friction 0.3 --dt 1e-6 --density 2600
}

lammps() {  # the benchmark's input, run for $1 steps, without its dumps
  local d="$work/lammps_$1"
  mkdir -p "$d"
  cp "$lammps_in/bed.data" "$d/"
  sed -e "s/^run [0-9]*$/run $1/" -e '/^write_dump/,$d' "$lammps_in/in.bed" > "$d/in.bed"
  (cd "$d" && OMP_NUM_THREADS=1 instructions lmp -in in.bed -log none -screen none)
}

per_step() {  # (Ir(n2) - Ir(n1)) / ((n2 - n1) * balls)
  echo "$1 $2" | awk -v n=$((n2 - n1)) -v b="$balls" '{printf "%.0f", ($2 - $1) / (n * b)}'
}

o1=$(ours "$n1"); o2=$(ours "$n2")
echo "sphere bed, $balls balls, steps $n1 and $n2, instructions per ball-step:"
echo "  ballast: $(per_step "$o1" "$o2")"
if [ -f "$lammps_in/in.bed" ]; then
  l1=$(lammps "$n1"); l2=$(lammps "$n2")
  echo "  lammps:  $(per_step "$l1" "$l2")"
else
  echo "  lammps:  not counted (no $lammps_in/in.bed: make bench-peers writes it)"
fi
