#!/usr/bin/env bash
# Installs, with apt-get, every Debian 12 package refmap needs to build, test, benchmark
# and plot, skipping what is already there. Run as root (or with sudo available).
set -euo pipefail
packages=(build-essential cmake pkg-config libeigen3-dev libgtest-dev libbenchmark-dev
          libtomlplusplus-dev libcli11-dev python3-matplotlib python3-numpy)
# optional: likwid marker regions (-DREFMAP_LIKWID=ON)
if [ "${REFMAP_WITH_LIKWID:-0}" = 1 ]; then packages+=(likwid); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
