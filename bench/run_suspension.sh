#!/usr/bin/env bash
# Relative viscosity of a sheared suspension of soft discs against the area fraction, for
# stiff and for soft particles (results/suspension.md). Every run is
# bench/scenes/shear_suspension.toml (2 x 1 shear cell, walls at -U/2 and +U/2, gamma = 1,
# mu_f = rho = 1, discs of radius a = 0.1 = H / 10 placed at random by [suspension]) with
# the area fraction, the capillary number Ca = mu_f gamma / G (G = 2 mu_s) and the grid set
# by --set. bench/suspension.py then averages eta_r over t in [T0, T_END] (block averages
# for the error) and writes results/suspension/: suspension.csv, eta_vs_phi.png,
# eta_time_series.png, snapshot_stress.png.
#   bash bench/run_suspension.sh [BUILD_DIR]   # defaults build; 12 runs, 2217 s wall on 1
#                                              # thread on the loaded shared machine (load ~15)
# Knobs (environment): NX (128: 6.4 cells per radius), T_END (4), T0 (1), PHIS
# ("0.05 0.1 0.2 0.3"; 0.4 places, see results/suspension.md, but is run apart for time),
# CAS (capillary numbers; the first is the "stiff" one, "0.01 0.05 0.2"), SEED (1), JOBS
# (runs at once, 1 thread each; 1), RUNS (the run directories, kept; default a temporary
# directory), OUT (results/suspension), SNAP_PHI (0.3: the fraction whose runs keep VTK frames
# for the snapshot). The phi = 0.4 points (stiff and soft) are run apart:
#   PHIS=0.4 CAS="0.01 0.05 0.2" SNAP_PHI=0.4 OUT=results/suspension/dense bash bench/run_suspension.sh
# and the default run's chart adds results/suspension/dense/suspension.csv when it exists.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build}/refmap
NX=${NX:-128}
T_END=${T_END:-4}
T0=${T0:-1}
PHIS=${PHIS:-"0.05 0.1 0.2 0.3"}
CAS=${CAS:-"0.01 0.05 0.2"}
SEED=${SEED:-1}
JOBS=${JOBS:-1}
if [ -z "${RUNS:-}" ]; then
  RUNS=$(mktemp -d)
  trap 'rm -rf "$RUNS"' EXIT
fi
OUT=${OUT:-results/suspension}
mkdir -p "$RUNS" "$OUT"
stiff=${CAS%% *}
# one line per run: directory, phi, Ca; the snapshot case (phi = 0.3, or the largest phi
# below it) keeps its VTK frames
snap_phi=${SNAP_PHI:-0.3}
list="$RUNS/runs.txt"
: > "$list"
for phi in $PHIS; do
  for ca in $CAS; do
    echo "$RUNS/phi${phi}_ca${ca} $phi $ca" >> "$list"
  done
done
run_one() {
  local dir=$1 phi=$2 ca=$3
  # G = mu_f gamma / Ca and mu_s = G / 2 (the paper's sigma = 2 mu_s b)
  local mu_s
  mu_s=$(/usr/bin/python3 -c "print(repr(0.5 / $ca))")
  local vtk=false
  [ "$phi" = "$snap_phi" ] && vtk=true
  rm -rf "$dir"
  local rc=0
  OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE "$bin" run bench/scenes/shear_suspension.toml --out "$dir" --threads 1 \
    --quiet --set "grid.nx=$NX" --set "grid.ny=$((NX / 2))" --set "time.end=$T_END" \
    --set "suspension.area_fraction=$phi" --set "suspension.mu_s=$mu_s" --set "suspension.seed=$SEED" \
    --set "output.vtk=$vtk" 2> "$dir.err" || rc=$?
  echo "$rc" > "$dir.rc"
  echo "phi $phi Ca $ca: exit $rc" >&2
}
export -f run_one
export bin NX T_END SEED snap_phi
xargs -P "$JOBS" -L 1 bash -c 'run_one "$@"' _ < "$list"
/usr/bin/python3 bench/suspension.py --runs "$list" --t0 "$T0" --stiff "$stiff" --nx "$NX" --out "$OUT" \
  --extra results/suspension/dense/suspension.csv --dilute results/suspension/dilute.csv
