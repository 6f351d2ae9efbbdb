#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, build-fuzz/) and fuzzes every loader of
# untrusted input for SECONDS each (default 35: about 4 minutes for the 6 targets, the CI run).
# The mutation seed is fixed (FOREST_FUZZ_SEED, default 1), so a CI run repeats the same
# inputs up to its time limit: a failure reproduces, and new findings come from longer runs.
#   scripts/fuzz.sh               # CI-sized run
#   scripts/fuzz.sh 3600 glb      # one hour on the .glb loader only
# Starts from the committed seed corpus (tests/fuzz/corpus/<target>/); new interesting inputs
# go to build-fuzz/corpus/<target>/. A crash, sanitizer report, leak, hang (> 10 s) or
# out-of-memory (> 2 GB) stops the run with exit code 1 and leaves the input in
# build-fuzz/artifacts/; copy it to tests/fuzz/regressions/<target>/ with the fix so that
# unit.FuzzCorpus.* replays it forever.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-35}
shift || true
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(scene species glb strokes mask views)

if [[ ! -f build-fuzz/build.ninja ]]; then
  cmake --preset fuzz >/dev/null
fi
cmake --build --preset fuzz

mkdir -p build-fuzz/artifacts
status=0
total=0
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t"
  echo "fuzz.sh: $t for ${seconds} s"
  if ! ASAN_OPTIONS="halt_on_error=1:abort_on_error=1" \
       UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" \
       LSAN_OPTIONS="suppressions=tests/fuzz/lsan.supp:print_suppressions=0" \
       "build-fuzz/fuzz_$t" -seed="${FOREST_FUZZ_SEED:-1}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
         -print_final_stats=1 -artifact_prefix="build-fuzz/artifacts/$t-" \
         "build-fuzz/corpus/$t" "tests/fuzz/corpus/$t" >"build-fuzz/fuzz-$t.log" 2>&1; then
    echo "fuzz.sh: $t FAILED; last lines of build-fuzz/fuzz-$t.log:" >&2
    tail -n 40 "build-fuzz/fuzz-$t.log" >&2
    status=1
  else
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "build-fuzz/fuzz-$t.log" | tail -n 1)
    cov=$(grep -oE "cov: [0-9]+ ft: [0-9]+" "build-fuzz/fuzz-$t.log" | tail -n 1)
    echo "fuzz.sh: $t: ${runs:-0} executions in ${seconds} s, ${cov:-no coverage line}, 0 findings"
    total=$(( total + ${runs:-0} ))
  fi
done
echo "fuzz.sh: ${#targets[@]} targets, $total executions in all, $([[ $status -eq 0 ]] && echo 0 findings || echo 'a FINDING (above)')"
exit $status
