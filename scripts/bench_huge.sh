#!/usr/bin/env bash
# The huge-scene table (#16): every structure the CLI knows, built with its defaults over
# procedural:huge (10,000,000 triangles, generated, nothing stored) and queried with 1M
# random rays, each structure in its own `accelviz-cli stats` process under /usr/bin/time -v,
# so every row has its own peak resident memory (scene + rays + structure + hits). Per row:
# scene load (generation) s, build s, trace s with the counters off (the fast path) and on,
# Mrays/s, the structure's own MB and the process's peak RSS. A build over the memory budget
# (default half of physical memory, or --memory-limit) stops with the CLI's one-line budget
# error, which becomes the row's note.
#   scripts/bench_huge.sh [SCENE] [RAYS] [--out PREFIX] [--structures a,b] [--threads N]
#                         [--memory-limit SIZE] [--time-limit S]
#     SCENE  default procedural:huge; RAYS a count (random:N:1) or any --rays spec, default 1000000
#     --out  default bench/huge: writes PREFIX.md and PREFIX.json (give another prefix when
#            smoke-testing on a small scene, e.g. scripts/bench_huge.sh procedural:soup 10000 --out /tmp/soup)
# brute tests every triangle for every ray: when triangles x rays exceeds 5e8 it traces only
# the first 5e8 / triangles rays of the same set, and its trace time is scaled up to all the
# rays (marked "extrapolated"). Takes about 3 minutes on a 2-core machine for procedural:huge.
# The CLI is taken from $ACCEL_BUILD_DIR/bin (default build/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cli="${ACCEL_BUILD_DIR:-$root/build}/bin/accelviz-cli"
scene=procedural:huge
rays=1000000
out=bench/huge
structures=""
extra=()
positional=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --structures) structures="$2"; shift 2 ;;
    --threads|--memory-limit|--time-limit) extra+=("$1" "$2"); shift 2 ;;
    -*) echo "bench_huge.sh: unknown option '$1'" >&2; exit 2 ;;
    *)
      case "$positional" in
        0) scene="$1" ;;
        1) rays="$1" ;;
        *) echo "bench_huge.sh: unexpected argument '$1'" >&2; exit 2 ;;
      esac
      positional=$((positional + 1)); shift ;;
  esac
done
[[ -x "$cli" ]] || { echo "bench_huge.sh: $cli not found: build first (scripts/build.sh)" >&2; exit 1; }
[[ -x /usr/bin/time ]] || { echo "bench_huge.sh: /usr/bin/time not found (Debian package 'time', see scripts/deps.sh)" >&2; exit 1; }
[[ "$rays" =~ ^[0-9]+$ ]] && rays="random:$rays:1"
# Every structure the CLI knows, in its own order (`params` prints one unindented line each).
[[ -n "$structures" ]] || structures="$("$cli" params | sed -n 's/^\([a-z0-9_]*\):.*/\1/p' | paste -sd, -)"
cd "$root"
mkdir -p "$(dirname "$out")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

