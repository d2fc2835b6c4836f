#!/usr/bin/env bash
# Both body-force estimators on Turek & Hron FSI2 (results/README.md, "Body
# forces: control volume against forcing"): one run of scenes/turek_hron_fsi2.toml to t = 10.5
# with build/bench/refmap_body_forces (the direct forcing's force, the clamped flag's momentum
# and the control-volume force of the cylinder + flag every step), summarised by
# bench/body_force_summary.py over three windows (the flag straight, growing, saturated), with
# the 0.01 s smoothing of bench/run_fsi.sh and without, into results/body_forces_fsi2.csv.
#   bash bench/run_body_forces.sh        # about 44 000 steps: 10 min CPU, ~50 min on a loaded machine
# Knobs: BIN (default build/bench/refmap_body_forces), ROWS (the per-step rows, default
# /tmp/refmap_body_forces_fsi2.csv; an existing file is reused if it reaches t = 10.5).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BIN="${BIN:-build/bench/refmap_body_forces}"
ROWS="${ROWS:-/tmp/refmap_body_forces_fsi2.csv}"
if ! awk -F, 'NR > 1 && $1 >= 10.5 {ok = 1} END {exit !ok}' "$ROWS" 2>/dev/null; then
  # solid.1.mu_s = 2.5e5: the flag's modulus when the study was run (the benchmark's shear
  # modulus; the scene has taken the bending rule since 2026-12-07, results/fsi.md)
  OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE "$BIN" scenes/turek_hron_fsi2.toml 0 time.end=10.5 solid.1.mu_s=2.5e5 > "$ROWS"
fi
out=results/body_forces_fsi2.csv
first=1
for w in "2 3" "5 7" "8.5 10.5"; do
  for s in 0.01 0; do
    # shellcheck disable=SC2086
    /usr/bin/python3 bench/body_force_summary.py "$ROWS" $w $s | if [ $first = 1 ]; then cat; else tail -n +2; fi
    first=0
  done
done > "$out"
cat "$out"
