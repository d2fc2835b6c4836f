#!/usr/bin/env bash
# Builds refmap_bench (Release, in build-bench/) and runs the whole benchmark suite with
# 1 and 2 OpenMP threads, then summarises the medians into results/.
#
#   bash bench/run_benchmarks.sh              # full run (5 repetitions, grids 128^2..2048^2)
#   QUICK=1 bash bench/run_benchmarks.sh      # 2 repetitions, only the 128^2 and 256^2 cases,
#                                             # the 100^2 extrapolation cases (bands 3, 5, 8)
#                                             # and the machine limits, for a smoke test
#   BENCH_FILTER='Poisson|Advection' bash bench/run_benchmarks.sh   # a subset (regex)
#
# Environment knobs (all optional):
#   BENCH_FILTER  Google Benchmark regex of the benchmarks to run (default: all)
#   QUICK=1       fewer repetitions, small grids only (intersected with BENCH_FILTER)
#   REPS          repetitions per benchmark (default 5, QUICK 2); the median is reported
#   MIN_TIME      --benchmark_min_time in seconds per repetition (default 0.2)
#   THREADS       thread counts to run (default "1 2")
#   MAX_LOAD      wait (sleep 60, at most 5 times) while the 1-minute load average is above
#                 this before starting (default 1.2; 0 disables the wait)
#   STUDIES       whole-run studies run afterwards by bench/run_studies.sh (default
#                 "costs many accuracy"; "none" skips them); QUICK is passed on
#   OMP_PROC_BIND and other OpenMP variables are passed through unchanged (default: unbound,
#                 so a thread can move away from a core another job is using)
#
# Output: results/raw/bench_<threads>t.json (Google Benchmark JSON, aggregates only),
#         results/raw/run_info.txt (machine, compiler, command line),
#         results/raw/run_<threads>t.txt (date, load averages before/after, wall time),
#         results/benchmarks.csv, results/benchmarks.md, results/*.png (bench/summarise.py);
#         then bench/run_studies.sh: results/scene_costs.*, results/accuracy_vs_cost*.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

QUICK="${QUICK:-0}"
if [[ "$QUICK" == 1 ]]; then REPS="${REPS:-2}"; else REPS="${REPS:-5}"; fi
MIN_TIME="${MIN_TIME:-0.2}"
THREADS="${THREADS:-1 2}"
MAX_LOAD="${MAX_LOAD:-1.2}"
FILTER="${BENCH_FILTER:-.}"
if [[ -z "${PYTHON:-}" ]]; then
  # the first python3 that has matplotlib (summarise.py writes the tables without it, but
  # no plots)
  for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c 'import matplotlib' 2>/dev/null; then PYTHON="$p"; break; fi
  done
  PYTHON="${PYTHON:-python3}"
fi

BUILD=build-bench
BIN="$BUILD/bench/refmap_bench"
RAW=results/raw
mkdir -p "$RAW"

echo "== configure and build (Release, $BUILD)"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j2 --target refmap_bench

if [[ "$QUICK" == 1 ]]; then
  # intersect the filter with the small grids: list the selected names, keep the machine
  # limits (Machine*), the 128^2 and 256^2 cases and the 100^2 extrapolation/fast-marching
  # cases (extrapolation: bands 3, 5, 8 only), pass them as an exact regex
  mapfile -t names < <("$BIN" --benchmark_list_tests=true --benchmark_filter="$FILTER" |
                       grep -E '^Machine|/(128|256)(/|$)|^(Extrapolate[A-Za-z]*|FastMarching)/100/' |
                       grep -Ev '^Extrapolate[A-Za-z]*/100/[4679](/|$)' || true)
  if [[ ${#names[@]} -eq 0 ]]; then
    echo "run_benchmarks.sh: QUICK=1 with BENCH_FILTER='$FILTER' selects nothing" >&2
    exit 1
  fi
  FILTER="^($(IFS='|'; echo "${names[*]}"))\$"
fi

load1() { cut -d' ' -f1 /proc/loadavg; }
wait_for_quiet() {
  [[ "$MAX_LOAD" == 0 ]] && return 0
  local k
  for k in 1 2 3 4 5; do
    if awk -v l="$(load1)" -v m="$MAX_LOAD" 'BEGIN { exit !(l > m) }'; then
      echo "   load average $(load1) > $MAX_LOAD: waiting 60 s ($k/5)"
      sleep 60
    else
      return 0
    fi
  done
  echo "   load average still $(load1) after 5 minutes: running anyway"
}

# source revision, recorded before anything in results/ is rewritten; results/ itself (the
# previous run's outputs) does not count as a source change
git update-index -q --refresh >/dev/null 2>&1 || true
GIT_REV="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
git diff --quiet HEAD -- . ':(exclude)results' 2>/dev/null || GIT_REV="$GIT_REV (with uncommitted changes)"
CXX_PATH="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$BUILD/CMakeCache.txt")"
{
  echo "date: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
  echo "host_model: $(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)"
  echo "cores: $(nproc)"
  echo "compiler: $("${CXX_PATH:-c++}" --version | head -1)"
  echo "git: $GIT_REV"
  echo "command: QUICK=$QUICK REPS=$REPS MIN_TIME=$MIN_TIME THREADS='$THREADS' BENCH_FILTER='${BENCH_FILTER:-}' bash bench/run_benchmarks.sh"
  echo "omp_proc_bind: ${OMP_PROC_BIND:-unset}"
} > "$RAW/run_info.txt"
# (per thread count, so re-running THREADS=2 alone keeps the 1-thread record)

for t in $THREADS; do
  echo "== $t thread(s): $REPS repetitions, min time $MIN_TIME s"
  wait_for_quiet
  info="$RAW/run_${t}t.txt"
  {
    echo "date_${t}t: $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
    echo "reps_${t}t: $REPS x min_time $MIN_TIME s"
    echo "load_before_${t}t: $(cut -d' ' -f1-3 /proc/loadavg)"
  } > "$info"
  start=$(date +%s)
  OMP_NUM_THREADS="$t" "$BIN" \
    --benchmark_filter="$FILTER" \
    --benchmark_repetitions="$REPS" \
    --benchmark_report_aggregates_only=true \
    --benchmark_min_time="$MIN_TIME" \
    --benchmark_format=json > "$RAW/bench_${t}t.json.tmp"
  mv "$RAW/bench_${t}t.json.tmp" "$RAW/bench_${t}t.json"
  echo "load_after_${t}t: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$info"
  echo "wall_s_${t}t: $(( $(date +%s) - start ))" >> "$info"
  echo "   done in $(( $(date +%s) - start )) s -> $RAW/bench_${t}t.json"
done

echo "== summarise"
"$PYTHON" bench/summarise.py --raw "$RAW" --out results

if [[ "${STUDIES:-}" != none ]]; then
  echo "== whole-run studies (bench/run_studies.sh, QUICK=$QUICK)"
  QUICK="$QUICK" BUILD="$BUILD" PYTHON="$PYTHON" bash bench/run_studies.sh
fi
