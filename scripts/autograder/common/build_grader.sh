#!/usr/bin/env bash
# Builds the CLI-only grader: accelviz-cli and the worker's runtime archive the judge links
# each submission against (no viewer, no tests, no Embree; docs/student.md).
#   build_grader.sh SOURCE_DIR BUILD_DIR
# The grader remembers where it was built (the kit's header under SOURCE_DIR/student, the
# archive under BUILD_DIR): build it where it will run, and leave both folders in place.
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: build_grader.sh SOURCE_DIR BUILD_DIR" >&2
  exit 2
fi
src=$1
build=$2
# The project needs CMake 3.25: say which image to pick rather than fail in the configure step.
version=$(cmake --version | sed -n 's/^cmake version \([0-9][0-9]*\.[0-9][0-9]*\).*/\1/p')
if [ "$(printf '%s\n' 3.25 "$version" | sort -V | head -n 1)" != 3.25 ]; then
  echo "build_grader.sh: CMake $version is older than 3.25: use an Ubuntu 24.04 (or Debian 12) image" >&2
  exit 1
fi
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DACCEL_BUILD_APP=OFF -DBUILD_TESTING=OFF \
  -DACCEL_WITH_EMBREE=OFF
cmake --build "$build" --target accelviz-cli accelviz_kit_worker -j"$(nproc)"
