#!/usr/bin/env bash
# Flow past a fixed cylinder at Re = 20 (Schafer & Turek 1996, test 2D-1; 
# docs/references.md#cylinder-in-a-channel-at-re--20): scenes/cylinder_re20.toml run to its steady state on several
# grids with each rigid-body forcing (docs/bodies.md), then bench/cylinder_summary.py writes
# results/cylinder_re20.csv (c_D, c_L, Delta p, recirculation length and the cost of each run:
# steps, wall time, threads, ms per step, the load average at its start and end; and the
# published bounds),
# results/cylinder_re20_convergence.csv (errors per grid and observed orders) and
# results/figures/cylinder_re20_accuracy_vs_cost.png.
#
#   bash bench/run_cylinder.sh                  # 4 variants x dx = 0.01, 0.005, 0.0025 + dt study
#   FORCINGS=sharp GRIDS="0.01 0.005" bash bench/run_cylinder.sh
#   KEEP=1 FORCINGS=sharp+hold+inc bash bench/run_cylinder.sh   # add one variant to the CSV
#
# Knobs: BIN (refmap executable, default build/refmap), RAW (run directories, default
# /tmp/refmap_cylinder), FORCINGS (default "diffuse interpolated sharp sharp+hold+inc": a
# forcing, with "+hold" solid[0].forcing_hold = true and with "+inc" time.splitting =
# "increment", docs/bodies.md; each run is named <variant>_dx_<dx>[_dtN]), KEEP (default 0;
# 1: the rows of the existing CSV whose run directories are not in RAW are kept, so a
# variant can be added without re-running the others), GRIDS (dx values among 0.01 0.005 0.0025 0.00125), THREADS
# (default 1; the two finest grids use THREADS_FINE, default 1, with OMP_WAIT_POLICY=PASSIVE:
# docs/performance.md, threads), VISCOUS ("explicit" or "implicit", default "implicit": on the finer grids the
# explicit viscous limit rho dx^2 / (6 mu) is below the advective one, see results/validation.md),
# T_STOP (default 8: every run stops after round(T_STOP / dt) steps instead of at its steady
# state near t = 17 (steady_tol): c_D moves by less than 1e-5 after t = 8 with every forcing on
# 10 and 20 cells per diameter, measured; 0 runs to the steady state. A step count, not an end
# time: a last step cut short to land on an end time spoils the force and the pressure),
# FINE_STEPS (default 2600: the 0.0025 grid stops after 2600 steps, t = 6.03, c_D within 1e-4 of
# its steady value on the coarser grids; the 0.00125 grid after 2 FINE_STEPS), DT_STUDY (default 1: the 0.01
# grid again at dt / 2 and dt / 4 for each forcing; 0: none), DT_STUDY_DX (default 0.01: the grid of the
# dt study, e.g. 0.005; runs <variant>_dx_<dx>_dt<f>), DT_FACTORS (default "2 4": the divisors of dt
# in the dt study), RADIUS_STUDY (default 0; 1: one extra
# diffuse run on dx = 0.005 with the radius reduced by dx/2, where the diffuse surface sits),
# REUSE (default 0; 1: keep a run whose directory already holds timings.csv), CSV (default
# results/cylinder_re20.csv). The summary reads every run directory in RAW, so runs of earlier
# invocations (other FORCINGS or GRIDS) are summarised with the new ones.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BIN="${BIN:-build/refmap}"
RAW="${RAW:-/tmp/refmap_cylinder}"
GRIDS="${GRIDS-0.01 0.005 0.0025}"  # GRIDS="" : the dt study only
VISCOUS="${VISCOUS:-implicit}"
mkdir -p "$RAW"
export OMP_WAIT_POLICY=PASSIVE

