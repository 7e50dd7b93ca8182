#!/usr/bin/env bash
# Runs each libFuzzer target (tests/fuzz) for SECONDS (default 45), two at a time on two
# cores, from its seed corpus and regressions. New inputs the fuzzer keeps go to a working
# corpus in the build folder (it grows across local runs; the checked-in seeds stay as they
# are). A crash, a hang (-timeout) or an out-of-memory (-rss_limit_mb) stops that target,
# leaves its input in BUILD/fuzz-artifacts/ and makes the script fail, naming the file:
# fix the bug, then add the file to tests/fuzz/regressions/NAME/ (replayed by ctest).
#   scripts/fuzz.sh [SECONDS] [NAME ...]     e.g. scripts/fuzz.sh 600 obj params
# The fuzz build is the sanitizer build of scripts/test.sh (build-asan/, clang, ACCEL_FUZZ=ON);
# ACCEL_FUZZ_BUILD names another.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ACCEL_FUZZ_BUILD:-$root/build-asan}"
seconds="${1:-45}"
shift || true
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(obj mesh rays params script bench_json)
case "$seconds" in ''|*[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2;; esac
jobs="$(nproc 2>/dev/null || echo 2)"

for name in "${names[@]}"; do
  [ -x "$build/bin/fuzz_$name" ] || {
    echo "fuzz.sh: $build/bin/fuzz_$name not found (build with -DACCEL_FUZZ=ON, see scripts/test.sh)" >&2; exit 2; }
done
mkdir -p "$build/fuzz-artifacts" "$build/fuzz-logs"

run_one() {
  local name="$1" work="$build/fuzz-corpus/$1"
  mkdir -p "$work"
  # The working corpus comes first: libFuzzer adds what it finds to the first folder.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS="suppressions=$root/tests/fuzz/lsan.supp" \
    "$build/bin/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$name-" \
      "$work" "$root/tests/fuzz/corpus/$name" "$root/tests/fuzz/regressions/$name" \
      >"$build/fuzz-logs/$name.log" 2>&1
}

failed=()
pids=() ; pid_names=()
for name in "${names[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  run_one "$name" & pids+=($!); pid_names+=("$name")
done
for i in "${!pids[@]}"; do
  name="${pid_names[$i]}"
  log="$build/fuzz-logs/$name.log"
  if wait "${pids[$i]}"; then
    runs="$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -oE '[0-9]+$' || echo '?')"
    cov="$(grep -oE 'cov: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+' || echo '?')"
    echo "fuzz_$name: ${seconds} s, $runs inputs, coverage $cov edges, no failure"
  else
    artifact="$(grep -oE "Test unit written to [^ ]+" "$log" | tail -1 | sed 's/Test unit written to //')"
    echo "fuzz_$name: FAILED ($(grep -m1 -oE 'ERROR: [A-Za-z]+: [^ ]+( [^ ]+)?|ERROR: libFuzzer: [a-z-]+' "$log" || echo 'see log')); input: ${artifact:-none}, log: $log" >&2
    failed+=("$name")
  fi
done
[ ${#failed[@]} -eq 0 ] && exit 0
echo "fuzz.sh: ${#failed[@]} target(s) failed: ${failed[*]}" >&2
# ACCEL_FUZZ_REPORT_ONLY=1 (scripts/test.sh): a new finding is reported, not a failed run.
# What gates a change is the replay of the seeds and regressions (ctest fuzz.replay.*): a
# fuzzer's random walk finds something new on some runs and not on others.
[ "${ACCEL_FUZZ_REPORT_ONLY:-0}" = 1 ] && { echo "fuzz.sh: reported only (ACCEL_FUZZ_REPORT_ONLY=1)" >&2; exit 0; }
exit 1
