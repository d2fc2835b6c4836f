#!/usr/bin/env bash
# Where each method fails (results/stability.md): stability and robustness maps from whole runs of
# build/refmap on coarse grids (bench/stability.py says what is swept and how each run is
# classified). Regenerates results/stability.csv, results/stability_limits.csv and the
# charts results/stability_{solid_cfl,deformation,density,contact,resolution}.png and the
# snapshots of each failure, results/stability_failures.png.
#
#   bash bench/run_stability.sh            # full (minutes on 2 cores)
#   bash bench/run_stability.sh --quick    # a subset of methods and values
#
# Knobs: BUILD (build directory, default build); OUT (default results); JOBS (parallel
# single-thread runs, default 2); SWEEPS (default a,b,c,d,e); PYTHON. Extra arguments go to
# bench/stability.py (e.g. --figure no, --figure only).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BUILD="${BUILD:-build}"
PYTHON="${PYTHON:-/usr/bin/python3}"
echo "== build refmap ($BUILD)"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j2 --target refmap >/dev/null
T0=$(date +%s)
"$PYTHON" bench/stability.py --bin "$BUILD/refmap" --out "${OUT:-results}" --jobs "${JOBS:-2}" \
  --sweeps "${SWEEPS:-a,b,c,d,e}" "$@"
echo "== done in $(( $(date +%s) - T0 )) s"
