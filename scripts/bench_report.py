#!/usr/bin/env python3
"""Summary tables of `accelviz-cli bench` JSON files (as scripts/bench_shared.sh writes them):
throughput per mesh and structure against Embree and against the fastest peer (Embree or
tinybvh), build time per mesh and structure against
Embree's medium build, and errors per structure and kernel.

    scripts/bench_report.py A.json [B.json ...] [--out-json ALL.json] > report.md
    scripts/bench_report.py --builds DEFAULT.json SWEEP.json [COLD.json] > builds_report.md

--builds (scripts/bench_builds.sh): the build table of DEFAULT.json's rows, then the bvh's
SAH cost and build time by default (binned SAH) and with SWEEP.json's builder=sah rows, then
COLD.json's cold builds (one fresh `stats` process each) against the same build warm and
against Embree medium, both from DEFAULT.json.

Rows of all files are merged; a peer row (Embree or tinybvh) is kept once per (scene, rays,
structure): later files timed the peers again only to give their own rows a ratio from the
same run. The merged
rows go to --out-json (the viewer's chart reads them)."""
import argparse
import datetime
import json
import math
import os
import platform
import subprocess


def cpu_name():
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
        fields = dict(line.split(":", 1) for line in out.splitlines() if ":" in line)
        return f"{fields['Model name'].strip()}, {fields['CPU(s)'].strip()} logical CPUs"
    except (OSError, subprocess.CalledProcessError, KeyError):
        return platform.processor() or "unknown CPU"


def geomean(values):
    values = [v for v in values if v and v > 0]
    return math.exp(sum(math.log(v) for v in values) / len(values)) if values else float("nan")


def merge(paths):
    rows, seen_embree = [], set()
    for path in paths:
        with open(path) as f:
            for r in json.load(f):
                if is_peer(r):
                    key = (r["scene"], r["rays"], r["structure"])
                    if key in seen_embree:
                        continue
                    seen_embree.add(key)
                rows.append(r)
    return rows


def mesh(scene):
    return os.path.basename(scene)


def is_peer(r):
    return r["structure"].startswith(PEER_PREFIXES)


PEER_PREFIXES = ("embree-", "tinybvh-")


def fastest_peer(rows, key):
    """The peer row (Embree or tinybvh) with the highest `key` (mrays_1t or mrays_mt), or None."""
    return max((r for r in rows if is_peer(r)), key=lambda r: r[key], default=None)


def peer_ratio(r, peer, key):
    """r's ratio over the fastest peer: the bench's own peer_ratio_* (timed in r's run) when the
    file has it, else r / the merged table's fastest peer row (files older than the key)."""
    stored = r.get("peer_ratio_" + key)
    if stored is not None:
        return stored
    if "peer_ratio_" + key in r:  # null: that run had no peer
        return None
    return r["mrays_" + key] / peer["mrays_" + key] if peer and peer["mrays_" + key] > 0 else None


