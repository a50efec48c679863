#!/usr/bin/env bash
# Builds RegoDEM with warnings as errors and runs every test; then builds with the
# address and undefined-behaviour sanitizers and runs every test again under them.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${REGODEM_BUILD_JOBS:-2}"

cmake --preset ci
cmake --build --preset ci -j "$jobs"
# Physics tests use two threads each: run the test programs one at a time.
ctest --preset ci

cmake --preset asan
cmake --build --preset asan -j "$jobs"
ctest --preset asan