start=$(date +%s)
load_start="$(cut -d' ' -f1-3 /proc/loadavg)"  # other work on the machine during the run, for the table's header
# The scene's triangle count, for brute's ray budget (a brute "build" costs nothing).
"$cli" stats --scene "$scene" --structure brute --json > "$work/scene.json"
triangles=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["triangles"])' "$work/scene.json")
echo "== $scene ($triangles triangles), rays $rays, structures $structures" >&2
IFS=, read -r -a names <<< "$structures"
for s in "${names[@]}"; do
  spec="$rays"
  if [[ "$s" == brute ]]; then
    spec=$(python3 - "$rays" "$triangles" <<'EOF'
import sys
rays, tris = sys.argv[1], int(sys.argv[2])
parts = rays.split(":")
if parts[0] == "random" and len(parts) == 3 and int(parts[1]) * tris > 5e8:
    parts[1] = str(max(1, int(5e8 // tris)))
print(":".join(parts))
EOF
)
  fi
  echo "-- $s ($spec)" >&2
  set +e
  /usr/bin/time -v -o "$work/$s.time" "$cli" stats --scene "$scene" --structure "$s" --rays "$spec" --json \
    "${extra[@]}" > "$work/$s.json" 2> "$work/$s.err"
  echo $? > "$work/$s.rc"
  set -e
  [[ "$(cat "$work/$s.rc")" == 0 ]] || echo "   failed: $(tail -n 1 "$work/$s.err")" >&2
done
end=$(date +%s)
load_end="$(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$work" "$scene" "$rays" "$structures" "$out" "$((end - start))" "$triangles" "$load_start" "$load_end" <<'EOF'
import json, os, re, subprocess, sys, datetime
work, scene, rays, structures, out, wall, tri, load_start, load_end = sys.argv[1:10]
machine = ""
try:
    for line in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines():
        if line.startswith("Model name:"):
            machine = line.split(":", 1)[1].strip()
except OSError:
    pass
cores = os.cpu_count()
mem_gib = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
n_total = int(rays.split(":")[1]) if rays.startswith("random:") else None
rows = []
for s in structures.split(","):
    rc = int(open(f"{work}/{s}.rc").read())
    timing = open(f"{work}/{s}.time").read()
    rss_kb = re.search(r"Maximum resident set size \(kbytes\): (\d+)", timing)
    elapsed = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", timing)
    wall_s = None
    if elapsed:
        wall_s = 0.0
        for part in elapsed.group(1).split(":"):
            wall_s = wall_s * 60 + float(part)
    row = {"structure": s, "ok": rc == 0, "exit_code": rc,
           "peak_rss_bytes": int(rss_kb.group(1)) * 1024 if rss_kb else None, "process_wall_s": wall_s}
    if rc == 0:
        j = json.load(open(f"{work}/{s}.json"))
        n = j["n_rays"]
        row.update({"triangles": j["triangles"], "params": j["params"] or "default", "extra": j["extra"],
                    "load_s": j["load_ms"] / 1e3, "build_s": j["build_ms"] / 1e3,
                    "memory_bytes": j["memory_bytes"], "nodes": j["nodes"], "rays": j["rays"], "n_rays": n,
                    "hits": j["hits"], "trace_s": j["trace_fast_ms"] / 1e3, "trace_counters_s": j["trace_ms"] / 1e3,
                    "mrays_per_s": n / (j["trace_fast_ms"] / 1e3) / 1e6 if j["trace_fast_ms"] > 0 else None,
                    "nodes_visited_per_ray": j["nodes_visited_per_ray"], "tris_tested_per_ray": j["tris_tested_per_ray"],
                    "extrapolated": n_total is not None and n < n_total})
        row["trace_all_rays_s"] = row["trace_s"] * (n_total / n) if row["extrapolated"] else row["trace_s"]
    else:
        err = [l for l in open(f"{work}/{s}.err").read().splitlines() if l.strip()]
        signal = re.search(r"Command terminated by signal (\d+)", timing)
        row["error"] = (f"killed by signal {signal.group(1)}" if signal else
                        (err[-1].removeprefix("accelviz-cli: ") if err else f"exit {rc}"))
    rows.append(row)

n_label = f"{n_total:,}" if n_total else rays
def f(v, fmt):
    return "-" if v is None else fmt.format(v)
md = []
md.append(f"# {scene}: every structure with its defaults, {n_label} rays\n")
md.append(f"Scene `{scene}` ({int(tri):,} triangles), rays `{rays}`; one `accelviz-cli stats` process per "
          f"structure under `/usr/bin/time -v`. Machine: {machine or 'unknown'}, {cores} logical CPUs, "
          f"{mem_gib:.1f} GiB; {datetime.date.today().isoformat()}; whole run {int(wall)} s; load average (1, 5, 15 min) "
          f"{load_start} at the start, {load_end} at the end.\n")
md.append("| structure | load s | build s | trace s | Mrays/s | trace s, counters on | nodes / tris per ray | "
          "structure MB | peak RSS GiB | note |")
md.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
for r in rows:
    if r["ok"]:
        note = f"extrapolated from {r['n_rays']:,} rays" if r["extrapolated"] else ""
        md.append(f"| {r['structure']} | {r['load_s']:.2f} | {r['build_s']:.2f} | {r['trace_all_rays_s']:.2f} | "
                  f"{r['mrays_per_s']:.3g} | {r['trace_counters_s'] * (n_total / r['n_rays'] if r['extrapolated'] else 1):.2f} | "
                  f"{r['nodes_visited_per_ray']:.3g} / {r['tris_tested_per_ray']:.3g} | "
                  f"{r['memory_bytes'] / 2**20:.0f} | {f(r['peak_rss_bytes'] and r['peak_rss_bytes'] / 2**30, '{:.2f}')} | {note} |")
    else:
        md.append(f"| {r['structure']} | - | - | - | - | - | - | - | "
                  f"{f(r['peak_rss_bytes'] and r['peak_rss_bytes'] / 2**30, '{:.2f}')} | {r['error'].replace('|', '/')} |")
md.append("")
md.append("load s: generating or reading the scene (and its per-triangle boxes); trace s: all the rays on every "
          "core with the counters off, as `trace` and `bench` run them; peak RSS: the whole process (scene, rays, "
          "structure, hits). Made by `scripts/bench_huge.sh`.")
text = "\n".join(md) + "\n"
sys.stdout.write(text)
open(out + ".md", "w").write(text)
meta = {"scene": scene, "triangles": int(tri), "rays": rays, "machine": machine, "logical_cpus": cores, "memory_gib": round(mem_gib, 1),
        "date": datetime.date.today().isoformat(), "wall_s": int(wall), "loadavg_start": load_start,
        "loadavg_end": load_end, "rows": rows}
open(out + ".json", "w").write(json.dumps(meta, indent=1) + "\n")
print(f"wrote {out}.md and {out}.json", file=sys.stderr)
EOF