def speed_table(rows, rays):
    structures = ["bvh", "kdtree", "octree", "grid", "spheretree"]
    sel = [r for r in rows if r["rays"] == rays]
    scenes = list(dict.fromkeys(r["scene"] for r in sel))
    out = [f"\nRays `{rays}`, watertight kernel, Mrays/s with 1 thread / all threads "
           f"({sel[0]['threads']}); ratio = bvh / the faster Embree row; the fastest peer row (Embree or "
           "tinybvh, each measure on its own) and the fastest bvh row's peer_ratio (bvh / the fastest peer, "
           "timed in the bvh row's run):\n",
           "| mesh | Embree 1t / mt | " + " | ".join(structures) + " | bvh / Embree 1t | bvh / Embree mt | "
           "fastest peer 1t / mt | bvh / peer 1t | bvh / peer mt |",
           "|---|---:|" + "---:|" * len(structures) + "---:|---:|---|---:|---:|"]
    ratios_1t, ratios_mt = [], []
    peer_ratios_1t, peer_ratios_mt, fastest_names = [], [], []
    for scene in scenes:
        here = [r for r in sel if r["scene"] == scene]
        embree = [r for r in here if r["structure"].startswith("embree-")]
        e1 = max((r["mrays_1t"] for r in embree), default=None)
        emt = max((r["mrays_mt"] for r in embree), default=None)
        cells = []
        bvh = None
        for s in structures:
            r = next((r for r in here if r["structure"] == s and r["kernel"] == "watertight"), None)
            cells.append(f"{r['mrays_1t']:.2f} / {r['mrays_mt']:.2f}" if r else "")
            if s == "bvh":
                bvh = r
        r1 = bvh["mrays_1t"] / e1 if bvh and e1 else None
        rmt = bvh["mrays_mt"] / emt if bvh and emt else None
        ratios_1t.append(r1)
        ratios_mt.append(rmt)
        fmt = lambda x: f"{x:.2f}" if x else ""
        embree_cell = f"{e1:.2f} / {emt:.2f}" if e1 else ""
        # The fastest peer, and the fastest watertight bvh row (of any parameters) against it.
        p1, pmt = fastest_peer(here, "mrays_1t"), fastest_peer(here, "mrays_mt")
        if p1 and pmt:
            names = (f"({p1['structure']})" if p1 is pmt else f"({p1['structure']} / {pmt['structure']})")
            peer_cell = f"{p1['mrays_1t']:.2f} / {pmt['mrays_mt']:.2f} {names}"
            fastest_names.append(pmt["structure"])
        else:
            peer_cell = ""
        bvh_rows = [r for r in here if r["structure"] == "bvh" and r["kernel"] == "watertight"]
        best = max(bvh_rows, key=lambda r: r["mrays_mt"], default=None)
        q1 = peer_ratio(best, p1, "1t") if best else None
        qmt = peer_ratio(best, pmt, "mt") if best else None
        peer_ratios_1t.append(q1)
        peer_ratios_mt.append(qmt)
        out.append(f"| {mesh(scene)} | {embree_cell} | " + " | ".join(cells) + f" | {fmt(r1)} | {fmt(rmt)} | "
                   f"{peer_cell} | {fmt(q1)} | {fmt(qmt)} |")
    valid_1t = [r for r in ratios_1t if r]
    valid_mt = [r for r in ratios_mt if r]
    if valid_mt:
        out.append(f"\nbvh / Embree over the {len(valid_mt)} meshes: geometric mean {geomean(valid_1t):.2f} "
                   f"(1 thread), {geomean(valid_mt):.2f} (all threads); all threads min {min(valid_mt):.2f}, "
                   f"max {max(valid_mt):.2f}.")
    valid_1t = [r for r in peer_ratios_1t if r]
    valid_mt = [r for r in peer_ratios_mt if r]
    if valid_mt:
        counts = ", ".join(f"{name} on {fastest_names.count(name)}" for name in dict.fromkeys(fastest_names))
        out.append(f"\nbvh / the fastest peer over the {len(valid_mt)} meshes: geometric mean {geomean(valid_1t):.2f} "
                   f"(1 thread), {geomean(valid_mt):.2f} (all threads); all threads min {min(valid_mt):.2f}, "
                   f"max {max(valid_mt):.2f}. Fastest peer with all threads: {counts}.")
    return out


