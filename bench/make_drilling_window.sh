#!/usr/bin/env bash
# Makes the checkpoint that bench_drilling_window starts from: the reduced sieve model
# (scenarios/paper/drill-sieve-reduced.yaml) poured, then drilled to 25 mm, half of its
# 50 mm, where the run stops at a stage end and writes its checkpoint. About 2 min for
# the bed and 5-10 min for the drilling on this machine's 2 cores.
#
#   bench/make_drilling_window.sh [REGODEM_BINARY] [CACHE_DIR]
# defaults: build/release/regodem, $REGODEM_BENCH_CACHE or the working directory.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
regodem="${1:-$here/build/release/regodem}"
cache="${2:-${REGODEM_BENCH_CACHE:-$PWD}}"
bed="$cache/drilling-window-bed"
window="$cache/drilling-window"
"$regodem" run "$here/scenarios/paper/drill-sieve-reduced-bed.yaml" -o "$bed" --overwrite
"$regodem" run "$here/scenarios/paper/drill-sieve-reduced.yaml" -o "$window" --overwrite \
  --set "initial_state.checkpoint=$bed" --set "stages.drill.until.depth=25 mm"
ls "$window"/checkpoints/*.rgck | tail -1 > "$window/window-checkpoint.txt"
echo "bench_drilling_window starts from $(cat "$window/window-checkpoint.txt")"
