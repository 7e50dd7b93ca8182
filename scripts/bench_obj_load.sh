#!/usr/bin/env bash
# OBJ loading speed (#16): the largest OBJ of ../shared/scenes (or FILE) loaded by
# `accelviz-cli stats --structure brute` (its load_ms: read, validate, tinyobjloader's parse,
# fan triangulation, per-triangle boxes), best of REPEATS runs with the file in the page
# cache, and tinyobjloader's parse alone on the same file (scripts/tinyobj_parse_time.cpp,
# compiled here against the system's libtinyobjloader_double, as core/ links it), in MB/s
# (10^6 bytes) and Mtriangles/s; next to tinyobjloader's own published figures.
#   scripts/bench_obj_load.sh [FILE.obj] [--repeats N] [--out PREFIX]
# Writes PREFIX.md and PREFIX.json (default bench/obj_load). Takes under a minute.
# The CLI is taken from $ACCEL_BUILD_DIR/bin (default build/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ACCEL_BUILD_DIR:-$root/build}"
cli="$build/bin/accelviz-cli"
shared="${ACCEL_SHARED_DIR:-$root/../shared}"
repeats=5
out=bench/obj_load
file=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --repeats) repeats="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -*) echo "bench_obj_load.sh: unknown option '$1'" >&2; exit 2 ;;
    *) file="$1"; shift ;;
  esac
done
[[ -x "$cli" ]] || { echo "bench_obj_load.sh: $cli not found: build first (scripts/build.sh)" >&2; exit 1; }
if [[ -z "$file" ]]; then
  [[ -d "$shared/scenes" ]] || { echo "bench_obj_load.sh: $shared/scenes not found" >&2; exit 1; }
  file="$(ls -S "$shared"/scenes/*.obj | head -n 1)"
fi
[[ -f "$file" ]] || { echo "bench_obj_load.sh: $file not found" >&2; exit 1; }
cd "$root"
mkdir -p "$(dirname "$out")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

tool="$build/tinyobj_parse_time"
if [[ ! -x "$tool" || "$root/scripts/tinyobj_parse_time.cpp" -nt "$tool" ]]; then
  c++ -std=c++20 -O2 -Wall -Wextra -DTINYOBJLOADER_USE_DOUBLE "$root/scripts/tinyobj_parse_time.cpp" \
    -o "$tool" -ltinyobjloader_double
fi

cat "$file" > /dev/null  # into the page cache: the runs time parsing, not the disk
echo "== $file: accelviz load_obj x $repeats, tinyobjloader ParseFromString x $repeats" >&2
for r in $(seq 1 "$repeats"); do
  "$cli" stats --scene "$file" --structure brute --json > "$work/stats_$r.json"
done
"$tool" "$file" "$repeats" > "$work/tinyobj.txt"

python3 - "$work" "$file" "$repeats" "$out" <<'EOF'
import datetime, glob, json, os, subprocess, sys
work, path, repeats, out = sys.argv[1:5]
size = os.path.getsize(path)
runs = [json.load(open(p)) for p in sorted(glob.glob(f"{work}/stats_*.json"))]
tris = runs[0]["triangles"]
ours_ms = sorted(r["load_ms"] for r in runs)
read_ms, parse_ms, vertices = open(f"{work}/tinyobj.txt").read().split()
read_ms, parse_ms = float(read_ms), float(parse_ms)
machine = ""
for line in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines():
    if line.startswith("Model name:"):
        machine = line.split(":", 1)[1].strip()

def rates(ms, nbytes, ntris):
    return nbytes / 1e6 / (ms / 1e3), ntris / 1e6 / (ms / 1e3)

# tinyobjloader's README (tinyobjloader/tinyobjloader, README.md, section "Optimized loader"):
# "Time are measured on MacBook 12(Early 2016, Core m5 1.2GHz). Rungholt scene(6M triangles):
# baseline(v1.0.x): 6800 msecs; optimised: 1500 msecs". It gives no file size: 270 MB is the
# Rungholt OBJ's size in aras-p/obj_parse_tester, readme.md ("Models used").
rungholt_bytes, rungholt_tris = 270e6, 6e6
published = [("tinyobjloader v1.0.x (baseline), Rungholt, MacBook 12 Early 2016, Core m5 1.2 GHz", 6800.0),
             ("tinyobjloader experimental optimised (multi-threaded), same", 1500.0)]
rows = []
best = ours_ms[0]
rows.append({"what": f"accelviz load_obj (read, validate, tinyobjloader parse, triangulate, per-triangle data), "
                     f"best of {repeats}", "file": os.path.basename(path), "ms": best,
             "median_ms": ours_ms[len(ours_ms) // 2], "machine": machine})
rows.append({"what": "tinyobjloader ParseFromString alone, same file and machine", "file": os.path.basename(path),
             "ms": parse_ms, "machine": machine})
for what, ms in published:
    rows.append({"what": what, "file": "rungholt.obj (270 MB, 6M triangles)", "ms": ms,
                 "machine": "MacBook 12 (Early 2016, Core m5 1.2 GHz)", "published": True})
for r in rows:
    nbytes, ntris = (rungholt_bytes, rungholt_tris) if r.get("published") else (size, tris)
    r["mb_per_s"], r["mtris_per_s"] = rates(r["ms"], nbytes, ntris)

md = [f"# OBJ loading speed: {os.path.basename(path)}\n",
      f"`{os.path.basename(path)}`: {size / 1e6:.2f} MB, {tris:,} triangles, {int(vertices):,} vertices; "
      f"{machine}, {os.cpu_count()} logical CPUs, {datetime.date.today().isoformat()}. File in the page cache; "
      f"accelviz's time is `accelviz-cli stats --structure brute`'s `load_ms` (best of {repeats}; median "
      f"{ours_ms[len(ours_ms) // 2]:.0f} ms), tinyobjloader's is `scripts/tinyobj_parse_time.cpp` (best of {repeats}; "
      f"reading the file into memory took {read_ms:.1f} ms more).\n",
      "| loader | file | machine | ms | MB/s | Mtriangles/s |", "|---|---|---|---:|---:|---:|"]
for r in rows:
    md.append(f"| {r['what']} | {r['file']} | {r['machine']} | {r['ms']:.0f} | {r['mb_per_s']:.1f} | {r['mtris_per_s']:.2f} |")
md.append("")
md.append("The published rows are tinyobjloader's own figures: README.md of tinyobjloader/tinyobjloader, section "
          "\"Optimized loader\" (\"Time are measured on MacBook 12(Early 2016, Core m5 1.2GHz)\"; Rungholt, 6M "
          "triangles: baseline v1.0.x 6800 msecs, optimised 1500 msecs). The README gives no file size; 270 MB is "
          "the Rungholt OBJ's size as aras-p/obj_parse_tester's readme.md lists it. Other machine, other file: compare "
          "orders of magnitude, not digits. Made by `scripts/bench_obj_load.sh`.")
text = "\n".join(md) + "\n"
sys.stdout.write(text)
open(out + ".md", "w").write(text)
open(out + ".json", "w").write(json.dumps({"file": os.path.relpath(path), "bytes": size, "triangles": tris, "vertices": int(vertices),
                                           "accelviz_load_ms": ours_ms, "tinyobj_read_ms": read_ms,
                                           "tinyobj_parse_ms": parse_ms, "rows": rows}, indent=1) + "\n")
print(f"wrote {out}.md and {out}.json", file=sys.stderr)
EOF
