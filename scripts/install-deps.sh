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

missing=()
for p in "${packages[@]}"; do
  # dpkg-query reports "install ok installed" only for a fully installed package.
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
