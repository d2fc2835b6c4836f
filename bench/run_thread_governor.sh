#!/usr/bin/env bash
# Two threads against one under the thread governor (solver/app/thread_governor.hpp) and under
# the previous default (passive waiting on a fixed team, reproduced with
# OMP_WAIT_POLICY=PASSIVE --fixed-threads), interleaved: for each repeat, scene, variant
# and team size one `refmap run`; optionally beside one competing busy process at the same
# priority (BUSY=1). One CSV row per run; bench/thread_governor.py takes the medians.
#   bash bench/run_thread_governor.sh BIN [REPS] > runs.csv
#   BUSY=1 bash bench/run_thread_governor.sh BIN [REPS] > runs_busy.csv
# Knob: SCENES ("scene:grid:steps ...", grid 0 = the scene's own; scene from scenes/ or
# bench/scenes/); BIN2: a second binary, compared with BIN instead of the passive variant (the
# variants are then "A" = BIN and "B" = BIN2, both with the governor: two builds, e.g. of
# another work threshold, results/threads.md). Needs an otherwise idle machine: say so (the
# load column) when quoting.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=$1; REPS=${2:-3}; BUSY=${BUSY:-0}
SCENES=${SCENES:-"disc_tgv:256:400 disc_tgv:512:120 lid_driven_cavity_re1000:0:2000 couette_elastic:0:3000 incrmt_circles_42:0:100 many_discs_64:0:30"}
TMP=$(mktemp -d /tmp/governor_study.XXXX)
busy=""
if [[ $BUSY == 1 ]]; then sh -c 'while :; do :; done' & busy=$!; fi
trap '[[ -n "$busy" ]] && kill "$busy"; rm -rf "$TMP"' EXIT
echo "scene,grid,variant,threads,busy,rep,total_s,switches,min_threads,load1"
for rep in $(seq "$REPS"); do
  for g in $SCENES; do
    sc=${g%%:*}; rest=${g#*:}; n=${rest%%:*}; steps=${rest##*:}
    f=scenes/$sc.toml; [[ -f $f ]] || f=bench/scenes/$sc.toml
    grid=(); [[ $n != 0 ]] && grid=(--set grid.nx="$n" --set grid.ny="$n")
    variants="passive_fixed governor"; [[ -n ${BIN2:-} ]] && variants="A B"
    for variant in $variants; do
      for th in 1 2; do
        unset OMP_WAIT_POLICY GOMP_SPINCOUNT
        extra=()
        if [[ $variant == passive_fixed ]]; then export OMP_WAIT_POLICY=PASSIVE; extra=(--fixed-threads); fi
        bin=$BIN; [[ $variant == B ]] && bin=$BIN2
        rm -rf "$TMP/run"
        OMP_NUM_THREADS=$th "$bin" run "$f" --out "$TMP/run" --threads "$th" --quiet "${grid[@]}" "${extra[@]}" \
          --set time.max_steps="$steps" --set output.vtk=false >/dev/null 2>&1 || true
        tot=$(awk -F, '$1=="total"{print $2}' "$TMP/run/timings.csv" 2>/dev/null || echo nan)
        sw=$(sed -n 's/^# thread_switches: //p' "$TMP/run/timings.csv" 2>/dev/null || echo nan)
        mt=$(sed -n 's/^# min_threads: //p' "$TMP/run/timings.csv" 2>/dev/null || echo nan)
        echo "$sc,$n,$variant,$th,$BUSY,$rep,$tot,$sw,$mt,$(cut -d' ' -f1 /proc/loadavg)"
      done
    done
  done
done
