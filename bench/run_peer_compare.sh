#!/usr/bin/env bash
# Side by side with the peer code IncRMT (Rycroft et al. 2020; github chr1shr/incrmt, which
# needs github chr1shr/tgmg beside it): the same circles in both codes, whole steps timed,
# peak memory, at growing numbers of solids (results/performance.md,
# "Side by side with IncRMT").
#
#   PEER_DIR=/path/with/incrmt+tgmg bash bench/run_peer_compare.sh [REFMAP_BINARY]
#
# PEER_DIR holds the peer's two repositories as PEER_DIR/incrmt and PEER_DIR/tgmg (any
# checkout; none of their code is in refmap). The script writes PEER_DIR/config.mk from the
# peer's own Linux template (g++ -fopenmp -O3) when there is none, builds the peer's
# libraries with its Makefiles and bench/peer/incrmt_discs.cc (our timing driver) against
# them, then for each case writes the scene and the circle list with
# bench/scenes/make_incrmt_circles.py and runs refmap and the peer INTERLEAVED, REPS rounds
# (the order alternating), each under GNU time for the peak resident memory, both on
# THREADS threads, WARM untimed steps then STEPS timed steps of each code's own time step.
# The machine's 1-minute load is recorded before every run: on a shared machine the ratio
# of two runs made seconds apart means more than either time.
#
# Cases (CASES, "label:circles:cells"): "42:42:128" is the peer's own 42-circle `multi-drop`
# example; "lattice:N:M" is N circles on a lattice (make_incrmt_circles.py --lattice). The
# peer keeps full-grid arrays for every solid (about 210 bytes per cell per solid), so its
# memory is solids x cells: MAX_PEER_GB skips a peer run whose estimate exceeds it.
#
# Knobs: CASES (default "42:42:128 lattice:16:512 lattice:64:512 lattice:144:512"), REPS (3),
# WARM (2), STEPS (5), THREADS (1), MAX_PEER_GB (10), OUT (results/peer_compare.csv),
# RAW (/tmp/refmap_peer).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
bin=$(realpath "${1:-build/refmap}")
: "${PEER_DIR:?set PEER_DIR to the directory holding incrmt/ and tgmg/}"
PEER_DIR=$(realpath "$PEER_DIR")
CASES=${CASES:-"42:42:128 lattice:16:512 lattice:64:512 lattice:144:512"}
REPS=${REPS:-3}; WARM=${WARM:-2}; STEPS=${STEPS:-5}; THREADS=${THREADS:-1}
MAX_PEER_GB=${MAX_PEER_GB:-10}
OUT=${OUT:-results/peer_compare.csv}
RAW=${RAW:-/tmp/refmap_peer}
mkdir -p "$RAW"

# ---- build the peer (its Makefiles, its compiler flags) and our driver
[ -f "$PEER_DIR/config.mk" ] || cp "$PEER_DIR/incrmt/config/config.mk.linux" "$PEER_DIR/config.mk"
make -s -C "$PEER_DIR/tgmg" lib
make -s -C "$PEER_DIR/incrmt/levelset" liblevel++.a
make -s -C "$PEER_DIR/incrmt" libf2d.a
peer="$PEER_DIR/incrmt_discs"
g++ -fopenmp -O3 -I"$PEER_DIR/incrmt" -I"$PEER_DIR/tgmg" -I"$PEER_DIR/incrmt/levelset" \
  bench/peer/incrmt_discs.cc -o "$peer" -L"$PEER_DIR/incrmt" -L"$PEER_DIR/incrmt/levelset" -lf2d -llevel++

peer_rev=$(git -C "$PEER_DIR/incrmt" rev-parse --short HEAD 2>/dev/null || echo unknown)
{
  echo "# refmap $(git rev-parse --short HEAD) ($bin) beside IncRMT $peer_rev (bench/peer/incrmt_discs.cc)"
  echo "# $(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1), $(nproc) cores; $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "# command: CASES='$CASES' REPS=$REPS WARM=$WARM STEPS=$STEPS THREADS=$THREADS bash bench/run_peer_compare.sh"
  echo "case,circles,cells,round,code,load_1min,steps,seconds,us_per_cell_step,dt,peak_rss_mb"
} > "$OUT"

