#!/usr/bin/env bash
# Runs every shipped scene for a fixed number of steps with one binary and writes each
# run's diagnostics.csv (wall_time column removed), solids.csv, events.csv, tracers.csv, markers.csv and last VTK frame to OUT; with a second
# directory, compares two such sets byte for byte. Used to show that a refactor keeps
# the scenes' output identical.
#   bash scripts/compare_scenes.sh run BINARY OUT [STEPS]   (STEPS default 40; THREADS=N
#                                                            for N OpenMP threads, default 1)
#   bash scripts/compare_scenes.sh diff OUT_A OUT_B
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  run)
    bin=$2; out=$3; steps=${4:-40}; threads=${THREADS:-1}
    mkdir -p "$out"
    for s in scenes/*.toml; do
      name=$(basename "$s" .toml)
      rm -rf "$out/run_$name"
      OMP_NUM_THREADS=$threads "$bin" run "$s" --out "$out/run_$name" --threads "$threads" --quiet \
        --set time.max_steps="$steps" > "$out/$name.log" 2>&1 || echo "exit $? $name" >> "$out/$name.log"
      if [ -f "$out/run_$name/diagnostics.csv" ]; then
        # drop the wall_time column (by name) and the header comment line
        awk -F, 'BEGIN{OFS=","} /^#/ {next} NR>0 && !c {for(i=1;i<=NF;i++) if($i=="wall_time") c=i}
                 {if(c){$c=""}; print}' "$out/run_$name/diagnostics.csv" > "$out/$name.diag.csv"
      fi
      [ -f "$out/run_$name/events.csv" ] && cp "$out/run_$name/events.csv" "$out/$name.events.csv"
      [ -f "$out/run_$name/solids.csv" ] && grep -v '^#' "$out/run_$name/solids.csv" > "$out/$name.solids.csv"
      for f in tracers markers; do
        [ -f "$out/run_$name/$f.csv" ] && grep -v '^#' "$out/run_$name/$f.csv" > "$out/$name.$f.csv"
      done
      # the last frame holds every field in full precision
      last=$(ls "$out/run_$name"/frame_*.vti 2>/dev/null | tail -1 || true)
      [ -n "$last" ] && cp "$last" "$out/$name.last.vti"
      rm -rf "$out/run_$name"
    done
    ;;
  diff)
    a=$2; b=$3; bad=0
    for f in "$a"/*.diag.csv "$a"/*.solids.csv "$a"/*.events.csv "$a"/*.tracers.csv "$a"/*.markers.csv "$a"/*.last.vti; do
      [ -e "$f" ] || continue
      g="$b/$(basename "$f")"
      if cmp -s "$f" "$g"; then echo "same      $(basename "$f")"; else echo "DIFFERENT $(basename "$f")"; bad=1; fi
    done
    exit $bad
    ;;
  *) sed -n 2,8p "$0"; exit 2 ;;
esac