run() {  # run VARIANT NAME DX THREADS DT [extra --set ..., a later time.max_steps wins]
  local variant=$1 name=$1_$2 dx=$3 threads=$4 dt=$5
  shift 5
  # a variant is a forcing with options: <forcing>[+hold][+inc][+rc][+quad][+ap] (+hold: solid[0].forcing_hold,
  # +inc: time.splitting = "increment"; docs/bodies.md, docs/method.md)
  # Every option is set either way, since the scene as shipped is sharp+hold+inc+rc+quad: a
  # variant without "+hold" runs without held cells, and so on.
  local forcing=${variant%%+*} opts=()
  case "$variant" in
    *+hold*) opts+=(--set "solid[0].forcing_hold=true") ;;
    *) opts+=(--set "solid[0].forcing_hold=false") ;;
  esac
  case "$variant" in
    *+inc*) opts+=(--set 'time.splitting="increment"') ;;
    *) opts+=(--set 'time.splitting="split"') ;;
  esac
  # +rc: time.rhie_chow_dt = the grid's own dt, 0.9278 dx, also in the dt study (0: dt itself)
  case "$variant" in
    *+rc*) opts+=(--set "time.rhie_chow_dt=$(python3 -c "print(0.9278 * $dx)")") ;;
    *) opts+=(--set "time.rhie_chow_dt=0") ;;
  esac
  # +quad: solid[0].forcing_interpolation = "quadratic" (docs/bodies.md)
  case "$variant" in
    *+quad*) opts+=(--set 'solid[0].forcing_interpolation="quadratic"') ;;
    *) opts+=(--set 'solid[0].forcing_interpolation="linear"') ;;
  esac
  # +ap: solid[0].forcing_faces = "aperture" (sharp forcing only: the cut faces as cut-cell faces,
  # docs/bodies.md)
  case "$variant" in
    *+ap*) opts+=(--set 'solid[0].forcing_faces="aperture"') ;;
    *) opts+=(--set 'solid[0].forcing_faces="staircase"') ;;
  esac
  if [ "${REUSE:-0}" = "1" ] && [ -f "$RAW/$name/timings.csv" ]; then
    echo "cylinder_re20: $name kept" >&2
    return
  fi
  local nx ny
  nx=$(python3 -c "print(round(2.2 / $dx))")
  ny=$(python3 -c "print(round(0.41 / $dx))")
  local stop=()
  [ "${T_STOP:-8}" != "0" ] && stop=(--set "time.max_steps=$(python3 -c "print(round(${T_STOP:-8} / $dt))")")
  echo "cylinder_re20: $name (dx = $dx, $nx x $ny, $threads thread(s), viscous = $VISCOUS, forcing = $forcing)" >&2
  rm -rf "${RAW:?}/$name"
  # the scene with four more probes: p at 1, 2 and 3 dx from the front and back surface points
  # on y = 0.2, all in fluid cells, from which bench/cylinder_summary.py extrapolates the
  # fluid's pressure to the surface (dp_fluid; the benchmark's points sit on the surface, where
  # a probe's bilinear stencil reads a cell inside the body), and u on the rows y = 0.2 -+ 3 dx / 2
  # beside the wake probe (L_a_centre: u on y = 0.2 itself, not the mean of the rows beside it)
  local scene="$RAW/$name.toml"
  { cat scenes/cylinder_re20.toml
    python3 -c "d = $dx
print(f'[[probe]]\nname = \"p_front_fluid\"\nfield = \"p\"\nstart = [{0.15 - 3 * d!r}, 0.2]\nend = [{0.15 - d!r}, 0.2]\npoints = 3')
print(f'[[probe]]\nname = \"p_back_fluid\"\nfield = \"p\"\nstart = [{0.25 + d!r}, 0.2]\nend = [{0.25 + 3 * d!r}, 0.2]\npoints = 3')
for n, y in (('below', 0.2 - 1.5 * d), ('above', 0.2 + 1.5 * d)):
    print(f'[[probe]]\nname = \"u_wake_{n}\"\nfield = \"u\"\nstart = [0.25, {y!r}]\nend = [0.45, {y!r}]\npoints = 81')"
  } > "$scene"
  local load0
  load0=$(cut -d' ' -f1 /proc/loadavg)
  OMP_NUM_THREADS=$threads nice "$BIN" run "$scene" --out "$RAW/$name" --quiet \
    --set grid.nx="$nx" --set grid.ny="$ny" --set time.dt="$dt" --set output.vtk=false --set output.diagnostics_every=10 \
    --set time.viscous="\"$VISCOUS\"" --set "solid[0].forcing=\"$forcing\"" "${opts[@]}" "${stop[@]}" "$@" \
    > "$RAW/$name.log" 2>&1 || { cat "$RAW/$name.log" >&2; exit 1; }
  # the machine's 1-minute load average at the run's start and end (the summary's load column)
  echo "$load0 $(cut -d' ' -f1 /proc/loadavg)" > "$RAW/$name/load.txt"
}

for forcing in ${FORCINGS:-diffuse interpolated sharp sharp+hold+inc}; do
  for dx in $GRIDS; do
    threads="${THREADS:-1}"
    extra=()
    case "$dx" in
      0.0025) threads="${THREADS_FINE:-1}"; extra=(--set "time.max_steps=${FINE_STEPS:-2600}") ;;
      0.00125) threads="${THREADS_FINE:-1}"; extra=(--set "time.max_steps=$((2 * ${FINE_STEPS:-2600}))") ;;
    esac
    # the scene's dt = 0.9278 dx on every grid
    run "$forcing" "dx_$dx" "$dx" "$threads" "$(python3 -c "print(0.9278 * $dx)")" "${extra[@]}"
  done
  if [ "${DT_STUDY:-1}" = "1" ]; then  # the grid DT_STUDY_DX at dt / f for f in DT_FACTORS
    dxs="${DT_STUDY_DX:-0.01}"
    for f in ${DT_FACTORS:-2 4}; do
      run "$forcing" "dx_${dxs}_dt$f" "$dxs" "${THREADS:-1}" "$(python3 -c "print(0.9278 * $dxs / $f)")"
    done
  fi
done
if [ "${RADIUS_STUDY:-0}" = "1" ]; then
  run diffuse "dx_0.005_r0.0475" 0.005 "${THREADS:-1}" 0.0046390 --set 'solid[0].radius=0.0475'
fi
CSV="${CSV:-results/cylinder_re20.csv}"
mkdir -p results/figures
dirs=()
for d in "$RAW"/*/; do [ -f "$d/timings.csv" ] && dirs+=("${d%/}"); done
keep=()
[ "${KEEP:-0}" = "1" ] && [ -f "$CSV" ] && keep=(--keep "$CSV")
/usr/bin/python3 bench/cylinder_summary.py "${keep[@]}" --convergence "${CSV%.csv}_convergence.csv" \
  --plot results/figures/cylinder_re20_accuracy_vs_cost.png "${dirs[@]}" > "$CSV.new"
mv "$CSV.new" "$CSV"
cat "$CSV" "${CSV%.csv}_convergence.csv"
