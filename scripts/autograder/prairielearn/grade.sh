#!/usr/bin/env bash
# PrairieLearn's external grader runs this, the image's /accelviz/grade.sh, in a fresh
# container for every submission (prairielearn.readthedocs.io/en/latest/externalGrading/):
# it grades the student's files in /grade/student with the grader built into the image and
# writes /grade/results/results.json.
#
# The results file is written only after the check has ended, in one rename, from what the
# judge printed on its standard output: nothing the student's code did while it ran can end
# up there. When the judge printed no results (it crashed, it is missing) the file still
# comes, marked not gradable (so the student loses no attempt), with score 0 and a message
# that says the grader failed. A compile error is the student's: gradable, score 0.
#
# Environment (the question's info.json may set variables: externalGradingOptions.environment):
#   ACCELVIZ_GRADE_ROOT   the folder that stands for /grade
#   ACCELVIZ_GRADER       the accelviz-cli to run (default: the one built into the image)
#   ACCELVIZ_EXTRA_ARGS   options appended to `accelviz-cli check` (split at spaces, no
#                         quoting). Unset, "--timeout 240" (seconds per structure) keeps a
#                         submission's endless loop inside PrairieLearn's 600 s; when you set
#                         it, include a --timeout of your own.
set -euo pipefail

ROOT="${ACCELVIZ_GRADE_ROOT:-/grade}"
CLI="${ACCELVIZ_GRADER:-/accelviz/build/bin/accelviz-cli}"
EXTRA_ARGS="${ACCELVIZ_EXTRA_ARGS---timeout 240}"
read -r -a extra <<<"$EXTRA_ARGS"
# Relative paths name files from the folder this was started in (the judge runs from its
# scratch folder, below).
if [[ $ROOT != /* ]]; then ROOT="$PWD/$ROOT"; fi
if [[ $CLI == */* && $CLI != /* ]]; then CLI="$PWD/$CLI"; fi
SUBMISSION="$ROOT/student"
RESULTS="$ROOT/results"

# The results folder belongs to the grader (PrairieLearn does not make it): created now,
# writable by root alone (the student's code runs as nobody when the sandbox is unavailable).
mkdir -p "$RESULTS"
chmod go-w "$RESULTS"

# The judge's scratch folder: its compiled worker and replay files, and what it prints.
# Searchable by others (nobody must reach the worker's folder, which the judge hands to it),
# not listable, not writable.
work=$(mktemp -d "${TMPDIR:-/tmp}/accelviz-grade.XXXXXX")
trap 'rm -rf "$work"' EXIT
chmod 711 "$work"
cd "$work"

# Runs the judge with the given extra options: its results to $work/stdout, its messages to
# $work/stderr, its exit code to $rc (0 all correct, 1 not, 2 bad use, 3 no sandbox here).
grade() {
  rc=0
  "$CLI" check --submission "$SUBMISSION" --format prairielearn --out-dir "$work/check" "$@" "${extra[@]}" \
    >"$work/stdout" 2>"$work/stderr" || rc=$?
  cat "$work/stderr"
}

grade
if [ "$rc" -eq 3 ]; then
  # No sandbox here: Docker's default seccomp profile blocks the user namespaces bubblewrap
  # needs. --no-sandbox is the choice made for this platform: the container already isolates
  # the submission (one per container, no network, thrown away after), the student's code
  # keeps its limits and seccomp filter, and it runs as the user nobody, which cannot write
  # the results folder.
  echo "grade.sh: no sandbox in this container; grading with --no-sandbox (code runs as nobody)"
  grade --no-sandbox
fi

# The judge's printout is the result when it ended normally (0 or 1) and printed one JSON
# object with a score: the grader never prints a partial object and exits 0 or 1.
printed=$(tr -d ' \t\r\n' <"$work/stdout")
tmp=$(mktemp "$RESULTS/.results.json.XXXXXX")
if [ "$rc" -le 1 ] && [[ $printed == \{*\} ]] && grep -q '"score"' "$work/stdout"; then
  cp "$work/stdout" "$tmp"
else
  # A JSON string of the end of the judge's messages: printable ASCII, tabs and newlines.
  said=$(tail -c 3000 "$work/stderr" | tr -cd '\11\12\40-\176')
  said=${said//\\/\\\\}
  said=${said//\"/\\\"}
  said=${said//$'\t'/\\t}
  said=${said//$'\n'/\\n}
  printf '{"gradable": false, "score": 0, "message": "The grader failed (exit %s) and graded nothing: please tell your instructor.", "output": "%s"}\n' \
    "$rc" "$said" >"$tmp"
  echo "grade.sh: the grader failed (exit $rc): results.json says so, not gradable"
fi
chmod 644 "$tmp"
mv -f "$tmp" "$RESULTS/results.json"
