#!/usr/bin/env bash
# Flow past a fixed cylinder at Re = 20 (Schafer & Turek 1996, test 2D-1;
# docs/references.md#cylinder-in-a-channel-at-re--20): scenes/cylinder_re20.toml run to its steady state on several
# grids, then bench/cylinder_summary.py writes results/cylinder_re20.csv (c_D, c_L, Delta p,
# recirculation length per grid, and the published bounds).
#
#   bash bench/run_cylinder.sh                  # dx = 0.01, 0.005, 0.0025 (~15 min, loaded machine)
#   GRIDS="0.01 0.005" bash bench/run_cylinder.sh
#
# Knobs: BIN (refmap executable, default build/refmap), RAW (run directories, default
# /tmp/refmap_cylinder), GRIDS (dx values among 0.01 0.005 0.0025), THREADS (default 1; the
# 0.0025 grid uses THREADS_FINE, default 2, with OMP_WAIT_POLICY=PASSIVE: docs/performance.md, threads),
# VISCOUS ("explicit" or "implicit", default "implicit": on the finer grids the explicit
# viscous limit rho dx^2 / (6 mu) is below the advective one, see results/validation.md),
# RADIUS_STUDY (default 1: one extra run on dx = 0.005 with the radius reduced by dx/2, to
# measure where the diffuse surface of the direct forcing sits), FINE_STEPS (default 2600: the
# 0.0025 grid stops after 2600 steps, t = 6.03, instead of its steady state near t = 17; on the
# coarser grids c_D, c_L at t = 6 are within 1e-4 of their steady values. A step count, not an
# end time: a last step cut short to land on an end time spoils the force and the pressure), DT_STUDY (default 1: the
# 0.01 grid again at dt / 2 and dt / 4, the forcing's dependence on dt), FORCING ("diffuse" or
# "interpolated": the cylinder's `forcing`, docs/bodies.md; default: the scene's; the run names
# get the prefix "$FORCING_"), CSV (default results/cylinder_re20.csv). results/cylinder_re20.csv
# holds both: the rows of a run with FORCING=diffuse and one with FORCING=interpolated
# RADIUS_STUDY=0 THREADS_FINE=1, the reference rows once.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BIN="${BIN:-build/refmap}"
RAW="${RAW:-/tmp/refmap_cylinder}"
GRIDS="${GRIDS:-0.01 0.005 0.0025}"
VISCOUS="${VISCOUS:-implicit}"
mkdir -p "$RAW"
export OMP_WAIT_POLICY=PASSIVE

run() {  # run NAME DX THREADS [extra --set ..., a later time.dt wins]
  local name=${FORCING:+${FORCING}_}$1 dx=$2 threads=$3
  shift 3
  local nx ny
  nx=$(python3 -c "print(round(2.2 / $dx))")
  ny=$(python3 -c "print(round(0.41 / $dx))")
  dt=$(python3 -c "print(0.9278 * $dx)")  # the scene's dt = 0.9278 dx on every grid
  local forcing=()
  [ -n "${FORCING:-}" ] && forcing=(--set "solid[0].forcing=\"$FORCING\"")
  echo "cylinder_re20: $name (dx = $dx, $nx x $ny, $threads thread(s), viscous = $VISCOUS${FORCING:+, forcing = $FORCING})" >&2
  OMP_NUM_THREADS=$threads nice "$BIN" run scenes/cylinder_re20.toml --out "$RAW/$name" --quiet \
    --set grid.nx="$nx" --set grid.ny="$ny" --set time.dt="$dt" --set output.vtk=false --set output.diagnostics_every=10 \
    --set time.viscous="\"$VISCOUS\"" "${forcing[@]}" "$@" > "$RAW/$name.log" 2>&1 || { cat "$RAW/$name.log" >&2; exit 1; }
}

dirs=()
for dx in $GRIDS; do
  threads="${THREADS:-1}"
  extra=()
  if [ "$dx" = "0.0025" ]; then
    threads="${THREADS_FINE:-2}"
    extra=(--set "time.max_steps=${FINE_STEPS:-2600}")
  fi
  run "dx_$dx" "$dx" "$threads" "${extra[@]}"
  dirs+=("$RAW/${FORCING:+${FORCING}_}dx_$dx")
done
if [ "${RADIUS_STUDY:-1}" = "1" ]; then
  run "dx_0.005_r0.0475" 0.005 "${THREADS:-1}" --set 'solid[0].radius=0.0475'
  dirs+=("$RAW/${FORCING:+${FORCING}_}dx_0.005_r0.0475")
fi
if [ "${DT_STUDY:-1}" = "1" ]; then  # the coarse grid at dt / 2 and dt / 4
  for f in 2 4; do
    run "dx_0.01_dt$f" 0.01 "${THREADS:-1}" --set "time.dt=$(python3 -c "print(0.009278 / $f)")"
    dirs+=("$RAW/${FORCING:+${FORCING}_}dx_0.01_dt$f")
  done
fi
CSV="${CSV:-results/cylinder_re20.csv}"
/usr/bin/python3 bench/cylinder_summary.py "${dirs[@]}" > "$CSV"
cat "$CSV"
