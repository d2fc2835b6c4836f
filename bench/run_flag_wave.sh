#!/usr/bin/env bash
# The grid-scale wave along the Turek & Hron flag (results/fsi.md, "The
# grid-scale wave along the flag"): short runs of scenes/turek_hron_fsi2.toml (and fsi3) with
# the flag's Kelvin-Voigt viscosity switched off or set, xi carried by the face or the cell
# velocities (solids.xi_velocity) or a grid-scale viscosity (solid grid_viscosity), on the
# scene's grid (4 cells across the flag) and on dx = 0.0025 (8 cells), each measured by bench/flag_wave.py (the amplitude of the velocity's
# short waves inside the flag, its growth rate and wavelength) into results/flag_wave.csv.
#   bash bench/run_flag_wave.sh           # 7 short runs, 2 at a time: ~15 min CPU (idle machine)
# Knobs: BIN (default build/refmap), RAW (run directories, default /tmp/refmap_flag_wave),
# ONLY (run only the variants whose name contains this string), JOBS (parallel runs, default 2).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BIN="${BIN:-build/refmap}"
RAW="${RAW:-/tmp/refmap_flag_wave}"
mkdir -p "$RAW" results
export OMP_WAIT_POLICY=PASSIVE OMP_NUM_THREADS=1
# dx = 0.0025 (8 cells across the flag) on the channel cut to x <= 1 (outflow there): the wave is
# local to the flag in these first 0.3 s and the cut grid is 2.5x cheaper
FINE2="grid.nx=400 grid.ny=164 domain.lx=1.0 time.dt=1.25e-4"
# the study was run with the flag's modulus matching the benchmark's shear modulus (mu_s = G_TH / 2),
# the scene's until 2026-12-07, when the scene took the bending rule (results/fsi.md): kept here
# so that the script regenerates results/flag_wave.csv
SHEAR="solid.1.mu_s=2.5e5"
# name | scene | end | overrides (space-separated key=value)
VARIANTS=(
  "fsi2_dx0.005_face_kv0|fsi2|0.6|$SHEAR solid.1.viscosity=0"
  "fsi2_dx0.005_cell_kv0|fsi2|0.6|$SHEAR solid.1.viscosity=0 solids.xi_velocity=\"cell\""
  "fsi2_dx0.005_face_kv300|fsi2|0.6|$SHEAR"
  "fsi2_dx0.005_cell_kv300|fsi2|0.6|$SHEAR solids.xi_velocity=\"cell\""
  "fsi2_dx0.005_face_gv0.4|fsi2|0.6|$SHEAR solid.1.viscosity=0 solid.1.grid_viscosity=0.4"
  "fsi2_dx0.0025_crop_face_kv0|fsi2|0.3|$SHEAR solid.1.viscosity=0 $FINE2"
  "fsi2_dx0.0025_crop_face_gv0.4|fsi2|0.3|$SHEAR solid.1.viscosity=0 solid.1.grid_viscosity=0.4 $FINE2"
)
run_one() {
  local name="$1" scene="$2" end="$3" sets="$4"
  local out="$RAW/$name" extra=(--set "time.end=$end" --set "output.interval=0.01")
  for kv in $sets; do extra+=(--set "$kv"); done
  rm -rf "$out"
  local status=0
  "$BIN" run "scenes/turek_hron_$scene.toml" --out "$out" --quiet "${extra[@]}" > "$RAW/$name.log" 2>&1 || status=$?
  local tlast
  tlast=$(awk -F, 'NR > 1 {t = $2} END {print t}' "$out/diagnostics.csv")
  local m
  m=$(/usr/bin/python3 bench/flag_wave.py "$out")
  echo "$m" > "$RAW/$name.wave"
  local growth wl alast
  growth=$(echo "$m" | awk '/^growth/ {print $2} /^no growth/ {print "none"}')
  alast=$(echo "$m" | grep -v growth | tail -n 1 | awk '{print $2}')
  wl=$(echo "$m" | grep -v growth | tail -n 1 | awk '{print $3}')
  echo "$name,$status,$tlast,$growth,$alast,$wl"
}
{
  echo "variant,exit_status,t_reached,growth_per_s,amplitude_last,wavelength_cells_last"
  n=0
  for v in "${VARIANTS[@]}"; do
    IFS='|' read -r name scene end sets <<< "$v"
    [[ -n "${ONLY:-}" && "$name" != *"$ONLY"* ]] && continue
    run_one "$name" "$scene" "$end" "$sets" > "$RAW/$name.row" &
    n=$((n + 1))
    if (( n % ${JOBS:-2} == 0 )); then wait; fi
  done
  wait
  for v in "${VARIANTS[@]}"; do
    IFS='|' read -r name _ <<< "$v"
    [ -f "$RAW/$name.row" ] && cat "$RAW/$name.row"
  done
} > "$RAW/flag_wave.csv"
[ -z "${ONLY:-}" ] && cp "$RAW/flag_wave.csv" results/flag_wave.csv
cat "$RAW/flag_wave.csv"
