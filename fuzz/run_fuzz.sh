#!/usr/bin/env bash
# Runs every libFuzzer target of a TIRPOL_FUZZ build for a bounded time under ASan+UBSan and prints
# the totals per target (inputs run, crashes, hangs, out-of-memory). Fails on any finding, naming
# the input libFuzzer saved; keep it as tests/data/fuzz-regressions/<target>/<name> once fixed, so
# the fuzz_replay.<target> ctest test replays it in every build.
#   fuzz/run_fuzz.sh BUILD_DIR [SECONDS_PER_TARGET]        (default TIRPOL_FUZZ_SECONDS or 12)
# With TIRPOL_FUZZ_RUNS=N each target runs exactly N inputs from the fixed seed instead of for a time,
# so the result depends only on the tree, not on the machine's speed (what `./run test` uses).
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$(cd "${1:?usage: fuzz/run_fuzz.sh BUILD_DIR [SECONDS_PER_TARGET]}" && pwd)
SECONDS_PER_TARGET=${2:-${TIRPOL_FUZZ_SECONDS:-12}}
RSS_LIMIT_MB=${TIRPOL_FUZZ_RSS_MB:-2048}
HANG_S=${TIRPOL_FUZZ_HANG_S:-10}
OUT=$BUILD/fuzz-results
rm -rf "$OUT" && mkdir -p "$OUT"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:allocator_may_return_null=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

targets=()
for exe in "$BUILD"/fuzz/tirpol_fuzz_*; do
  [[ -x $exe && $exe != *_replay ]] && targets+=("$(basename "$exe" | sed 's/^tirpol_fuzz_//')")
done
if ((${#targets[@]} == 0)); then
  echo "run_fuzz: no fuzz executables in $BUILD/fuzz (configure with -DTIRPOL_FUZZ=ON and clang)" >&2
  exit 1
fi

seeds_of() {  # the seed folders of a target: fuzz/corpus/<t>, tests/data/fuzz-regressions/<t>, seed_dirs.txt
  local t=$1 dirs=("$ROOT/fuzz/corpus/$t" "$ROOT/tests/data/fuzz-regressions/$t")
  while read -r name rest; do
    [[ $name == "$t" ]] && for d in $rest; do dirs+=("$ROOT/$d"); done
  done < <(grep -v '^#' "$ROOT/fuzz/seed_dirs.txt")
  for d in "${dirs[@]}"; do [[ -d $d ]] && echo "$d"; done  # libFuzzer stops at a missing folder
}

budget=(-max_total_time="$SECONDS_PER_TARGET")
[[ -n ${TIRPOL_FUZZ_RUNS:-} ]] && budget=(-runs="$TIRPOL_FUZZ_RUNS")
failed=0
printf '%-18s %10s %8s %6s %5s  %s\n' target inputs crashes hangs ooms result | tee "$OUT/summary.txt"
for t in "${targets[@]}"; do
  mkdir -p "$OUT/$t/corpus" "$OUT/$t/artifacts"
  mapfile -t seeds < <(seeds_of "$t")
  # A fixed libFuzzer seed (TIRPOL_FUZZ_SEED, default 1; 0 = random) makes CI explore the same
  # inputs from the same corpus on every run, so a pass or a finding is reproducible; campaigns
  # that look further set another seed or 0.
  # The first folder receives new inputs; the seed folders are only read. Inputs are capped at 64 KB
  # (the real files are smaller), so a run explores structure rather than size.
  mkdir -p "$OUT/$t/tmp"
  ( cd "$OUT/$t" && TMPDIR="$OUT/$t/tmp" timeout $((SECONDS_PER_TARGET + 120)) "$BUILD/fuzz/tirpol_fuzz_$t" \
      -seed="${TIRPOL_FUZZ_SEED:-1}" "${budget[@]}" -rss_limit_mb="$RSS_LIMIT_MB" \
      -timeout="$HANG_S" -max_len=65536 \
      -print_final_stats=1 -artifact_prefix="$OUT/$t/artifacts/" "$OUT/$t/corpus" "${seeds[@]}" ) \
      >"$OUT/$t/log.txt" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$OUT/$t/log.txt" | grep -o '[0-9]*$' | tail -1)
  crashes=0 hangs=0 ooms=0
  grep -q 'ERROR: libFuzzer: timeout' "$OUT/$t/log.txt" && hangs=1
  grep -q 'ERROR: libFuzzer: out-of-memory\|ERROR: libFuzzer: malloc' "$OUT/$t/log.txt" && ooms=1
  if ((rc != 0 && hangs == 0 && ooms == 0)); then crashes=1; fi
  result=ok
  if ((rc != 0)); then
    result="FAILED: $(ls "$OUT/$t/artifacts" 2>/dev/null | head -1) (log: $OUT/$t/log.txt)"
    [[ $rc == 124 ]] && result="FAILED: the run itself did not end (log: $OUT/$t/log.txt)"
    failed=1
  fi
  printf '%-18s %10s %8s %6s %5s  %s\n' "$t" "${runs:-?}" "$crashes" "$hangs" "$ooms" "$result" | tee -a "$OUT/summary.txt"
done
if ((failed)); then
  echo "run_fuzz: a target found a crash, hang or out-of-memory input; see the artifact named above" >&2
  exit 1
fi
echo "run_fuzz: all ${#targets[@]} targets ran ${TIRPOL_FUZZ_RUNS:-${SECONDS_PER_TARGET}s} ${TIRPOL_FUZZ_RUNS:+inputs} each without a finding (summary: $OUT/summary.txt)"
