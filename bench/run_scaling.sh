#!/usr/bin/env bash
# The scaling measurement of issue 27 (item 4): 1000 soft discs on 1024^2 against one disc on
# the same grid (bench/scenes/many_discs_1000.toml, many_discs_1_1024.toml, written by
# bench/scenes/make_many_discs.py): peak resident memory (GNU time's maximum RSS), the run's
# own memory estimate, microseconds per cell and step over STEPS timed steps after WARM
# warm-up steps on THREADS threads, the share of the per-solid phases (xi advection,
# extrapolation, level set) and the contact phase's milliseconds per step. One row per scene in results/scaling_1000_discs.csv, with
# the machine's load average at the start (timings on a shared machine are unreliable).
#   bash bench/run_scaling.sh [BINARY]        (default build/refmap; STEPS=10 WARM=2 THREADS=1)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/refmap}
steps=${STEPS:-10}; warm=${WARM:-2}; threads=${THREADS:-1}
raw=${RAW:-/tmp/refmap_scaling}
out=${OUT:-results/scaling_1000_discs.csv}
mkdir -p "$raw"
echo "scene,solids,nx,ny,threads,timed_steps,us_per_cell_step,solid_share,contact_ms_per_step,peak_rss_mb,estimate,solid_window_cells,solid_storage_mb,load_1min" > "$out"
for scene in many_discs_1_1024 many_discs_1000; do
  load=$(cut -d' ' -f1 /proc/loadavg)
  OMP_NUM_THREADS=$threads /usr/bin/time -v "$bin" run "bench/scenes/$scene.toml" --out "$raw/$scene" \
    --threads "$threads" --fixed-threads --timing-warmup "$warm" --set time.max_steps=$((steps + warm)) \
    --set output.vtk=false > "$raw/$scene.log" 2> "$raw/$scene.time"
  t="$raw/$scene/timings.csv"
  key() { grep "^# $1:" "$t" | cut -d: -f2 | tr -d ' '; }
  rss=$(grep "Maximum resident set size" "$raw/$scene.time" | awk '{print $NF}')
  est=$(grep "^memory: about" "$raw/$scene.log" | sed 's/^memory: about //; s/,/;/g')
  python3 - "$scene" "$(key solids)" "$(key nx)" "$(key ny)" "$threads" "$(key timed_steps)" "$(key timed_wall_s)" \
    "$rss" "$est" "$(key solid_window_cells)" "$(key solid_storage_bytes)" "$load" "$t" >> "$out" <<'PY'
import csv, sys
scene, n, nx, ny, th, steps, wall, rss, est, wc, sb, load, timings = sys.argv[1:]
us = float(wall) * 1e6 / (int(nx) * int(ny) * int(steps))
phase = {r[0]: float(r[1]) for r in csv.reader(l for l in open(timings) if not l.startswith("#")) if r[0] != "phase"}
# the per-solid phases (each solid's window) and the contact phase (force and gaps), per timed step
solid = sum(phase.get(k, 0.0) for k in ("xi advection", "extrapolation", "level set")) / phase["total"]
contact = phase.get("contact", 0.0) * 1e3 / int(steps)
print(f"{scene},{n},{nx},{ny},{th},{steps},{us:.4f},{solid:.3f},{contact:.2f},{int(rss) / 1024:.1f},{est},{wc},"
      f"{int(sb) / 2**20:.1f},{load}")
PY
done
cat "$out"
