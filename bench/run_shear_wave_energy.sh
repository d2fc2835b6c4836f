#!/usr/bin/env bash
# The finite-amplitude shear wave's total energy against the solid step (docs/method.md, "Time
# step"; results/stability.md, "Energy of the elastic coupling"): scenes/shear_wave.toml on 64^2
# (64 cells per wavelength) over four periods, solids.solid_cfl = P from 1 to 0.075, both stress
# forms (cell, face), both elastic couplings (time.elastic_coupling = "symplectic_euler", Algorithm
# 1, and "verlet"). 20 runs, one thread each, one at a time (~5 min on a loaded 2-core machine).
#
#   bash bench/run_shear_wave_energy.sh
#
# Knobs: BIN (refmap executable, default build/refmap), OUT (default results),
# RAW (run directories, default /tmp/refmap_shear_wave_energy).
# Output: results/shear_wave_energy.csv.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
export OMP_NUM_THREADS=1
exec nice python3 bench/shear_wave_energy.py --bin "${BIN:-build/refmap}" --out "${OUT:-results}" \
  --raw "${RAW:-/tmp/refmap_shear_wave_energy}" "$@"
