#!/usr/bin/env bash
# Configures and builds accelviz into build/ (Release). Extra arguments go to cmake's
# configure step, e.g. scripts/build.sh -DACCEL_BUILD_APP=OFF; --student DIR builds a
# student's structures in (docs/student.md; --no-student takes them out again).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${ACCEL_BUILD_DIR:-$root/build}"
jobs="$(nproc 2>/dev/null || echo 2)"
source "$root/scripts/student_args.sh"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "${student_cmake_args[@]}" "${remaining_args[@]}" >/dev/null
cmake --build "$build_dir" -j"$jobs"