run_refmap() {  # case circles m round scene
  local load dir="$RAW/refmap_$1_$2_$3"
  load=$(cut -d' ' -f1 /proc/loadavg)
  rm -rf "$dir"
  OMP_NUM_THREADS=$THREADS /usr/bin/time -v "$bin" run "$5" --out "$dir" --threads "$THREADS" --quiet \
    --timing-warmup "$WARM" --set time.max_steps=$((WARM + STEPS)) --set output.vtk=false \
    > "$dir.log" 2> "$dir.time"
  local t="$dir/timings.csv" rss wall steps dt
  rss=$(awk '/Maximum resident set size/ {print $NF}' "$dir.time")
  wall=$(grep "^# timed_wall_s:" "$t" | cut -d: -f2 | tr -d ' ')
  steps=$(grep "^# timed_steps:" "$t" | cut -d: -f2 | tr -d ' ')
  dt=$(awk -F, '/^#/ {next} !h {h = 1; for (i = 1; i <= NF; i++) if ($i == "dt") c = i; next} c {v = $c} END {print v}' \
       "$dir/diagnostics.csv")
  python3 -c "import sys; c,n,m,r,l,s,w,dt,rss=sys.argv[1:]; \
print(f'{c},{n},{m},{r},refmap,{l},{s},{float(w):.4f},{float(w)*1e6/(int(m)**2*int(s)):.4f},{dt},{int(rss)/1024:.1f}')" \
    "$1" "$2" "$3" "$4" "$load" "$steps" "$wall" "$dt" "$rss" >> "$OUT"
}

run_peer() {  # case circles m round list
  local load dir="$RAW/peer_$1_$2_$3"
  load=$(cut -d' ' -f1 /proc/loadavg)
  mkdir -p "$dir"
  # the driver runs in its own directory (the peer's constructor names an output directory)
  (cd "$dir" && OMP_NUM_THREADS=$THREADS /usr/bin/time -v "$peer" "$5" "$3" "$WARM" "$STEPS" > out.txt 2> time.txt)
  local rss line
  rss=$(awk '/Maximum resident set size/ {print $NF}' "$dir/time.txt")
  line=$(tail -1 "$dir/out.txt")  # circles m steps seconds us dt
  read -r _ _ s w us dt <<< "$line"
  python3 -c "import sys; c,n,m,r,l,s,w,us,dt,rss=sys.argv[1:]; \
print(f'{c},{n},{m},{r},incrmt,{l},{s},{float(w):.4f},{float(us):.4f},{dt},{int(rss)/1024:.1f}')" \
    "$1" "$2" "$3" "$4" "$load" "$s" "$w" "$us" "$dt" "$rss" >> "$OUT"
}

for c in $CASES; do
  IFS=: read -r label n m <<< "$c"
  list="$RAW/circles_${label}_$n.txt"
  if [ "$label" = 42 ]; then
    scene=$(python3 bench/scenes/make_incrmt_circles.py "$RAW" "$m" --list "$list")
  else
    scene=$(python3 bench/scenes/make_incrmt_circles.py "$RAW" "$m" --lattice "$n" --list "$list")
  fi
  peer_gb=$(python3 -c "print(f'{$n * ($m + 4) ** 2 * 210 / 1e9:.1f}')")
  peer_ok=$(python3 -c "print(int($peer_gb <= $MAX_PEER_GB))")
  [ "$peer_ok" = 1 ] || echo "   $c: the peer would need about $peer_gb GB (> MAX_PEER_GB = $MAX_PEER_GB): refmap only"
  for r in $(seq 1 "$REPS"); do
    if [ $((r % 2)) = 1 ]; then
      run_refmap "$label" "$n" "$m" "$r" "$scene"
      [ "$peer_ok" = 1 ] && run_peer "$label" "$n" "$m" "$r" "$list"
    else
      [ "$peer_ok" = 1 ] && run_peer "$label" "$n" "$m" "$r" "$list"
      run_refmap "$label" "$n" "$m" "$r" "$scene"
    fi
    echo "   $c round $r: done"
  done
done
cat "$OUT"
