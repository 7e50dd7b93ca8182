#!/usr/bin/env bash
# GitHub Classroom's autograding step runs this (.github/workflows/classroom.yml) in the
# student's repository: it grades the .cpp files at the repository's root with the grader the
# workflow built from accelviz/, prints the judge's report into the run's log, and exits with
# the judge's code, which is the grade: 0 all correct (the test passes), anything else fails.
# The judge compiles only the top-level .cpp and .h files of the folder: accelviz/ is not
# the student's and is left out.
#
# Environment:
#   ACCELVIZ_GRADER       the accelviz-cli to run (default: accelviz/build/bin/accelviz-cli)
#   ACCELVIZ_SUBMISSION   the folder of the student's files (default: the current folder)
#   ACCELVIZ_EXTRA_ARGS   options appended to `accelviz-cli check` (split at spaces, no
#                         quoting): e.g. "--ray-scale 0.5 --timeout 120". The autograding
#                         action passes only PATH and HOME on: set it in the step's command,
#                         `ACCELVIZ_EXTRA_ARGS="--ray-scale 0.5" bash .github/accelviz-grade.sh`.
set -euo pipefail

CLI="${ACCELVIZ_GRADER:-accelviz/build/bin/accelviz-cli}"
SUBMISSION="${ACCELVIZ_SUBMISSION:-.}"
EXTRA_ARGS="${ACCELVIZ_EXTRA_ARGS-}"
read -r -a extra <<<"$EXTRA_ARGS"

# The judge's scratch folder (its compiled worker and the wrong rays' replay files).
# Searchable by others: as root without the sandbox, the judge hands the worker's folder to nobody.
work=$(mktemp -d "${TMPDIR:-/tmp}/accelviz-grade.XXXXXX")
trap 'rm -rf "$work"' EXIT
chmod 711 "$work"

rc=0
"$CLI" check --submission "$SUBMISSION" --out-dir "$work/check" "${extra[@]}" || rc=$?
if [ "$rc" -eq 3 ]; then
  # No sandbox here: GitHub's Ubuntu 24.04 runners restrict the unprivileged user namespaces
  # bubblewrap needs (the workflow tries to lift that; where it could not, this runs).
  # --no-sandbox is the choice made for this platform: the runner is a throw-away virtual
  # machine holding only the student's own repository, and the student's code keeps its
  # limits and seccomp filter.
  echo "accelviz-grade.sh: no sandbox on this runner; grading with --no-sandbox"
  rc=0
  "$CLI" check --submission "$SUBMISSION" --out-dir "$work/check" --no-sandbox "${extra[@]}" || rc=$?
fi
exit "$rc"
