#!/usr/bin/env bash
# Relative viscosity of a shear cell with one rigid disc pinned at its centre, free to turn
# (output.wall_stress, solver/components/wall_stress.hpp): walls at -0.5 / +0.5, periodic along x,
# 2 x 1 cell, nu = 1 (Stokes flow: gamma a^2 / nu <= 0.04), run to t = 1.5 (the start-up
# decays as e^{-pi^2 t}). Three radii give the walls' confinement, fitted as
# (eta_r - 1) / phi = c0 + c2 (a/H)^2; c0 is the unconfined dilute coefficient, 2 in
# two-dimensional Stokes flow (Brady 1984). Writes results/shear_cell.csv.
# Usage: bash bench/run_shear_cell.sh [BUILD_DIR] [NX]   (defaults build, 128)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build}/refmap
nx=${2:-128}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=results/shear_cell.csv
echo "radius,a_over_H,phi,nx,eta_r,coefficient,steps,wall_s" > "$out.tmp"
for r in 0.1 0.15 0.2; do
  cat > "$tmp/cell.toml" <<TOML
name = "shear_cell"
[domain]
lx = 2.0
ly = 1.0
[grid]
nx = $nx
ny = $((nx / 2))
[fluid]
density = 1.0
viscosity = 1.0
[boundary]
left = "periodic"
right = "periodic"
bottom = { type = "moving_wall", velocity = -0.5 }
top = { type = "moving_wall", velocity = 0.5 }
[time]
end = 1.5
[output]
vtk = false
wall_stress = true
[[solid]]
name = "disc"
shape = "circle"
center = [1.0, 0.5]
radius = $r
density = 1.0
motion = "pinned"
TOML
  OMP_NUM_THREADS=1 "$bin" run "$tmp/cell.toml" --out "$tmp/run" --threads 1 --quiet
  /usr/bin/python3 - "$tmp/run/diagnostics.csv" "$r" "$nx" >> "$out.tmp" <<'PY'
import csv, math, sys
rows = [r for r in csv.reader(l for l in open(sys.argv[1]) if not l.startswith("#"))]
head, last = rows[0], rows[-1]
col = {n: i for i, n in enumerate(head)}
a = float(sys.argv[2]); phi = math.pi * a * a / 2.0
eta = float(last[col["eta_r"]])
print(f"{a},{a},{phi:.6f},{sys.argv[3]},{eta:.6f},{(eta - 1) / phi:.4f},{last[col['step']]},{float(last[col['wall_time']]):.1f}")
PY
done
mv "$out.tmp" "$out"
/usr/bin/python3 - "$out" <<'PY'
import csv, sys
import numpy as np
rows = list(csv.DictReader(open(sys.argv[1])))
x = np.array([float(r["a_over_H"]) ** 2 for r in rows]); y = np.array([float(r["coefficient"]) for r in rows])
c2, c0 = np.polyfit(x, y, 1)
print(f"(eta_r - 1)/phi = {c0:.3f} + {c2:.2f} (a/H)^2  (unconfined dilute coefficient {c0:.3f}; 2-D Einstein: 2)")
PY
