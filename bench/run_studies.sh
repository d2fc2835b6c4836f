#!/usr/bin/env bash
# Whole-run studies (results/performance.md, "Whole-run studies"), made with the refmap executable and the
# scene files (no code of their own beyond the analysis in bench/studies.py):
#
#  1. scene costs: microseconds per cell per step of the paper's scenes, by phase (the
#     phases of `refmap run`'s timing table, read from DIR/timings.csv), with 1 and 2
#     threads and the speed-up; scenes of the contact branch (two_solids_tgv, bounce_soft)
#     are included when their files exist;
#  2. many small solids vs one large one: 512^2 box, 1 disc of radius 0.2 vs 16 and 64 discs
#     of radius 0.2/sqrt(N) (bench/scenes/many_discs_<N>.toml), and on 1024^2 one disc of
#     radius 0.2 vs 1000 of radius 0.01 (many_discs_1_1024, many_discs_1000: the scaling scene
#     of results/performance.md, "Many solids"): solid-phase time per step and the solids' storage; 64 discs and the 1024^2
#     pair also on 2 threads;
#  3. accuracy against cost: error vs wall time over grids, central and Superbee fluxes, for
#     the Taylor-Green vortex, the lid-driven cavity at Re 100 and the elastic-layer Couette
#     flow.
#
#   bash bench/run_studies.sh            # full (target <= 20 min on a quiet 2-core machine)
#   QUICK=1 bash bench/run_studies.sh    # cheapest settings, a couple of minutes
#
# Knobs: QUICK=1; OUT (output directory, default results); BUILD (build directory, default build-bench, shared with
# run_benchmarks.sh); PYTHON; STUDIES="costs many accuracy" (a subset); REPS (repetitions of
# each timing run, the median run by total time is kept; default 3, QUICK 1).
# Output: results/scene_costs.csv, results/scene_costs.png, results/accuracy_vs_cost.csv,
# results/accuracy_vs_cost_{taylor_green,cavity,couette}.png; the raw runs (timings.csv,
# probes, diagnostics; VTK only for TGV: first and last frame) in results/raw/studies/ (not
# committed: see .gitignore) and results/raw/studies_info.txt (machine, load, wall times).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

QUICK="${QUICK:-0}"
BUILD="${BUILD:-build-bench}"
STUDIES="${STUDIES:-costs many accuracy}"
if [[ "$QUICK" == 1 ]]; then REPS="${REPS:-1}"; else REPS="${REPS:-3}"; fi
if [[ -z "${PYTHON:-}" ]]; then
  for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c 'import matplotlib, numpy' 2>/dev/null; then PYTHON="$p"; break; fi
  done
  PYTHON="${PYTHON:-python3}"
fi

BIN="$BUILD/refmap"
OUT="${OUT:-results}"
RAW="$OUT/raw/studies"
INFO="$OUT/raw/studies_info.txt"
mkdir -p "$RAW"

echo "== configure and build refmap (Release, $BUILD)"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j2 --target refmap

git update-index -q --refresh >/dev/null 2>&1 || true
GIT_REV="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
git diff --quiet HEAD -- . ':(exclude)results' 2>/dev/null || GIT_REV="$GIT_REV (with uncommitted changes)"
CXX_PATH="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$BUILD/CMakeCache.txt")"
T0=$(date +%s)
# keep the record of the parts not run this time (their results stay in $RAW)
KEEP=""
for part in costs many accuracy; do
  if [[ " $STUDIES " != *" $part "* && -f "$INFO" ]]; then
    KEEP+="$(grep -E "^[a-z_]+_${part}(_s)?:" "$INFO" || true)"$'\n'
  fi
done
{
  echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
  echo "host_model: $(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)"
  echo "cores: $(nproc)"
  echo "compiler: $("${CXX_PATH:-c++}" --version | head -1)"
  echo "git: $GIT_REV"
  echo "command: QUICK=$QUICK REPS=$REPS STUDIES='$STUDIES' bash bench/run_studies.sh"
  echo "omp_proc_bind: ${OMP_PROC_BIND:-unset}"
  echo "uptime_before: $(uptime)"
  printf '%s' "$KEEP" | sed '/^$/d'
} > "$INFO"
# per part: date, uptime before/after, wall time (part_begin NAME / part_end NAME)
part_begin() {
  P0=$(date +%s)
  { echo "date_$1: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"; echo "uptime_before_$1: $(uptime)"; } >> "$INFO"
}
part_end() {
  { echo "uptime_after_$1: $(uptime)"; echo "wall_$1_s: $(( $(date +%s) - P0 ))"; } >> "$INFO"
}

# run DIR THREADS SCENE [refmap options...]: one quiet run into DIR (replaced)
run() {
  local dir="$1" t="$2" scene="$3"; shift 3
  rm -rf "$dir"
  OMP_NUM_THREADS="$t" "$BIN" run "$scene" --out "$dir" --threads "$t" --fixed-threads --quiet "$@"
}

