#!/usr/bin/env bash
# callgrind_query.sh [--rays random:30000:1] [--param key=value]... MESH
# Instructions, simulated L1 data misses and mispredicted branches per ray of the default
# BVH's fast single-ray query and of Embree's rtcIntersect1, counted by callgrind in one
# `accelviz-cli bench` process (the query functions only: --toggle-collect), on the same
# rays. valgrind hides AVX-512, so accelviz runs its AVX2 kernel here. Takes ~3 minutes
# for crytek_sponza (the bench's build and reference run under valgrind too). The figures
# of bench/README.md ("What limits the single-ray speed") are made with it.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cli="${ACCEL_CLI:-$here/../build/bin/accelviz-cli}"
rays="random:30000:1"
params=()
while [[ $# -gt 1 ]]; do
  case "$1" in
    --rays) rays="$2"; shift 2 ;;
    --param) params+=(--param "$2"); shift 2 ;;
    *) echo "callgrind_query.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
[[ $# -eq 1 ]] || { echo "usage: callgrind_query.sh [--rays SPEC] [--param key=value]... MESH" >&2; exit 2; }
mesh="$1"
command -v valgrind >/dev/null || { echo "callgrind_query.sh: valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
[[ -x "$cli" ]] || { echo "callgrind_query.sh: $cli not built (scripts/build.sh)" >&2; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
valgrind --tool=callgrind --branch-sim=yes --cache-sim=yes --callgrind-out-file="$out/cg.out" \
  --toggle-collect='accel::wide8_fast_avx2*' --toggle-collect='rtcIntersect1*' \
  "$cli" bench --scene "$mesh" --structures bvh "${params[@]}" --rays "$rays" --threads 1 --min-time 0.001 \
  --no-tinybvh >"$out/log" 2>&1 || { tail -5 "$out/log" >&2; exit 1; }
callgrind_annotate --inclusive=yes "$out/cg.out" >"$out/annotated" 2>/dev/null
python3 - "$out/cg.out" "$out/annotated" <<'EOF'
import re, sys
# Calls per function from the output file; inclusive costs from callgrind_annotate.
names, calls, callee = {}, {}, None
for line in open(sys.argv[1]):
    m = re.match(r'(c?fn)=\((\d+)\)(?: (.*))?$', line.rstrip('\n'))
    if m:
        kind, i, name = m.groups()
        if name:
            names[i] = name
        if kind == 'cfn':
            callee = names[i]
        continue
    if line.startswith('calls=') and callee:
        calls[callee] = calls.get(callee, 0) + int(line.split()[0][6:])
queries = (('accelviz bvh', 'wide8_fast_avx2('), ('embree', 'rtcIntersect1'))
events, inclusive = [], {}
for line in open(sys.argv[2]):
    if line.startswith('Events shown:'):
        events = line.split()[2:]
        continue
    for label, pattern in queries:
        if events and pattern in line and label not in inclusive:
            # Every event is a number (or '.'), some followed by a "(xx%)" column.
            nums = [f for f in line.split() if re.fullmatch(r'[\d,]+|\.', f)][:len(events)]
            inclusive[label] = {e: (0 if v == '.' else int(v.replace(',', ''))) for e, v in zip(events, nums)}
print('query             calls  instr/ray  L1d misses/ray  mispredicts/ray')
for label, pattern in queries:
    n = sum(c for f, c in calls.items() if pattern.rstrip('(') in f)
    c = inclusive.get(label)
    if not n or not c:
        continue
    d1 = c.get('D1mr', 0) + c.get('D1mw', 0)
    print(f"{label:14s} {n:8d} {c['Ir'] / n:10.0f} {d1 / n:15.1f} {c.get('Bcm', 0) / n:16.1f}")
EOF
