#!/usr/bin/env bash
# Runs every benchmark program in BUILD/bench and prints one table per module.
# Usage: bench/run_benchmarks.sh BUILD_DIR [extra Google Benchmark flags]
set -euo pipefail
build=${1:?usage: run_benchmarks.sh BUILD_DIR}
shift || true
shopt -s nullglob
programs=("$build"/bench/tirpol_*_bench)
if ((${#programs[@]} == 0)); then
  echo "no benchmark programs in $build/bench (configure with -DTIRPOL_BUILD_BENCHMARKS=ON)" >&2
  exit 1
fi
for prog in "${programs[@]}"; do
  name=$(basename "$prog")
  echo "=== ${name#tirpol_} ==="
  "$prog" --benchmark_min_time=0.2 --benchmark_counters_tabular=true "$@" 2>/dev/null
  echo
done
# Python benchmarks (bench/*.py) run against the built module; each skips with a message where its
# Python stack (e.g. cv2) is missing.
if [[ -d "$build/python/tirpol" ]]; then
  for script in "$(dirname "$0")"/*.py; do
    echo "=== $(basename "$script" .py) ==="
    PYTHONPATH="$build/python" /usr/bin/python3 "$script"
    echo
  done
fi
