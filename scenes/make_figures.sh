#!/usr/bin/env bash
# Runs the paper's scenes with refmap and turns each run into PNGs with scenes/plot_run.py:
# results/figures/<figure>/*.png, plus RUN_INFO.txt there (command, grid, wall time, git rev).
#
#   bash scenes/make_figures.sh                 # every scene at its default resolution
#   QUICK=1 bash scenes/make_figures.sh         # coarse quick runs (grids halved, shorter cavity)
#   bash scenes/make_figures.sh zalesak disc_tgv_conservative   # only these figures (names below)
#   PLOT_ONLY=1 bash scenes/make_figures.sh      # re-plot the existing runs in $OUT, no simulation
#
# Environment: REFMAP (binary, default build/refmap), THREADS (default 1), OUT (run
# directories, default out/figures), DEST (PNGs, default results/figures), PYTHON (a python3
# with numpy and matplotlib; default /usr/bin/python3 if it has them, else python3), DPI.
# Scenes that are not on this branch (two_solids_tgv, wall_microgravity, bounce_stiff,
# bounce_soft) are skipped with a note. A run that stops early (exit 3: non-finite fields,
# e.g. the non-conservative disc) is still plotted from the frames it wrote.
set -uo pipefail
cd "$(dirname "$0")/.."

REFMAP=${REFMAP:-build/refmap}
THREADS=${THREADS:-1}
OUT=${OUT:-out/figures}
DEST=${DEST:-results/figures}
DPI=${DPI:-110}
QUICK=${QUICK:-0}
if [ -z "${PYTHON:-}" ]; then
  PYTHON=python3
  if /usr/bin/python3 -c 'import numpy, matplotlib' 2>/dev/null; then PYTHON=/usr/bin/python3; fi
fi
if [ ! -x "$REFMAP" ]; then
  echo "make_figures: $REFMAP not found: build first (cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2)" >&2
  exit 2
fi
if ! "$PYTHON" -c 'import numpy, matplotlib' 2>/dev/null; then
  echo "make_figures: $PYTHON lacks numpy/matplotlib (Debian: apt-get install python3-numpy python3-matplotlib)" >&2
  exit 2
fi

ONLY=("$@")
SUMMARY=()
FAILED=0

