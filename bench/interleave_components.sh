#!/bin/bash
# Interleaved wall times of two refmap binaries (BIN_DIR/refmap-base, BIN_DIR/refmap-final),
# 1 and 2 threads, VTK off, three rounds: the components refactor measured "no slower"
# (results/performance.md, "Components refactor"). Usage: BIN_DIR=DIR bash bench/interleave_components.sh
cd "$(dirname "$0")/.."
out=results/raw/components_interleaved.csv; echo "scene,binary,round,threads,wall_s" > $out
declare -A steps=([disc_tgv]=300 [two_solids_tgv]=300 [lid_driven_cavity_re100]=400 [actuated_disc]=300 [turek_hron_fsi2]=150)
for round in 1 2 3; do
 for s in disc_tgv two_solids_tgv lid_driven_cavity_re100 actuated_disc turek_hron_fsi2; do
  for b in base final; do
   for th in 1 2; do
    t0=$(date +%s.%N)
    OMP_NUM_THREADS=$th ${BIN_DIR:?set BIN_DIR to the folder holding refmap-base and refmap-final}/refmap-$b run scenes/$s.toml --out /tmp/il_$b --threads $th --quiet --set time.max_steps=${steps[$s]} --set output.vtk=false >/dev/null 2>&1
    t1=$(date +%s.%N)
    echo "$s,$b,$round,$th,$(echo "$t1 - $t0" | bc)" >> $out
   done
  done
 done
done
