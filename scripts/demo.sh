#!/usr/bin/env bash
# Installs what is missing, builds refmap in Release, runs the default demo scene (two soft
# solids colliding in a Taylor-Green vortex, the paper's Figs. 8-9) and draws its figures.
# Usage: bash scripts/demo.sh [SCENE.toml]   (from the repository root)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/two_solids_tgv.toml}
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target refmap
name=$(basename "$scene" .toml)
./build/refmap run "$scene" --out "out/$name"
# Debian's python3 has numpy and matplotlib (installed above); another python3 may come
# first in PATH without them
py=python3
if /usr/bin/python3 -c 'import numpy, matplotlib' 2>/dev/null; then py=/usr/bin/python3; fi
"$py" scenes/plot_run.py "out/$name" --out "out/$name/figures" --count 8
echo "demo output: $(pwd)/out/$name (VTK frames with $name.pvd for ParaView, diagnostics.csv, solids.csv, events.csv)"
echo "demo figures: $(pwd)/out/$name/figures"
