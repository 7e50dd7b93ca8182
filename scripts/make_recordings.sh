#!/usr/bin/env bash
# Regenerates the recordings of docs/viewer.md (bench/figures/*.gif, *.mp4) from the viewer scripts in
# scripts/recordings/NAME.txt: `record PATH` ... `record stop` around the steps to show.
#   scripts/make_recordings.sh                      all of them
#   scripts/make_recordings.sh traversal_kdtree     only scripts/recordings/traversal_kdtree.txt
exec "$(dirname "${BASH_SOURCE[0]}")/make_figures.sh" --recordings "$@"