def build_table(rows):
    """Build ms per mesh: Embree medium, then each structure with its embree_build_ratio. Each
    mesh's numbers come from the first run that built it (the rows of one run share thread
    count and timing policy; merge() keeps that run's Embree rows). Files older than the
    embree_build_ratio key timed one build of each on different threads: their build ms are
    shown, the ratio cell stays empty rather than mixing policies."""
    structures = list(dict.fromkeys(r["structure"] for r in rows if not r["structure"].startswith("embree-")))
    # By mesh name, not path: a mesh benched under two paths is one row (its first run's).
    meshes = list(dict.fromkeys(mesh(r["scene"]) for r in rows))
    threads = sorted({r["threads"] for r in rows if "threads" in r})
    out = [f"\nBuild time in ms on {'/'.join(map(str, threads))} threads (best of 3 builds; files without "
           "`embree_build_ratio` are from an older bench that timed one build), and in parentheses Embree medium "
           "build ms / the row's (> 1: builds faster than Embree medium), timed in the same run:\n",
           "| mesh | Embree medium | Embree high | " + " | ".join(structures) + " |",
           "|---|---:|---:|" + "---:|" * len(structures)]
    ratios = {s: [] for s in structures}
    for name in meshes:
        here = [r for r in rows if mesh(r["scene"]) == name]
        first = {}
        for r in here:
            first.setdefault(r["structure"], r)  # the first run's row of each structure

        def cell(r):
            if r is None:
                return ""
            ratio = r.get("embree_build_ratio")
            return f"{r['build_ms']:.1f}" + (f" ({ratio:.2f})" if ratio else "")

        cells = [cell(first.get("embree-medium")), cell(first.get("embree-high"))]
        for s in structures:
            r = first.get(s)
            cells.append(cell(r))
            if r and r.get("embree_build_ratio"):
                ratios[s].append(r["embree_build_ratio"])
        out.append(f"| {name} | " + " | ".join(cells) + " |")
    means = [f"{s} {geomean(v):.2f}" for s, v in ratios.items() if v]
    if means:
        out.append(f"\nEmbree medium build ms / structure build ms, geometric mean over the meshes: {', '.join(means)}.")
    return out


def cold_table(default_rows, cold_rows):
    """Cold builds (COLD.json: the median of three fresh `stats` processes) against the warm
    build of the same structure and Embree medium's, both from the bench run of DEFAULT.json
    (best of 3 builds in one process). Issue #31's targets are in the last column."""
    targets = {"bvh": 1.0, "grid": 1.5, "kdtree": 3.0, "octree": 3.0, "spheretree": 3.0}
    out = ["\nCold builds: the median of 3 fresh `accelviz-cli stats` processes (the first build of a process, "
           "what every CLI run and the viewer's first build of a scene pay), against the same build warm (best "
           "of 3 in the bench process above) and against Embree medium's build there:\n",
           "| mesh | structure | cold ms | warm ms | cold / warm | Embree medium ms | cold / Embree | target (issue #31) |",
           "|---|---|---:|---:|---:|---:|---:|---|"]
    for c in cold_rows:
        name = mesh(c["scene"])
        warm = next((r for r in default_rows if mesh(r["scene"]) == name and r["structure"] == c["structure"]), None)
        embree = next((r for r in default_rows if mesh(r["scene"]) == name and r["structure"] == "embree-medium"), None)
        cold = c["cold_median_ms"]
        if name == "crytek_sponza.obj":
            target = f"cold / Embree <= {targets[c['structure']]:g}"
        elif name == "procedural:terrain":
            target = "cold < 500 ms"
        else:
            target = ""
        out.append(f"| {name} | {c['structure']} | {cold:.1f} | " +
                   (f"{warm['build_ms']:.1f} | {cold / warm['build_ms']:.2f}" if warm else " | ") + " | " +
                   (f"{embree['build_ms']:.1f} | {cold / embree['build_ms']:.2f}" if embree else " | ") +
                   f" | {target} |")
    return out


