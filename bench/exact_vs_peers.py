#!/usr/bin/env python3
"""The table of bench/exact_vs_peers.sh: KIND=FILE arguments, one bench JSON per run and ray
set. Per mesh and ray set, each ratio is taken within one run (both rows timed in the same
process) and the best of the runs is kept; then geometric means and minima over the cases."""
import argparse
import json
import math
import os
from collections import defaultdict

FASTEST = ("embree-medium", "tinybvh-bvh8", "tinybvh-bvh4", "tinybvh-bvh8-hq")  # the peers
RATIOS = [
    ("exact / fastest peer", "watertight", FASTEST),
    ("exact / Embree robust", "watertight", ("embree-robust",)),
    ("moller / fastest peer", "moller", FASTEST),
]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("runs", nargs="+", help="KIND=bench JSON of one run")
    p.add_argument("--out-md")
    p.add_argument("--out-json")
    args = p.parse_args()
    best = defaultdict(dict)  # (mesh, kind) -> (ratio name, threads) -> best ratio
    peer_of = {}
    wrong = defaultdict(int)
    for spec in args.runs:
        kind, _, path = spec.partition("=")
        rows = json.load(open(path))
        by_scene = defaultdict(dict)
        for r in rows:
            name = r["structure"] if r["structure"] != "bvh" else "bvh " + r["kernel"]
            by_scene[os.path.basename(r["scene"]).removesuffix(".obj")][name] = r
        for mesh, named in by_scene.items():
            case = (mesh, kind)
            if "bvh watertight" in named:
                w = named["bvh watertight"]
                wrong[case] = max(wrong[case], w["false_miss"] + w["false_hit"] + w["wrong_prim"])
            for label, kernel, peers in RATIOS:
                ours = named.get("bvh " + kernel)
                present = [named[n] for n in peers if n in named]
                if not ours or not present:
                    continue
                for threads in ("1t", "mt"):
                    top = max(present, key=lambda r: r["mrays_" + threads])
                    ratio = ours["mrays_" + threads] / top["mrays_" + threads]
                    key = (label, threads)
                    if ratio > best[case].get(key, 0.0):
                        best[case][key] = ratio
                        peer_of[(case, key)] = top["structure"]
    cases = sorted(best, key=lambda c: (c[1], c[0]))
    cols = [(label, t) for label, _, _ in RATIOS for t in ("1t", "mt")]
    out = ["| mesh | rays | " + " | ".join(f"{label} ({t})" for label, t in cols) + " | exact: wrong answers |",
           "|---|---|" + "---:|" * len(cols) + "---:|"]
    for c in cases:
        cells = []
        for key in cols:
            v = best[c].get(key)
            cells.append("-" if v is None else f"{v:.2f} ({peer_of[(c, key)]})" if key[0] != "exact / Embree robust"
                         else f"{v:.2f}")
        out.append(f"| {c[0]} | {c[1]} | " + " | ".join(cells) + f" | {wrong[c]} |")
    summary = {}
    for key in cols:
        vals = [best[c][key] for c in cases if key in best[c]]
        if vals:
            summary[f"{key[0]} ({key[1]})"] = {"geomean": math.exp(sum(map(math.log, vals)) / len(vals)),
                                               "min": min(vals)}
    out += ["", "| ratio | geometric mean | minimum |", "|---|---:|---:|"]
    out += [f"| {k} | {v['geomean']:.2f} | {v['min']:.2f} |" for k, v in summary.items()]
    text = "\n".join(out) + "\n"
    print(text, end="")
    if args.out_md:
        open(args.out_md, "w").write(text)
    if args.out_json:
        json.dump({"cases": [{"mesh": c[0], "rays": c[1], "wrong": wrong[c],
                              **{f"{k[0]} ({k[1]})": best[c].get(k) for k in cols}} for c in cases],
                   "summary": summary}, open(args.out_json, "w"), indent=1)


if __name__ == "__main__":
    main()
