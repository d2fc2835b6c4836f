#!/usr/bin/env bash
# The scaling measurement (results/performance.md, "Many solids"): 1000 soft discs on 1024^2 against one disc on
# the same grid (bench/scenes/many_discs_1000.toml, many_discs_1_1024.toml, written by
# bench/scenes/make_many_discs.py): peak resident memory (GNU time's maximum RSS), the run's
# own memory estimate, microseconds per cell and step over STEPS timed steps after WARM
# warm-up steps on THREADS threads, the share of the per-solid phases (xi advection,
# extrapolation, level set) and the contact phase's milliseconds per step. One row per scene in results/scaling_1000_discs.csv, with
# the machine's load average at the start (timings on a shared machine are unreliable).
#   bash bench/run_scaling.sh [BINARY]        (default build/refmap; STEPS=10 WARM=2 THREADS=1)
#
# Instruction counts instead (repeatable on a loaded machine; valgrind cannot run AVX-512 code,
# so BINARY is a build with -DREFMAP_NO_AVX512=ON):
#   CALLGRIND=1 bash bench/run_scaling.sh build-prof/refmap   (CG_STEPS=3; CG_SCENES: a subset)
# runs each scene for CG_STEPS steps under callgrind, counting only refmap::run (the steps and
# their per-step outputs, not the set-up), and writes results/scaling_1000_discs_instructions.csv:
# instructions per cell and step, in all and in the per-solid phases, each inclusive of what
# it calls (the columns are described in the file).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/refmap}
steps=${STEPS:-10}; warm=${WARM:-2}; threads=${THREADS:-1}
raw=${RAW:-/tmp/refmap_scaling}
out=${OUT:-results/scaling_1000_discs.csv}
mkdir -p "$raw"
if [ "${CALLGRIND:-0}" = 1 ]; then
  cg_steps=${CG_STEPS:-3}
  out=${OUT:-results/scaling_1000_discs_instructions.csv}
  {
    echo "# $(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1); git $(git rev-parse --short HEAD); $bin"
    echo "# command: CALLGRIND=1 CG_STEPS=$cg_steps bash bench/run_scaling.sh $bin"
    # per cell and step: all of refmap::run; Simulation::update_solids (the per-solid phases), of which
    # Solid::advect (with its stage extrapolations), Solid::extrapolate_layers (all calls, stages
    # and after the step) and Solid::rebuild_level_set; Simulation::solid_force; the contact
    # (force and gaps); the rest (the fluid, the blending, diagnostics and output)
    echo "scene,solids,nx,ny,steps,instructions,update_solids,advect,extrapolation,level_set,solid_force,contact,rest"
  } > "$out"
  for scene in ${CG_SCENES:-many_discs_1_1024 many_discs_1000}; do
    rm -rf "$raw/cg_$scene"
    # OMP_WAIT_POLICY set: refmap would otherwise re-exec itself with it (solver/app/main.cpp), which
    # valgrind refuses
    OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-PASSIVE} OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$raw/cg_$scene.out" \
      "--toggle-collect=refmap::run(*" "$bin" run "bench/scenes/$scene.toml" --out "$raw/cg_$scene" --threads 1 \
      --quiet --set time.max_steps="$cg_steps" --set output.vtk=false > "$raw/cg_$scene.log" 2>&1
    callgrind_annotate --inclusive=yes --threshold=100 "$raw/cg_$scene.out" > "$raw/cg_$scene.txt"
    t="$raw/cg_$scene/timings.csv"
    key() { grep "^# $1:" "$t" | cut -d: -f2 | tr -d ' '; }
    python3 - "$scene" "$(key solids)" "$(key nx)" "$(key ny)" "$cg_steps" "$raw/cg_$scene.txt" >> "$out" <<'PY'
import re, sys
scene, n, nx, ny, steps, ann = sys.argv[1:]
rows = []
for line in open(ann):
    m = re.match(r"\s*([\d,]+)\s+\(", line)
    if m:
        rows.append((int(m.group(1).replace(",", "")), line))
def find(pat):  # the largest inclusive count of a line naming the function
    return max((c for c, line in rows if re.search(pat, line)), default=0)
per = int(nx) * int(ny) * int(steps)
total = find(r"(^|[\s:])refmap::run\(")
update = find(r"refmap::Simulation::update_solids\(")
stress = find(r"refmap::Simulation::solid_force\(")
contact = find(r"refmap::Simulation::compute_contact_force\(") + find(r"refmap::Contact::observe\(")
cols = [total, update, find(r"refmap::Solid::advect\("), find(r"refmap::Solid::extrapolate(_layers)?\("),
        find(r"refmap::Solid::rebuild_level_set\("), stress, contact, total - update - stress - contact]
print(f"{scene},{n},{nx},{ny},{steps}," + ",".join(f"{c / per:.1f}" for c in cols))
PY
  done
  cat "$out"
  exit 0
fi
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
