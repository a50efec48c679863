#!/usr/bin/env bash
# Thread scaling and the bit-for-bit check on a machine with more cores (the device
# machine some sessions are lent: Ubuntu, other library versions, no dependencies).
#
#   bench/many_cores.sh pack [CACHE]   here: a portable build (x86-64-v3) of the two
#                                      benchmarks, the libraries they need that the other
#                                      machine lacks, the drilling window and the 20,000 bed
#                                      into build/device (CACHE: $REGODEM_BENCH_CACHE)
#   bench/many_cores.sh run            there, from the tree's root (carry build/device;
#                                      results into $OUT, else build/device/out)
#
# `run` times the drilling window (bench_drilling_window) and the settled bed with heat
# (bench_settled_bed) on 1, 2, 4, 8 and 16 threads (REGODEM_BENCH_THREADS) and prints the
# window's state hash on each: equal hashes are the same run, bit for bit.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
device="$here/build/device"
case "${1:-}" in
  pack)
    cache="${2:-${REGODEM_BENCH_CACHE:?give the bench cache (bench/make_drilling_window.sh made it)}}"
    cmake -S "$here" -B "$here/build/portable" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-march=x86-64-v3 \
      -DREGODEM_BUILD_TESTS=OFF -DREGODEM_BUILD_PYTHON=OFF -DREGODEM_BUILD_MPI=OFF
    cmake --build "$here/build/portable" -j2 --target bench_drilling_window bench_settled_bed
    mkdir -p "$device/lib" "$device/cache"
    cp "$here"/build/portable/bench/bench_{drilling_window,settled_bed} "$device/"
    cp "$(cat "$cache/drilling-window/window-checkpoint.txt")" "$device/window.rgck"
    cp "$cache/regodem-bench-bed-20000.csv" "$device/cache/"
    # Real files, not links, under the names the programs ask for.
    for lib in libbenchmark.so.1debian libspdlog.so.1.10 libyaml-cpp.so.0.7; do
      cp -L "/usr/lib/x86_64-linux-gnu/$lib" "$device/lib/$lib"
    done
    du -sh "$device"
    ;;
  run)
    out="${OUT:-$device/out}"
    mkdir -p "$out"
    export LD_LIBRARY_PATH="$device/lib" REGODEM_SOURCE_DIR="$here" REGODEM_DRILLING_WINDOW="$device/window.rgck"
    export REGODEM_BENCH_CACHE="$device/cache" REGODEM_BENCH_THREADS="${REGODEM_BENCH_THREADS:-1,2,4,8,16}"
    lscpu > "$out/lscpu.txt"
    "$device/bench_drilling_window" --benchmark_out="$out/window.json" --benchmark_out_format=json > "$out/window.txt" 2>&1
    python3 - "$out/window.json" <<'PY'
import json, sys
for b in json.load(open(sys.argv[1]))["benchmarks"]:
    print(b["name"], "state_hash %d" % b["state_hash"], "%.0f ms" % b["real_time"],
          "%.3g particle-steps/s" % b["particle_steps_per_s"])
PY
    "$device/bench_settled_bed" --benchmark_filter='BM_SettledBed/particles:20000/threads:[0-9]+/heat:1' \
      --benchmark_counters_tabular=true --benchmark_out="$out/bed.json" --benchmark_out_format=json
    ;;
  *) echo "usage: bench/many_cores.sh pack [CACHE] | run" >&2; exit 2 ;;
esac
