#!/usr/bin/env bash
# Installs the Debian packages named after the label, and only those that are
# missing; does nothing (and needs no network) when all are present. Shared by
# install-deps.sh (what Ballast needs) and install-peers.sh (LAMMPS and YADE).
#   scripts/install-packages.sh LABEL PACKAGE...
# Run as root on Debian 12; elsewhere it uses sudo when it can.
set -euo pipefail

label=$1
shift
packages=("$@")

missing=()
for p in "${packages[@]}"; do
  # dpkg-query reports "install ok installed" only for a fully installed package.
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "$label: all ${#packages[@]} packages present"
  exit 0
fi

echo "$label: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "$label: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "$label: done"
