#!/usr/bin/env bash
# The dilute coefficient (eta_r - 1)/phi of ONE free, stiff soft disc (radius a = 0.1,
# Ca = mu gamma / G = 0.01) at the centre of a wall-bounded, periodic shear cell (walls at
# y = 0 and H moving at -H/2 and +H/2, gamma = 1, period L along x, mu = rho = 1, started
# from the undisturbed shear), and the corrections that separate it from the unconfined 2-D
# Einstein value 2 (Brady 1984): results/suspension.md, "The dilute limit".
# Series (each one parameter varied about the test's cell H = 1, L = 2, dx = 1/64, i.e. 6.4
# cells per radius, solids.transition = 3 cells):
#   res     the grid: nx = 128 192 256 512 on L x H = 2 x 1 (6.4 ... 25.6 cells per radius;
#           the blended interface's half-width, 3 cells, shrinks with dx)
#   wall    the walls: H = 0.5 0.75 1 1.5 2 at L = 2H and dx = 1/64 (a/H = 0.2 ... 0.05)
#   wallfine  the walls again at dx = 1/128: H = 1 1.5
#   period  the periodic images: L = 1 2 4 at H = 1, dx = 1/64
#   width   the blend's half-width solids.transition = 1.5 2 3 4 cells at dx = 1/64
#   ca      the stiffness: Ca = 0.005 0.01 0.02 at dx = 1/64
# bench/suspension_dilute.py averages eta_r (output.wall_stress) over the last WIN of each
# run and writes results/suspension/dilute.csv and dilute_coefficient.png.
#   bash bench/run_suspension_dilute.sh [BUILD_DIR]
# Knobs (environment): SERIES ("res wall wallfine period width ca"), RES_NX ("128 192 256 512"),
# T_END (1.0: the end time of H = 1; H > 1 runs to T_END H^2, the slowest viscous mode's
# time H^2/(pi^2 nu) scaling), T_FINE (0.6: the end time of the res runs with nx >= 384, for
# time), WIN (0.4: the averaged fraction of each run, its end), JOBS (1), RUNS (the run
# directories, kept; default a temporary directory), RESUME (set: keep the runs of RUNS that
# finished, e.g. a long one run apart with SERIES=res RES_NX=512).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build}/refmap
SERIES=${SERIES:-"res wall wallfine period width ca"}
RES_NX=${RES_NX:-"128 192 256 512"}
T_END=${T_END:-1.0}
T_FINE=${T_FINE:-0.6}
WIN=${WIN:-0.4}
JOBS=${JOBS:-1}
if [ -z "${RUNS:-}" ]; then
  RUNS=$(mktemp -d)
  trap 'rm -rf "$RUNS"' EXIT
fi
mkdir -p "$RUNS" results/suspension
list="$RUNS/dilute_runs.$$.txt"  # one per invocation: several may share RUNS (RESUME)
: > "$list"
# one line per run: directory series L H nx ny transition Ca t_end
add() {  # series L H nx transition Ca
  local s=$1 L=$2 H=$3 nx=$4 wt=$5 ca=$6
  local ny t
  ny=$(/usr/bin/python3 -c "print(round($nx * $H / $L))")
  t=$(/usr/bin/python3 -c "print(repr($T_FINE if '$s' == 'res' and $nx >= 384 else $T_END * max(1.0, $H) ** 2))")
  # the directory is named by the parameters, so a run shared by two series runs once
  echo "$RUNS/L${L}_H${H}_nx${nx}_w${wt}_ca${ca}_t${t} $s $L $H $nx $ny $wt $ca $t" >> "$list"
}
for s in $SERIES; do
  case $s in
    res) for nx in $RES_NX; do add res 2 1 "$nx" 3 0.01; done ;;
    wallfine) for H in 1 1.5; do add wallfine "$(/usr/bin/python3 -c "print(2 * $H)")" "$H" \
            "$(/usr/bin/python3 -c "print(round(256 * $H))")" 3 0.01; done ;;
    wall) for H in 0.5 0.75 1 1.5 2; do add wall "$(/usr/bin/python3 -c "print(2 * $H)")" "$H" \
            "$(/usr/bin/python3 -c "print(round(128 * $H))")" 3 0.01; done ;;
    period) for L in 1 2 4; do add period "$L" 1 $((64 * L)) 3 0.01; done ;;
    width) for wt in 1.5 2 3 4; do add width 2 1 128 "$wt" 0.01; done ;;
    ca) for ca in 0.005 0.01 0.02; do add ca 2 1 128 3 "$ca"; done ;;
    *) echo "unknown series $s" >&2; exit 2 ;;
  esac
done
run_one() {
  local dir=$1 L=$3 H=$4 nx=$5 ny=$6 wt=$7 ca=$8 t=$9
  if [ -n "${RESUME:-}" ] && [ "$(cat "$dir.rc" 2>/dev/null)" = 0 ]; then
    echo "$(basename "$dir"): kept" >&2
    return
  fi
  local mu_s
  mu_s=$(/usr/bin/python3 -c "print(repr(0.5 / $ca))")  # G = 2 mu_s = mu gamma / Ca
  rm -rf "$dir"
  mkdir -p "$dir.in"
  cat > "$dir.in/cell.toml" <<TOML
name = "dilute_disc"
[domain]
lx = $L
ly = $H
[grid]
nx = $nx
ny = $ny
[fluid]
density = 1.0
viscosity = 1.0
[boundary]
left = "periodic"
right = "periodic"
bottom = { type = "moving_wall", velocity = $(/usr/bin/python3 -c "print(-0.5 * $H)") }
top = { type = "moving_wall", velocity = $(/usr/bin/python3 -c "print(0.5 * $H)") }
[initial]
velocity = "expression"
u_expr = "y - $(/usr/bin/python3 -c "print(0.5 * $H)")"
v_expr = "0"
[time]
end = $t
viscous = "implicit"
[output]
vtk = false
wall_stress = true
[solids]
transition = $wt
[[solid]]
name = "disc"
shape = "circle"
center = [$(/usr/bin/python3 -c "print(0.5 * $L)"), $(/usr/bin/python3 -c "print(0.5 * $H)")]
radius = 0.1
mu_s = $mu_s
density = 1.0
viscosity = 1.0
velocity = "fluid"
TOML
  local rc=0
  OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE "$bin" run "$dir.in/cell.toml" --out "$dir" --threads 1 --quiet \
    2> "$dir.err" || rc=$?
  echo "$rc" > "$dir.rc"
  echo "$(basename "$dir"): exit $rc" >&2
}
export -f run_one
export bin RESUME
awk '!seen[$1]++' "$list" | xargs -P "$JOBS" -L 1 bash -c 'run_one "$@"' _
/usr/bin/python3 bench/suspension_dilute.py --runs "$list" --win "$WIN" --out results/suspension
