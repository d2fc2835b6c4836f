#!/usr/bin/env bash
# Turek & Hron (2006) FSI2 / FSI3 (docs/references.md#turek-and-hron-fsi-benchmark; results/fsi.md): runs
# scenes/turek_hron_fsi{2,3}.toml and summarises the tip displacement and the forces with
# bench/fsi_summary.py into results/turek_hron_fsi{2,3}.csv, the tip trajectory figure with
# bench/fsi_plot.py, a snapshot of the vorticity at the last frame with bench/fsi_snapshot.py.
#
#   bash bench/run_fsi.sh                 # both cases, to the scenes' end times (hours on 1 core)
#   CASES=fsi3 END=4 bash bench/run_fsi.sh
#   CASES=fsi2 END=13.54 SETS="grid.nx=1000 grid.ny=164 time.dt=1.25e-4" TAG=_dx0.0025 \
#     bash bench/run_fsi.sh      # FSI2 on the grid of dx = 0.0025 (about 2 h here)
#
# The tip comes from markers.csv, which refmap writes with each VTK frame (docs/tracers.md);
# the scenes write a frame every 0.02 (FSI2) or 0.005 (FSI3), 25 or 38 samples per period of
# the lift (half that per period of u_x and the drag). To keep the disk use bounded
# this script deletes the frames as they come, except every 50th (for snapshots).
# A run that blows up (exit 3) is summarised over the WINDOW ending 0.1 s before its last
# row, and its CSV ends with a '# FAILED: ...' line (the solver's message).
# Knobs: BIN (default build/refmap), RAW (run directories, default /tmp/refmap_fsi),
# CASES (fsi2 fsi3), END (override time.end), SETS (more scene overrides, space-separated
# key=value), TAG (appended to the run directory's and the outputs' names), THREADS (default 1), WINDOW (seconds at the end
# of the run the statistics are taken over, default 2), SMOOTH (seconds of the centred running
# mean taken of the forces before their statistics, default 0.01: removes the per-step noise of the
# forcing force; lowers the amplitude of a 4 Hz sine by 0.2 %, of an 11 Hz one by 2 %).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BIN="${BIN:-build/refmap}"
RAW="${RAW:-/tmp/refmap_fsi}"
mkdir -p "$RAW" results
export OMP_WAIT_POLICY=PASSIVE

prune() {  # delete the frames of $1 except every 50th and the newest, while pid $2 runs
  while kill -0 "$2" 2>/dev/null; do
    sleep 5
    ls "$1"/frame_*.vti 2>/dev/null | head -n -1 | while read -r f; do
      n=$(basename "$f" .vti); n=$((10#${n#frame_}))
      [ $((n % 50)) -ne 0 ] && rm -f "$f"
    done
  done
}

for c in ${CASES:-fsi2 fsi3}; do
  tag="${TAG:-}"
  out="$RAW/$c$tag"
  extra=()
  [ -n "${END:-}" ] && extra+=(--set "time.end=$END")
  for kv in ${SETS:-}; do extra+=(--set "$kv"); done
  OMP_NUM_THREADS="${THREADS:-1}" nice "$BIN" run "scenes/turek_hron_$c.toml" --out "$out" --quiet \
    "${extra[@]}" > "$RAW/$c$tag.log" 2>&1 &
  pid=$!
  prune "$out" "$pid" &
  status=0
  wait "$pid" || status=$?
  wait
  t_end=()
  if [ "$status" -ne 0 ]; then
    tail -n 3 "$RAW/$c$tag.log" >&2
    # a run that blew up (exit 3) is still summarised, over the window that ends a tenth of a
    # second before its last diagnostics row (the blow-up itself left out), and its CSV says so
    [ "$status" -eq 3 ] || exit 1
    t_end=($(awk -F, '!/^#/ && NR > 2 {t = $2} END {printf "%.4f", t - 0.1}' "$out/diagnostics.csv"))
  fi
  rho_s=$(grep -m1 '^density = ' <(sed -n '/^name = "flag"/,$p' "scenes/turek_hron_$c.toml") | awk '{print $3}')
  /usr/bin/python3 bench/fsi_summary.py "$out" "${c^^}" "$rho_s" "${WINDOW:-2}" "${SMOOTH:-0.01}" "${t_end[@]}" > "results/turek_hron_$c$tag.csv"
  [ "$status" -eq 0 ] || grep -m1 'simulation failed' "$RAW/$c$tag.log" | sed 's/^refmap: error: /# FAILED: /' >> "results/turek_hron_$c$tag.csv"
  /usr/bin/python3 bench/fsi_plot.py "$out" "results/figures/turek_hron_$c${tag}_tip.png" "${t_end[@]}"
  last=$(ls "$out"/frame_[0-9]*.vti | tail -n 1)
  /usr/bin/python3 bench/fsi_snapshot.py "$last" "results/figures/turek_hron_$c${tag}_snapshot.png"
  cat "results/turek_hron_$c$tag.csv"
done
