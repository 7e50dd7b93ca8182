#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image from the uploaded
# zip (unpacked into /autograder/source): it installs what the CLI-only grader needs, builds
# it into /autograder/source/build, and grades the worked example once, so that a broken
# image fails here, in front of the lecturer, and not on the first student's submission.
# Pick the Ubuntu 24.04 base image: 22.04's CMake (3.22) is older than the 3.25 needed.
set -euo pipefail

ROOT="${ACCELVIZ_AUTOGRADER_ROOT:-/autograder}"
HERE="$ROOT/source"

export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
sed 's/#.*//' "$HERE/packages.txt" | xargs apt-get install -y -qq --no-install-recommends
rm -rf /var/lib/apt/lists/*

bash "$HERE/build_grader.sh" "$HERE/source" "$HERE/build"

# Without the sandbox the compiler and the student's code run as nobody, who must read the
# kit (the header under source/student, the archive under build): every file readable, every
# folder on the way searchable.
chmod -R a+rX "$HERE"
chmod a+x "$ROOT"

# The worked example must pass, graded as run_autograder grades a submission on this
# platform: without the sandbox, as nobody (--no-sandbox).
smoke=$(mktemp -d)
chmod 711 "$smoke"
"$HERE/build/bin/accelviz-cli" check --submission "$HERE/source/student/example" --no-sandbox \
  --ray-scale 0.05 --no-time --out-dir "$smoke/check"
rm -rf "$smoke"
echo "setup.sh: the grader is built and grades the worked example correctly"
