#!/usr/bin/env bash
# Installs, with apt-get, every Debian 12 package refmap needs to build, test, benchmark
# and plot, skipping what is already there. Run as root (or with sudo available).
set -euo pipefail
packages=(build-essential cmake pkg-config libeigen3-dev libgtest-dev libbenchmark-dev
          libtomlplusplus-dev libcli11-dev python3-matplotlib python3-numpy)
# optional: likwid marker regions (-DREFMAP_LIKWID=ON)
if [ "${REFMAP_WITH_LIKWID:-0}" = 1 ]; then packages+=(likwid); fi
if [ -n "${REFMAP_DEPS_PACKAGES:-}" ]; then read -ra packages <<< "$REFMAP_DEPS_PACKAGES"; fi

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
# Another installation may hold apt's locks (unattended upgrades, a second refmap command):
# wait for them instead of failing at once with "Could not get lock". DPkg::Lock::Timeout
# makes apt-get itself wait for the dpkg lock; the retry loop also covers the lists lock
# of `apt-get update`, which that option does not always cover. (APT_GET, APT_WAIT_S and
# REFMAP_DEPS_PACKAGES exist for tests/test_install_deps.sh.)
apt_wait() {
  local tries=0 log
  log=$(mktemp)
  until $SUDO "${APT_GET:-apt-get}" -o DPkg::Lock::Timeout=600 "$@" 2>"$log"; do
    if grep -q "Could not get lock\|Unable to acquire\|is another process using it" "$log" && [ $tries -lt 60 ]; then
      tries=$((tries + 1))
      echo "install-deps: apt is busy (another installation holds its lock); waiting ${APT_WAIT_S:-10} s ($tries/60)" >&2
      sleep "${APT_WAIT_S:-10}"
    else
      cat "$log" >&2; rm -f "$log"; return 1
    fi
  done
  cat "$log" >&2; rm -f "$log"
}
apt_wait update -qq
apt_wait install -y -qq --no-install-recommends "${missing[@]}"