wanted() {
  [ ${#ONLY[@]} -eq 0 ] && return 0
  local n
  for n in "${ONLY[@]}"; do [ "$n" = "$1" ] && return 0; done
  return 1
}

toml_int() {  # toml_int FILE KEY: first integer value of 'KEY = N' in FILE
  sed -n "s/^[[:space:]]*$2[[:space:]]*=[[:space:]]*\([0-9][0-9]*\).*/\1/p" "$1" | head -n 1
}

# figure NAME SCENE "PLOT ARGS" [--set k=v ...]
figure() {
  local name=$1 scene=$2 plot_args=$3
  shift 3
  local sets=("$@")
  wanted "$name" || return 0
  if [ ! -f "$scene" ]; then
    echo "make_figures: $name: $scene is not on this branch, skipped"
    SUMMARY+=("$name: skipped ($scene missing)")
    return 0
  fi
  local nx ny
  nx=$(toml_int "$scene" nx)
  ny=$(toml_int "$scene" ny)
  if [ "$QUICK" = 1 ]; then
    if [ -n "$nx" ] && [ -n "$ny" ] && [ "$nx" -ge 16 ] && [ "$ny" -ge 16 ]; then
      nx=$((nx / 2))
      ny=$((ny / 2))
      sets+=(--set "grid.nx=$nx" --set "grid.ny=$ny")
    fi
    case $name in
      lid_driven_cavity_re1000) sets+=(--set time.end=30) ;;  # not yet steady: a quick look only
    esac
  fi
  for ((k = 0; k < ${#sets[@]}; k++)); do  # a --set of the grid given by the caller wins
    case ${sets[$k]} in
      grid.nx=*) nx=${sets[$k]#grid.nx=} ;;
      grid.ny=*) ny=${sets[$k]#grid.ny=} ;;
    esac
  done
  local run="$OUT/$name" dest="$DEST/$name"
  mkdir -p "$dest" "$OUT"
  local cmd=("$REFMAP" run "$scene" --out "$run" --threads "$THREADS" --quiet "${sets[@]}")
  local t0 t1 rc wall rev
  if [ "${PLOT_ONLY:-0}" = 1 ]; then
    if [ ! -f "$run.status" ]; then
      echo "make_figures: $name: PLOT_ONLY=1 but no earlier run in $run, skipped"
      SUMMARY+=("$name: skipped (no run in $run)")
      return 0
    fi
    read -r rc wall rev < "$run.status"
    echo "make_figures: $name: re-plotting $run (${nx}x${ny})"
  else
    rm -rf "$run"
    echo "make_figures: $name: ${nx}x${ny}: ${cmd[*]}"
    t0=$(date +%s.%N)
    "${cmd[@]}" > "$run.log" 2>&1
    rc=$?
    t1=$(date +%s.%N)
    wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
    rev="$(git rev-parse --short HEAD 2>/dev/null)$(git diff --quiet HEAD -- solver kernels "$scene" 2>/dev/null || echo '+dirty')"
    echo "$rc $wall $rev" > "$run.status"
  fi
  local status="completed"
  if [ "$rc" -ne 0 ]; then
    status="stopped early (exit $rc): $(grep -m1 -i 'error\|stopp\|non-finite' "$run.log" | head -c 300)"
    echo "make_figures: $name: $status"
    if [ ! -f "$run/diagnostics.csv" ]; then
      FAILED=1
      SUMMARY+=("$name: FAILED, exit $rc (log $run.log)")
      return 0
    fi
  fi
  local t_last
  t_last=$(tail -n 1 "$run/diagnostics.csv" | cut -d, -f2)
  rm -f "$dest"/*.png "$dest"/path_distance.txt
  # shellcheck disable=SC2086
  local pcmd=("$PYTHON" scenes/plot_run.py "$run" --out "$dest" --dpi "$DPI" --title "$name" $plot_args)
  if ! "${pcmd[@]}" > "$run.plot.log" 2>&1; then
    cat "$run.plot.log" >&2
    FAILED=1
    SUMMARY+=("$name: plotting FAILED (log $run.plot.log)")
    return 0
  fi
  {
    echo "figure: $name"
    echo "scene: $scene"
    echo "grid: ${nx}x${ny}$([ "$QUICK" = 1 ] && echo ' (QUICK=1)')"
    echo "run: ${cmd[*]}"
    echo "run status: $status; simulated to t = $t_last; wall time ${wall} s ($THREADS thread(s))"
    echo "plot: ${pcmd[*]}"
    echo "git (solver at run time): $rev"
    echo "date: $(date -u -r "$run/diagnostics.csv" '+%Y-%m-%d %H:%M UTC') (run finished)"
    echo "host: $(nproc) cores, load at plotting $(cut -d' ' -f1-3 /proc/loadavg) (the machine was shared: wall times are upper bounds)"
    if [ -f "$dest/path_distance.txt" ]; then echo "centroid path distances:"; grep -v '^#' "$dest/path_distance.txt"; fi
  } > "$dest/RUN_INFO.txt"
  SUMMARY+=("$name: ${nx}x${ny}, t = $t_last, ${wall} s, $status -> $dest/")
}

REFS="--reference-path tests/data/sugiyama2011_disc_centroid_path.csv:Sugiyama2011 --reference-path tests/data/kolahdouz2023_disc_centroid_path.csv:Kolahdouz2023"

GHIA="--probe-reference u_vertical=tests/data/ghia1982_u_vertical.csv:y_exact:u_Re1000:Ghia1982 --probe-reference v_horizontal=tests/data/ghia1982_v_horizontal.csv:x_exact:v_Re1000:Ghia1982"

figure lid_driven_cavity_re1000 scenes/lid_driven_cavity_re1000.toml "--field speed,p --count 1 $GHIA"
figure zalesak scenes/zalesak.toml "--field speed --times 0,0.25,0.5,0.75,1 --columns 5"
figure disc_tgv_conservative scenes/disc_tgv.toml "--field vorticity --times 0,0.5,1,1.5,2,3,4 --columns 4"
figure disc_tgv_nonconservative scenes/disc_tgv.toml "--field vorticity --times 0,0.5,1,1.5,2,3,4 --columns 4" \
  --set solids.conservative=false
figure couette_elastic scenes/couette_elastic.toml "--field u --times 0.4,1.2,2,2.8,4,4.8 --columns 6 --probe-reference u_profile=tests/data/couette_elastic_startup.csv:y:u_t4.8:exact"
# to t = 20 (the scene stops at 8): the digitised Sugiyama path ends about there
figure soft_disc_cavity scenes/soft_disc_cavity.toml "--field vorticity --times 0,1,2,4,5,6,8,12,16,20 --columns 5 $REFS" \
  --set time.end=20
figure two_solids_tgv scenes/two_solids_tgv.toml "--field vorticity --count 8"
figure wall_microgravity scenes/wall_microgravity.toml "--field vorticity --count 8"
figure bounce_stiff scenes/bounce_stiff.toml "--field vorticity --count 8"
figure bounce_soft scenes/bounce_soft.toml "--field vorticity --count 8"

echo
echo "make_figures: summary"
for s in "${SUMMARY[@]}"; do echo "  $s"; done
exit $FAILED