def error_table(rows):
    keys = list(dict.fromkeys((r["structure"], r["kernel"]) for r in rows))
    out = ["\nErrors against the double-precision reference, summed over every mesh and both ray sets "
           "(a ray counts once: a false miss, a false hit, a wrong triangle that is not a tie, or the right "
           "triangle at a wrong t):\n",
           "| structure | kernel | rays | false miss | false hit | wrong tri | wrong t | max rel t err | "
           "Mrays/s mt vs Embree (geo. mean) | Mrays/s mt vs fastest peer (geo. mean) |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    peers = {}  # (scene, rays) -> the fastest peer row with all threads
    for r in rows:
        if is_peer(r):
            key = (r["scene"], r["rays"])
            if key not in peers or r["mrays_mt"] > peers[key]["mrays_mt"]:
                peers[key] = r
    for structure, kernel in keys:
        sel = [r for r in rows if r["structure"] == structure and r["kernel"] == kernel]
        ratio = geomean([r.get("embree_ratio_mt") for r in sel])
        ratio_cell = "baseline" if structure.startswith("embree-") else ("" if math.isnan(ratio) else f"{ratio:.2f}")
        peer = geomean([peer_ratio(r, peers.get((r["scene"], r["rays"])), "mt") for r in sel])
        peer_cell = "peer" if any(is_peer(r) for r in sel) else ("" if math.isnan(peer) else f"{peer:.2f}")
        out.append(f"| {structure} | {kernel} | {sum(r['n_rays'] for r in sel):,} | {sum(r['false_miss'] for r in sel)} | "
                   f"{sum(r['false_hit'] for r in sel)} | {sum(r['wrong_prim'] for r in sel)} | "
                   f"{sum(r.get('wrong_t', 0) for r in sel)} | "
                   f"{max(r['max_rel_t_err'] for r in sel):.2g} | {ratio_cell} | {peer_cell} |")
    return out


def sah_table(default_rows, sweep_rows):
    """The bvh's default builder against the full SAH sweep, per mesh: SAH cost (lower is
    better; same ct/ci) and build ms, each from its own bench run."""
    def by_mesh(rows):
        out = {}
        for r in rows:
            if r["structure"] == "bvh" and r.get("sah_cost") is not None:
                out.setdefault(mesh(r["scene"]), r)
        return out
    default, sweep = by_mesh(default_rows), by_mesh(sweep_rows)
    out = ["\nbvh SAH cost (width 4, ct=1, ci=1 per 4-triangle test, root area 1) and build ms: the default "
           "builder (binned SAH, 64 bins) against the full sweep (builder=sah), and the cost ratio:\n",
           "| mesh | binned SAH cost | sweep SAH cost | binned / sweep | binned build ms | sweep build ms |",
           "|---|---:|---:|---:|---:|---:|"]
    ratios = []
    for name, d in default.items():
        s = sweep.get(name)
        if s is None:
            continue
        ratio = d["sah_cost"] / s["sah_cost"]
        ratios.append(ratio)
        out.append(f"| {name} | {d['sah_cost']:.4g} | {s['sah_cost']:.4g} | {ratio:.3f} | {d['build_ms']:.1f} | "
                   f"{s['build_ms']:.1f} |")
    if ratios:
        within = sum(1 for r in ratios if r <= 1.02)
        out.append(f"\nbinned / sweep SAH cost: geometric mean {geomean(ratios):.3f}, worst {max(ratios):.3f}; "
                   f"within 2% on {within} of {len(ratios)} scenes.")
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="+")
    ap.add_argument("--out-json")
    ap.add_argument("--made-by", default="scripts/bench_shared.sh", help="the script named in the header line")
    ap.add_argument("--builds", action="store_true", help="build report: DEFAULT.json SWEEP.json")
    a = ap.parse_args()
    if a.builds:
        if len(a.files) not in (2, 3):
            ap.error("--builds takes DEFAULT.json SWEEP.json [COLD.json]")
        default_rows, sweep_rows = (merge([f]) for f in a.files[:2])
        lines = [f"Measured {datetime.date.today().isoformat()} on {cpu_name()} (`scripts/bench_builds.sh`)."]
        lines += build_table(default_rows) + sah_table(default_rows, sweep_rows)
        if len(a.files) == 3:
            with open(a.files[2]) as f:
                lines += cold_table(default_rows, json.load(f))
        print("\n".join(lines))
        return 0
    rows = merge(a.files)
    if a.out_json:
        tmp = a.out_json + ".tmp"
        with open(tmp, "w") as f:
            json.dump(rows, f, indent=1)
        os.replace(tmp, a.out_json)  # never a half-written file
    lines = [f"Measured {datetime.date.today().isoformat()} on {cpu_name()} (`{a.made_by}`)."]
    for rays in dict.fromkeys(r["rays"] for r in rows):
        lines += speed_table(rows, rays)
    lines += build_table(rows)
    lines += error_table(rows)
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