# ---------------------------------------------------------------- 1. scene costs
if [[ " $STUDIES " == *" costs "* ]]; then
  if [[ "$QUICK" == 1 ]]; then WARM=3; STEPS=20; else WARM=10; STEPS=200; fi
  SCENES=(lid_driven_cavity_re1000 disc_tgv soft_disc_cavity zalesak two_solids_tgv bounce_soft)
  echo "== scene costs: $WARM warm-up + $STEPS timed steps, threads 1 and 2, $REPS repetition(s)"
  part_begin costs
  rm -rf "$RAW/cost"
  for sc in "${SCENES[@]}"; do
    f="scenes/$sc.toml"
    if [ ! -f "$f" ]; then echo "   $f: not present, skipped"; continue; fi
    for t in 1 2; do
      for r in $(seq 1 "$REPS"); do
        run "$RAW/cost/$sc/${t}t/rep$r" "$t" "$f" --timing-warmup "$WARM" \
          --set time.max_steps=$((WARM + STEPS)) --set output.vtk=false
      done
      echo "   $sc, $t thread(s): done"
    done
  done
  part_end costs
fi

# ---------------------------------------------------------------- 2. many small solids
if [[ " $STUDIES " == *" many "* ]]; then
  if [[ "$QUICK" == 1 ]]; then WARM=2; STEPS=5; else WARM=5; STEPS=30; fi
  echo "== many small solids vs one: 512^2, N = 1, 16, 64 discs; 1024^2, 1 and 1000 discs; $WARM + $STEPS steps"
  part_begin many
  rm -rf "$RAW/many"
  # scene:threads (the scaling goals quote 2-thread speed-ups for 64 and 1000 discs)
  for spec in "1:1" "16:1" "64:1 2" "1_1024:1 2" "1000:1 2"; do
    n=${spec%%:*}
    for t in ${spec#*:}; do
      for r in $(seq 1 "$REPS"); do
        run "$RAW/many/many_discs_$n/${t}t/rep$r" "$t" "bench/scenes/many_discs_$n.toml" --timing-warmup "$WARM" \
          --set time.max_steps=$((WARM + STEPS)) --set output.vtk=false
      done
    done
    echo "   many_discs_$n: done"
  done
  part_end many
fi

# ---------------------------------------------------------------- 3. accuracy vs cost
if [[ " $STUDIES " == *" accuracy "* ]]; then
  if [[ "$QUICK" == 1 ]]; then
    TGV_N="32 64"; CAV_N="32"; COU_N="16"
  else
    TGV_N="32 64 128 256"; CAV_N="32 64 128"; COU_N="16 32 64"
  fi
  echo "== accuracy vs cost (1 thread): TGV n = $TGV_N; cavity Re 100 n = $CAV_N; Couette cells/unit = $COU_N"
  part_begin accuracy
  rm -rf "$RAW/acc"
  for adv in central superbee; do
    for n in $TGV_N; do   # t = 1, first and last VTK frame (the error is read from the last)
      run "$RAW/acc/taylor_green/$adv/$n" 1 scenes/taylor_green.toml \
        --set grid.nx=$n --set grid.ny=$n --set solver.advection=$adv --set output.interval=0 \
        --set output.diagnostics_every=100
      echo "   taylor_green $adv $n: done"
    done
    for n in $CAV_N; do   # to the steady state (steady_tol 1e-7 of the scene)
      run "$RAW/acc/cavity/$adv/$n" 1 scenes/lid_driven_cavity_re100.toml \
        --set grid.nx=$n --set grid.ny=$n --set solver.advection=$adv --set output.vtk=false \
        --set output.diagnostics_every=100
      echo "   cavity $adv $n: done"
    done
    for n in $COU_N; do   # t = 4.8; nx = 8 columns always, lx follows dx (as tests/test_couette_elastic.cpp)
      lx=$("$PYTHON" -c "print(repr(8.0 / $n))")
      run "$RAW/acc/couette/$adv/$n" 1 scenes/couette_elastic.toml \
        --set grid.ny=$((2 * n)) --set domain.lx=$lx --set domain.ly=2.0 --set solver.advection=$adv \
        --set output.vtk=false --set output.diagnostics_every=1000
      echo "   couette $adv $n: done"
    done
  done
  part_end accuracy
fi

{
  echo "uptime_after: $(uptime)"
  echo "wall_total_s: $(( $(date +%s) - T0 ))"
} >> "$INFO"

echo "== analyse"
"$PYTHON" bench/studies.py --raw "$RAW" --info "$INFO" --out "$OUT"
echo "run_studies.sh: done in $(( $(date +%s) - T0 )) s (plus the build)"
