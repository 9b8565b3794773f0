#!/usr/bin/env bash
# Installs the Debian packages Ballast needs, and only those that are missing.
# Does nothing (and needs no network) when everything is already present.
# Run as root on Debian 12; elsewhere it uses sudo when it can.
set -euo pipefail

packages=(
  build-essential cmake make g++
  libeigen3-dev libhdf5-dev nlohmann-json3-dev
  libgtest-dev libcli11-dev libbenchmark-dev
  python3 python3-h5py python3-numpy python3-matplotlib
  hdf5-tools
  clang-format
)

exec bash "$(dirname "$0")/install-packages.sh" install-deps "${packages[@]}"
