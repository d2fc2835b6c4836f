#!/usr/bin/env bash
# Threads across solids (results/threads.md): wall time per step of the many-small-solids scenes and
# two small-grid scenes on 1 and 2 threads, two binaries interleaved (1 thread then 2,
# binary A then B, repeated), under a wait policy and optionally beside one competing busy
# process at nice 19. Prints one CSV row per run: the medians are taken by
# bench/threads_study.py.
#   bash bench/run_threads_study.sh BIN_A BIN_B [REPS] > runs.csv
# Knobs: POLICY (OMP_WAIT_POLICY value, empty = unset), BUSY=1 (one competing busy
# process for the duration, at nice BUSY_NICE, default 19), SCENES ("name:steps ..." ; default below).
set -euo pipefail
cd "$(dirname "$0")/.."
A=$1; B=$2; REPS=${3:-3}
SCENES=${SCENES:-"bench/scenes/incrmt_circles_42.toml:100 bench/scenes/many_discs_64.toml:30 bench/scenes/many_discs_16.toml:30 scenes/two_solids_tgv.toml:300 scenes/couette_elastic.toml:3000"}
TMP=$(mktemp -d /tmp/solids_par_study.XXXX)
busy=""
if [[ "${BUSY:-0}" == 1 ]]; then nice -n "${BUSY_NICE:-19}" sh -c 'while :; do :; done' & busy=$!; fi
trap '[[ -n "$busy" ]] && kill "$busy"; rm -rf "$TMP"' EXIT
echo "scene,steps,cells,binary,threads,policy,busy,rep,loop_s,us_per_cell_step,load1"
for rep in $(seq "$REPS"); do
  for sc in $SCENES; do
    f=${sc%%:*}; n=${sc##*:}; name=$(basename "$f" .toml)
    nx=$(sed -n 's/^nx *= *\([0-9]*\).*/\1/p' "$f" | head -1); ny=$(sed -n 's/^ny *= *\([0-9]*\).*/\1/p' "$f" | head -1)
    for th in 1 2; do
      for bin in "$A" "$B"; do
        rm -rf "$TMP/run"
        if [[ -n "${POLICY:-}" ]]; then export OMP_WAIT_POLICY=$POLICY; else unset OMP_WAIT_POLICY; fi
        OMP_NUM_THREADS=$th timeout 120 "$bin" run "$f" --out "$TMP/run" --threads "$th" --quiet \
          --set time.max_steps="$n" --set output.vtk=false >/dev/null 2>&1 || true
        tot=$(awk -F, '$1=="total"{print $2}' "$TMP/run/timings.csv" 2>/dev/null || echo nan)
        load=$(cut -d' ' -f1 /proc/loadavg)
        us=$(awk -v t="$tot" -v n="$n" -v c=$((nx * ny)) 'BEGIN{printf "%.5f", 1e6 * t / (n * c)}')
        echo "$name,$n,$((nx * ny)),$bin,$th,${POLICY:-default},${BUSY:-0},$rep,$tot,$us,$load"
      done
    done
  done
done
