#!/usr/bin/env bash
# Runs every libFuzzer target of a TIRPOL_FUZZ build under ASan+UBSan and prints the totals per
# target (inputs run, crashes, hangs, out-of-memory). Fails on any finding, naming the input
# libFuzzer saved; keep it as tests/data/fuzz-regressions/<target>/<name> once fixed, so the
# fuzz_replay.<target> ctest test and this script's test mode replay it in every build.
#
#   fuzz/run_fuzz.sh --test BUILD_DIR
#       `./run test`: a fixed libFuzzer seed (1) and a fixed number of inputs per target
#       (fuzz/test_runs.txt), after every seed and regression input: the result depends only on the
#       tree. A target missing from test_runs.txt fails, so a new target cannot be left out.
#   fuzz/run_fuzz.sh BUILD_DIR [SECONDS_PER_TARGET]
#       `./run fuzz`: open-ended exploration for a time per target (default TIRPOL_FUZZ_SECONDS or
#       12), from a random seed (TIRPOL_FUZZ_SEED, default 0 = random; the log names the seed used).
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
mode=explore
if [[ ${1:-} == --test ]]; then mode=test; shift; fi
BUILD=$(cd "${1:?usage: fuzz/run_fuzz.sh [--test] BUILD_DIR [SECONDS_PER_TARGET]}" && pwd)
SECONDS_PER_TARGET=${2:-${TIRPOL_FUZZ_SECONDS:-12}}
RSS_LIMIT_MB=${TIRPOL_FUZZ_RSS_MB:-2048}
HANG_S=${TIRPOL_FUZZ_HANG_S:-10}
RUNS_FILE=$ROOT/fuzz/test_runs.txt
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

runs_of() {  # the fixed input count of a target in test mode
  awk -v t="$1" '$1 == t { print $2 }' "$RUNS_FILE"
}

failed=0
start_all=$SECONDS
printf '%-18s %10s %8s %6s %5s %6s  %s\n' target inputs crashes hangs ooms secs result | tee "$OUT/summary.txt"
for t in "${targets[@]}"; do
  mkdir -p "$OUT/$t/corpus" "$OUT/$t/artifacts" "$OUT/$t/tmp"
  mapfile -t seeds < <(seeds_of "$t")
  if [[ $mode == test ]]; then
    runs=$(runs_of "$t")
    if [[ -z $runs ]]; then
      printf '%-18s %10s %8s %6s %5s %6s  %s\n' "$t" - - - - - "FAILED: no run count in fuzz/test_runs.txt" |
        tee -a "$OUT/summary.txt"
      failed=1
      continue
    fi
    # -runs counts every execution, the seed and regression inputs included; the same seed, corpus
    # and binary make the same inputs in the same order.
    budget=(-seed=1 -runs="$runs")
    wall=$((HANG_S * 4 + 600))
  else
    budget=(-seed="${TIRPOL_FUZZ_SEED:-0}" -max_total_time="$SECONDS_PER_TARGET")
    wall=$((SECONDS_PER_TARGET + 120))
  fi
  # The first folder receives new inputs; the seed folders are only read. Inputs are capped at 64 KB
  # (the real files are smaller), so a run explores structure rather than size.
  start=$SECONDS
  ( cd "$OUT/$t" && TMPDIR="$OUT/$t/tmp" timeout "$wall" "$BUILD/fuzz/tirpol_fuzz_$t" \
      "${budget[@]}" -rss_limit_mb="$RSS_LIMIT_MB" -timeout="$HANG_S" -max_len=65536 \
      -print_final_stats=1 -artifact_prefix="$OUT/$t/artifacts/" "$OUT/$t/corpus" "${seeds[@]}" ) \
      >"$OUT/$t/log.txt" 2>&1
  rc=$?
  elapsed=$((SECONDS - start))
  inputs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$OUT/$t/log.txt" | grep -o '[0-9]*$' | tail -1)
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
  printf '%-18s %10s %8s %6s %5s %6s  %s\n' "$t" "${inputs:-?}" "$crashes" "$hangs" "$ooms" "$elapsed" "$result" |
    tee -a "$OUT/summary.txt"
done
echo "run_fuzz: $((SECONDS - start_all)) s for ${#targets[@]} targets" | tee -a "$OUT/summary.txt"
if ((failed)); then
  echo "run_fuzz: a target found a crash, hang or out-of-memory input; see the artifact named above" >&2
  [[ $mode == test ]] && echo "run_fuzz: test mode is deterministic: the same tree finds it again (docs/fuzzing.md)" >&2
  exit 1
fi
if [[ $mode == test ]]; then
  echo "run_fuzz: all ${#targets[@]} targets ran their fixed inputs (fuzz/test_runs.txt, seed 1) without a finding"
else
  echo "run_fuzz: all ${#targets[@]} targets ran ${SECONDS_PER_TARGET}s each without a finding (summary: $OUT/summary.txt)"
fi
