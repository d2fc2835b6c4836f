#!/usr/bin/env bash
# Installs what is missing, builds refmap in Release and runs the default demo scene.
# Usage: bash scripts/demo.sh [SCENE.toml]   (from the repository root)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/two_solids_tgv.toml}
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target refmap
name=$(basename "$scene" .toml)
./build/refmap run "$scene" --out "out/$name"
echo "demo output: $(pwd)/out/$name"
