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
# The asan test preset leaves out Pour.* (the step and contact code of the other physics
# tests at more particles: two minutes under the sanitizers, proved by the release build),
# the four slowest physics tests whose code the other bond, mesh and moving-wall tests run
# under the sanitizers too (a bonded cantilever, a turning auger, a translating mesh plate
# and plate: 38 s) and PlotCommand.* (their work is Python's, which the sanitizers do not see).
ctest --preset asan
