#!/usr/bin/env bash
# Explicit against semi-implicit stepping (docs/implicit.md; results/implicit.md): one run each of
# couette_elastic (64 cells per unit), the shear wave (scenes/shear_wave.toml) over dt,
# soft_disc_cavity (to t = 1), bounce_stiff at mu_s = 1e3, 1e4, 1e5 (to t = 0.5; the explicit
# small-dt run at 1e3) and disc_tgv; the velocity solve's tolerance time.implicit_tol on
# couette_elastic and the shear wave ("tol"); the full soft_disc_cavity run (128^2, t = 8) with
# its centroid path against Sugiyama et al. ("soft_disc_full"). Each pair runs back to back (explicit, then
# semi-implicit) with 1 thread, so the wall-time ratio is of the same machine load. "uc": the
# upper-convected solid stress (time.solid_stress = "upper_convected") on couette, the shear
# wave, disc_tgv and the three bounces, beside the rows of the other cases (not re-run).
#
#   bash bench/run_implicit_study.sh          # ~30 min on a loaded 2-core machine
#   CASES="couette shear" bash bench/run_implicit_study.sh
#   CASES=uc bash bench/run_implicit_study.sh    # only the upper-convected rows
#
# Knobs: BIN (refmap executable, default build/refmap), OUT (default results),
# RAW (run directories, default /tmp/refmap_implicit_study), CASES.
# Output: results/implicit.csv (case, variant, dt rule, steps, wall, accuracy columns).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
export OMP_NUM_THREADS=1
exec nice python3 bench/implicit_study.py --bin "${BIN:-build/refmap}" --out "${OUT:-results}" \
  --raw "${RAW:-/tmp/refmap_implicit_study}" --cases ${CASES:-couette shear soft_disc bounce disc_tgv tol soft_disc_full uc}
