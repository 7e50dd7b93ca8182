#!/usr/bin/env bash
# Configures and builds accelviz into build/ (Release). Extra arguments go to cmake's
# configure step, e.g. scripts/build.sh -DACCEL_BUILD_APP=OFF; --student DIR builds a
# student's structures in (docs/student.md; --no-student takes them out again).
#   --viewer-only   only what scripts/run.sh needs: the viewer, the CLI and (with a student's
#                   structures) the worker; the tests are left to scripts/test.sh
#   --progress      one line of progress (percentage, time so far, the file compiling) and
#                   the time it took; errors and warnings in full
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${ACCEL_BUILD_DIR:-$root/build}"
jobs="$(nproc 2>/dev/null || echo 2)"
viewer_only=0
progress=0
args=()
for a in "$@"; do
  case "$a" in
    --viewer-only) viewer_only=1 ;;
    --progress) progress=1 ;;
    *) args+=("$a") ;;
  esac
done
source "$root/scripts/student_args.sh" "${args[@]+"${args[@]}"}"
started=$SECONDS
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "${student_cmake_args[@]+"${student_cmake_args[@]}"}" \
      "${remaining_args[@]+"${remaining_args[@]}"}" >/dev/null
targets=()
if [ "$viewer_only" = 1 ]; then
  # The student's loop needs the viewer, the CLI (check) and the worker that holds their
  # code; the ~70 test files, the fuzz targets and the kit's test structures are not built.
  targets=(--target accelviz-viewer-path)
fi

if [ "$progress" = 0 ]; then
  cmake --build "$build_dir" -j"$jobs" "${targets[@]+"${targets[@]}"}"
  exit 0
fi

# Progress: make's "[ 45%] Building CXX object core/.../kd_tree.cpp.o" lines become one line
# "[ 45%] 1:23 core/structures/kd_tree.cpp", rewritten in place on a terminal (one line per
# file in a log); anything else (a warning, an error) is printed as it comes.
log="$(mktemp "${TMPDIR:-/tmp}/accelviz-build.XXXXXX")"
trap 'rm -f "$log"' EXIT
tty=0
[ -t 1 ] && tty=1
echo "accelviz: building in $build_dir on $jobs cores (a first build of the viewer and the CLI takes about 5 minutes on 2 cores)"
status=0
{ cmake --build "$build_dir" -j"$jobs" "${targets[@]+"${targets[@]}"}" 2>&1 || echo "accelviz-build-status $?"; } |
  while IFS= read -r line; do
    printf '%s\n' "$line" >>"$log"
    if [[ "$line" =~ ^\[\ *([0-9]+)%\]\ (Building|Linking)\ [A-Z]+\ (object|executable|static\ library|shared\ library)\ (.*)$ ]]; then
      pct="${BASH_REMATCH[1]}"
      file="${BASH_REMATCH[4]}"
      file="${file/CMakeFiles\/*.dir\//}"
      file="${file%.o}"
      elapsed=$((SECONDS - started))
      text="$(printf '[%3s%%] %d:%02d %s' "$pct" $((elapsed / 60)) $((elapsed % 60)) "$file")"
      if [ "$tty" = 1 ]; then printf '\r\033[K%s' "${text:0:$((${COLUMNS:-100} - 1))}"; else printf '%s\n' "$text"; fi
    elif [[ "$line" =~ ^\[\ *[0-9]+%\]\ Built\ target ]] || [[ "$line" =~ ^accelviz-build-status ]] ||
         [[ "$line" =~ ^(g|)make ]]; then
      :
    else
      [ "$tty" = 1 ] && printf '\r\033[K'
      printf '%s\n' "$line"
    fi
  done
[ "$tty" = 1 ] && printf '\r\033[K'
if line="$(grep '^accelviz-build-status' "$log")"; then
  status="${line##* }"
  echo "accelviz: the build failed (exit $status) after $((SECONDS - started)) s; the full log was printed above" >&2
  exit "$status"
fi
elapsed=$((SECONDS - started))
echo "accelviz: built in $((elapsed / 60)) min $((elapsed % 60)) s"
