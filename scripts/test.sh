#!/usr/bin/env bash
# Installs what is missing, builds refmap in Release and runs the whole test suite; then
# builds the unit tests with AddressSanitizer + UndefinedBehaviorSanitizer and runs them
# again (label `unit`; any report fails the test that triggered it).
# Usage: bash scripts/test.sh            (from the repository root)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
# the tests are independent: run two at a time, one OpenMP thread each
OMP_NUM_THREADS=1 ctest --test-dir build --output-on-failure -j"$(nproc)"

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DREFMAP_SANITIZE=ON -DREFMAP_BUILD_BENCH=OFF
cmake --build build-asan -j"$(nproc)" --target refmap_tests refmap
# detect_leaks: every allocation of refmap is owned (libgomp's thread pool is not reported)
OMP_NUM_THREADS=1 ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan -L unit --output-on-failure -j"$(nproc)"
