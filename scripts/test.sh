#!/usr/bin/env bash
# Installs what is missing, builds refmap in Release and runs the whole test suite.
# Usage: bash scripts/test.sh            (from the repository root)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
# the tests are independent: run two at a time, one OpenMP thread each
OMP_NUM_THREADS=1 ctest --test-dir build --output-on-failure -j"$(nproc)"
