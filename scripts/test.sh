#!/usr/bin/env bash
# Installs missing packages, builds, and runs every test (the viewer's under xvfb-run).
# Then builds the web page (scripts/build_web.sh) and drives it in headless Chromium
# (tests/web/test_page.py) when emscripten is installed. Then repeats the core and CLI tests
# in a second build instrumented with AddressSanitizer and UBSan (build-asan/, clang; built
# while the browser test runs), with smaller ray counts (ACCEL_TEST_RAY_SCALE) to keep CI
# short, and runs each libFuzzer target of that build for ACCEL_FUZZ_SECONDS (default 8).
#   ACCEL_SKIP_SANITIZERS=1 scripts/test.sh   # only the Release run (and the web page)
#   ACCEL_SKIP_WEB=1 scripts/test.sh          # without the web page
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"
"$root/scripts/deps.sh"
# Each phase's header says when it starts, so a CI log shows where the time goes.
phase() { echo "== $1 (at ${SECONDS} s)"; }

full_build_args=()
if [ ! -f "$root/build/CMakeCache.txt" ]; then
  # A fresh clone (CI): first time a student's path, timed -- the viewer, the CLI and the
  # worker built with the kd-tree skeleton, then its first picture -- so every CI log
  # carries the figure README.md quotes. The full build below reuses all of it.
  phase "A student's first picture (scripts/run.sh --student student/skeletons/kdtree, fresh clone)"
  first_start=$SECONDS
  "$root/scripts/build.sh" --viewer-only --progress --student "$root/student/skeletons/kdtree"
  built_at=$SECONDS
  picture="$root/build/first_picture.png"
  printf 'structure my_kdtree\nray-at-pixel 640 360\nscreenshot %s\n' "$picture" >"$root/build/first_picture.txt"
  xvfb-run -a -s "-screen 0 1280x720x24" "$root/build/bin/accelviz" --script "$root/build/first_picture.txt" >/dev/null
  [ -s "$picture" ] || { echo "the first picture was not written" >&2; exit 1; }
  echo "first picture of a skeleton: $((SECONDS - first_start)) s after the clone (build $((built_at - first_start)) s, the viewer $((SECONDS - built_at)) s)"
  full_build_args=(--no-student)  # the skeleton out again: it fails check by design
fi

phase "Release build and tests"
"$root/scripts/build.sh" "${full_build_args[@]+"${full_build_args[@]}"}"
phase "Release tests"
(cd "$root/build" && ctest --output-on-failure -j"$jobs")

sanitizers=0
[ "${ACCEL_SKIP_SANITIZERS:-0}" != 1 ] && sanitizers=1
# -g1: line tables for the sanitizers' stack traces, without the full debug information.
# clang: libFuzzer comes with it, so one build holds the tests, the CLI and tests/fuzz.
asan_build() {
  cmake -S "$root" -B "$root/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DACCEL_SANITIZE=ON -DACCEL_FUZZ=ON \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
        -DACCEL_BUILD_APP=OFF >/dev/null
  cmake --build "$root/build-asan" -j"$jobs"
}
asan_pid=""

if [ "${ACCEL_SKIP_WEB:-0}" != 1 ] && command -v emcc >/dev/null; then
  phase "Web page (emscripten)"
  # With the kit's worked example built in: the browser test's student check runs it.
  "$root/scripts/build_web.sh" --student "$root/student/example"
  if [ "$sanitizers" = 1 ]; then
    # The browser test keeps about one core busy (it mostly waits for the page): the ASan
    # build runs beside it, its output kept for after (build-asan/build.log).
    phase "Web page's browser test (headless Chromium), beside the AddressSanitizer + UBSan build"
    mkdir -p "$root/build-asan"
    asan_build >"$root/build-asan/build.log" 2>&1 &
    asan_pid=$!
  else
    phase "Web page's browser test (headless Chromium)"
  fi
  # Exit 77: no Chromium, so nothing was checked (skipped, as ctest counts it).
  status=0
  # The folder to upload (site/), as a course website serves it.
  python3 "$root/tests/web/test_page.py" --web-dir "$root/build-web/site" --cli "$root/build/bin/accelviz-cli" \
    --shared "$root/../shared" || status=$?
  if [ "$status" -ne 0 ] && [ "$status" -ne 77 ]; then
    [ -z "$asan_pid" ] || wait "$asan_pid" || true  # no build left running behind the failure
    exit "$status"
  fi
fi

if [ "$sanitizers" = 1 ]; then
  if [ -n "$asan_pid" ]; then
    phase "AddressSanitizer + UBSan build (clang, with the libFuzzer targets): its end"
    build_status=0
    wait "$asan_pid" || build_status=$?
    cat "$root/build-asan/build.log"
    [ "$build_status" -eq 0 ] || exit "$build_status"
  else
    phase "AddressSanitizer + UBSan build (clang, with the libFuzzer targets)"
    asan_build
  fi
  phase "AddressSanitizer + UBSan tests"
  # The core suite runs in eight shards, without three hard-suite configurations and the
  # Moller-Trumbore failure report (tests/CMakeLists.txt says why). Rays at 3% of the Release
  # pass's: every code path is still met many times, and this pass looks for memory errors,
  # not wrong answers.
  # ACCEL_FUZZ_SECONDS: the CLI's end-to-end fuzz (cli.fuzz_e2e) runs as long as each
  # libFuzzer target below (8 s by default; 20 s in the Release pass).
  (cd "$root/build-asan" && ACCEL_TEST_RAY_SCALE=0.03 ACCEL_FUZZ_SECONDS="${ACCEL_FUZZ_SECONDS:-8}" \
     ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     ctest --output-on-failure -j"$jobs")
  phase "Fuzzing (each libFuzzer target for a bounded time, scripts/fuzz.sh)"
  # New findings are printed with their input files (fix them, then add each input to
  # tests/fuzz/regressions/); the replay of the regressions above is what gates.
  ACCEL_FUZZ_BUILD="$root/build-asan" ACCEL_FUZZ_REPORT_ONLY=1 "$root/scripts/fuzz.sh" "${ACCEL_FUZZ_SECONDS:-8}"
fi
phase "done"
