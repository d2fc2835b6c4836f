#!/usr/bin/env bash
# The multigrid density-contrast study (results/multigrid.md): the standard Poisson problem
# (tests/fixtures/poisson_problem.hpp, standard_problem(N, R)) solved to 1e-8 by V(2,2)
# V(2,2) and F(2,2) cycles and by MGPCG, with each coarse operator (solver.coarse_operator: "average", the
# restriction-weighted mean of beta; "harmonic", fine faces in series normal to the coarse
# face and strips in parallel), N = 256 ... 2048, density ratio R = 1 and 1000, on 1 and 2
# threads. Writes results/poisson_contrast.csv (one row per case and thread count:
# median of REPS repetitions, default 1: cycle counts are deterministic, times noisy) and the raw JSON in results/raw/poisson_contrast_<t>t.json.
#
#   bash bench/run_poisson_contrast.sh            # BUILD=build (needs -DREFMAP_BUILD_BENCH=ON)
#   THREADS=1 REPS=5 bash bench/run_poisson_contrast.sh
#   SUMMARISE_ONLY=1 bash bench/run_poisson_contrast.sh   # the CSV from the existing JSON
#   FILTER=galerkin TAG=_galerkin THREADS=1 bash bench/run_poisson_contrast.sh
#       # only the cases matching FILTER (a regex on the name after "PoissonContrast/"), into
#       # results/raw/poisson_contrast_<t>t<TAG>.json; the CSV is made from every
#       # poisson_contrast_<t>t*.json of the thread counts in THREADS, in name order, a later
#       # file's row replacing an earlier one of the same case
#   The setup cost of each coarse operator (not in the CSV; quoted in results/multigrid.md):
#   OMP_NUM_THREADS=1 build/bench/refmap_bench --benchmark_filter='^PoissonContrastSetup/' 
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BUILD="${BUILD:-build}"
BIN="$BUILD/bench/refmap_bench"
THREADS="${THREADS:-1 2}"
REPS="${REPS:-1}"
FILTER="${FILTER:-}"
TAG="${TAG:-}"
RAW=results/raw
mkdir -p "$RAW"
[[ -x "$BIN" ]] || cmake --build "$BUILD" -j2 --target refmap_bench
for t in $THREADS; do
  [[ "${SUMMARISE_ONLY:-0}" == 1 ]] && break
  echo "== $t thread(s), load: $(cut -d' ' -f1-3 /proc/loadavg)"
  OMP_NUM_THREADS=$t "$BIN" --benchmark_filter="^PoissonContrast/.*${FILTER}" \
    --benchmark_repetitions="$REPS" --benchmark_report_aggregates_only=true \
    --benchmark_min_time=0.01 --benchmark_format=json --benchmark_out_format=json \
    --benchmark_out="$RAW/poisson_contrast_${t}t${TAG}.json" >/dev/null
done
python3 - "$RAW" $THREADS <<'PY'
import glob, json, sys
raw, threads = sys.argv[1], sys.argv[2:]
rows = []
for t in threads:
  for path in sorted(glob.glob(f"{raw}/poisson_contrast_{t}t*.json")):
    d = json.load(open(path))
    bs = d["benchmarks"]
    medians = [b for b in bs if b.get("aggregate_name") == "median"]
    for b in medians or bs:  # REPS=1: no aggregates, the single run
        name = b["run_name"]  # PoissonContrast/<m>/<co>/N/R/real_time
        _, m, co, n, r = name.split("/")[:5]
        if "error_message" in b:
            rows.append((m, co, int(n), int(r), int(t), float("nan"), float("nan"), -1, float("nan"), float("nan")))
            continue
        ms, cpu = b["real_time"], b["cpu_time"]  # time_unit ms
        # the solver's "iterations" counter follows Google Benchmark's own key in the
        # JSON, so json.load keeps the counter (cycles / CG steps)
        rows.append((m, co, int(n), int(r), int(t), ms / 1e3, cpu / 1e3, round(b["iterations"]),
                     b["rel_residual"], b["ns_per_unknown"]))
rows = list({r[:5]: r for r in rows}.values())  # a later file's row replaces an earlier one
load = open("/proc/loadavg").read().split()[:3]
with open("results/poisson_contrast.csv", "w") as f:
    f.write(f"# bash bench/run_poisson_contrast.sh; shared machine, load at the end {' '.join(load)}\n")
    # s_per_solve: wall time; cpu_s_per_solve: the main thread's CPU time (on 1 thread the
    # better measure on a loaded machine: it leaves out the time the thread waited for a
    # core); cycles = -1: did not converge in 100000 cycles
    f.write("method,coarse_operator,grid,ratio,threads,s_per_solve,cpu_s_per_solve,cycles,rel_residual,ns_per_unknown\n")
    for m, co, n, r, t, s, c, it, rr, ns in sorted(rows):
        f.write(f"{m},{co},{n},{r},{t},{s:.4g},{c:.4g},{it},{rr:.3g},{ns:.4g}\n")
print(open("results/poisson_contrast.csv").read())
PY
