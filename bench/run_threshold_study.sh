#!/usr/bin/env bash
# Two refmap binaries that differ only in their work threshold (kernels/loop.hpp,
# kMinParallelCells), interleaved: for each repeat and scene, binary A then B, each on 1 then
# 2 threads (the default thread governor). One CSV row per run (timings.csv total); the
# medians and speed-ups: results/threads.md, "The work threshold". Needs an otherwise idle
# machine (the load column says how idle).
#   bash bench/run_threshold_study.sh BIN_A BIN_B [REPS] > runs.csv
# Knob: SCENES ("scene:grid:steps ...", grid 0 = the scene's own; scene from scenes/ or
# bench/scenes/).
set -euo pipefail
cd "$(dirname "$0")/.."
A=$1; B=$2; REPS=${3:-3}
SCENES=${SCENES:-"lid_driven_cavity_re1000:0:2000 disc_tgv:256:400 disc_tgv:512:120 two_solids_tgv:0:300 couette_elastic:0:3000 incrmt_circles_42:0:100 many_discs_64:0:30"}
TMP=$(mktemp -d /tmp/threshold_study.XXXX)
trap 'rm -rf "$TMP"' EXIT
echo "scene,grid,bin,threads,rep,total_s,load1"
for rep in $(seq "$REPS"); do
  for g in $SCENES; do
    sc=${g%%:*}; rest=${g#*:}; n=${rest%%:*}; steps=${rest##*:}
    f=scenes/$sc.toml; [[ -f $f ]] || f=bench/scenes/$sc.toml
    grid=(); [[ $n != 0 ]] && grid=(--set grid.nx="$n" --set grid.ny="$n")
    for bin in "$A" "$B"; do
      for th in 1 2; do
        rm -rf "$TMP/run"
        OMP_NUM_THREADS=$th "$bin" run "$f" --out "$TMP/run" --threads "$th" --quiet "${grid[@]}" \
          --set time.max_steps="$steps" --set output.vtk=false >/dev/null 2>&1 || true
        tot=$(awk -F, '$1=="total"{print $2}' "$TMP/run/timings.csv" 2>/dev/null || echo nan)
        echo "$sc,$n,$(basename "$bin"),$th,$rep,$tot,$(cut -d' ' -f1 /proc/loadavg)"
      done
    done
  done
done
