#!/usr/bin/env bash
# Installs the two peer codes of `make bench-peers` (issue 7) when missing: LAMMPS
# (Debian's lammps: GRANULAR and RIGID, MPI through Open MPI's mpirun) and YADE.
# Kept apart from install-deps.sh on purpose: the build and the tests never need
# them, and CI must not install them.
set -euo pipefail

packages=(lammps yade openmpi-bin)

exec bash "$(dirname "$0")/install-packages.sh" install-peers "${packages[@]}"
