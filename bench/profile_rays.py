#!/usr/bin/env python3
"""The tables of bench/profile_rays.sh from its callgrind dumps and native bench runs.

Each callgrind run of `accelviz-cli bench` is split into one dump per bench row (a dump
before every progress line). A dump is the row of the one query function it counted:
accelviz's fast 8-wide query (accel::wide8_fast_avx2), tinybvh's (cli::TinyBvhScene::
intersect, in the order of the bench's tinybvh rows) or Embree's (rtcIntersect1, medium then
high). Per row: instructions and mispredicted branches per call, and the instructions of
each source line, put in a category by the function of the source they come from (the
functions are found in the sources by their signatures, so the mapping follows edits). The
number of times a line ran is the count of its most executed instruction (--dump-instr):
that gives the inner nodes and leaves tested per ray from one line of each kernel.
"""
import argparse
import json
import os
import re
import subprocess
import sys
from collections import defaultdict

CATEGORIES = ["ray set-up", "node tests", "child order and stack", "leaf tests", "exact fallback",
              "query entry and exit", "other"]
TINYBVH_ROWS = ["tinybvh-bvh8", "tinybvh-bvh4", "tinybvh-bvh8-hq"]
EMBREE_ROWS = ["embree-medium", "embree-high"]


def brace_range(lines, start):
    """1-based [first, last] lines of the block that opens at or after line index `start`."""
    depth, opened = 0, False
    for i in range(start, len(lines)):
        for ch in lines[i]:
            if ch == '{':
                depth, opened = depth + 1, True
            elif ch == '}':
                depth -= 1
                if opened and depth == 0:
                    return start + 1, i + 1
    return start + 1, len(lines)


def find(lines, pattern, after=0):
    for i in range(after, len(lines)):
        if re.search(pattern, lines[i]):
            return i
    return None


class SourceMap:
    """(file basename, line) -> category, from function ranges found in the sources."""

    def __init__(self, root, tinybvh_header):
        self.ranges = defaultdict(list)  # basename -> [(first, last, category)], innermost first
        self.whole = {"geometry.cpp": "exact fallback", "tinybvh_baseline.cpp": "ray set-up"}
        self.markers = {}  # name -> (basename, line) of the lines counted per node / leaf
        core = os.path.join(root, "core")
        self._accel(os.path.join(core, "geometry.h"), [
            (r"^TriangleTester::TriangleTester\(", "ray set-up"),
            (r"^BoxTester::BoxTester\(", "ray set-up"),
            (r"^int TriangleTester::watertight4\(", "leaf tests"),
            (r"^int TriangleTester::moller4\(", "leaf tests"),
            (r"^int TriangleTester::intersect4\(", "leaf tests"),
            (r"TriangleTester::test_lanes\(", "exact fallback"),
        ])
        self._accel(os.path.join(core, "structures", "wide_bvh_isa_unit.h"), [
            (r"^struct WideRayFor<ACCEL_ISA_TAG>", "ray set-up"),
            (r"int intersect_children\(", "node tests"),
            (r"int nearer_slots\(", "child order and stack"),
            (r"^Hit ACCEL_ISA_NAME\(wide8_fast_\)", "query entry and exit"),
        ])
        self._accel(os.path.join(core, "structures", "wide_bvh.h"), [
            (r"void test_leaf\(", "leaf tests"),
            (r"static void prefetch\(", "child order and stack"),
            (r"static int popcount8\(", "child order and stack"),
            (r"::traverse_stack\(const Ray", "child order and stack"),
            (r"::traverse_with\(const Ray", "query entry and exit"),
            (r"^struct WideRayFor<Sse2Tag>", "ray set-up"),
        ])
        self._accel(os.path.join(core, "structure.h"), [
            (r"bool take_triangle_result\(", "leaf tests"),
            (r"^inline Hit no_hit\(", "ray set-up"),
            (r"^inline Hit finish_query\(", "query entry and exit"),
        ])
        self._marker(os.path.join(core, "structures", "wide_bvh_isa_unit.h"), "accel node",
                     r"_mm256_movemask_ps\(_mm256_cmp_ps\(t0, t1, _CMP_LE_OQ\)\)")
        self._marker(os.path.join(core, "structures", "wide_bvh.h"), "accel leaf",
                     r"const TriangleBlock\* block = blocks_\.data\(\) \+ ref_first\(r\);")
        self._marker(os.path.join(core, "geometry.h"), "accel block", r"const __m128 u_ = _mm_sub_ps\(")
        self._tinybvh(tinybvh_header)

    def _accel(self, path, functions):
        lines = open(path).read().split("\n")
        base = os.path.basename(path)
        for pattern, category in functions:
            i = find(lines, pattern)
            if i is None:
                print(f"profile_rays.py: note: {base}: no line matches {pattern!r}; its lines count as 'other'",
                      file=sys.stderr)
                continue
            first, last = brace_range(lines, i)
            self.ranges[base].append((first, last, category))
        # Innermost first: a range inside another (a lambda of traverse_stack) wins.
        self.ranges[base].sort(key=lambda r: r[1] - r[0])

    def _marker(self, path, name, pattern):
        lines = open(path).read().split("\n")
        i = find(lines, pattern)
        if i is not None:
            self.markers[name] = (os.path.basename(path), i + 1)

    def _tinybvh(self, path):
        if not os.path.exists(path):
            return
        lines = open(path).read().split("\n")
        base = os.path.basename(path)
        start = find(lines, r"template <bool posX, bool posY, bool posZ> int32_t BVH8_CPU::Intersect\( Ray& ray \) const")
        dispatch = find(lines, r"^int32_t BVH8_CPU::Intersect\( Ray& ray \) const")
        if start is None:
            return
        first, last = brace_range(lines, start)
        loop = find(lines, r"while \(1\)", start)
        nodes = find(lines, r"while \(!\(nodeIdx & LEAF_BIT\)\)", start)
        valid = find(lines, r"const uint32_t validNodes", start)
        leaf = find(lines, r"// Moeller-Trumbore", start)
        compress = find(lines, r"// compress stack", start)
        if None in (loop, nodes, valid, leaf, compress):
            return
        self.ranges[base] += [
            (first, loop, "ray set-up"),
            (nodes + 1, valid, "node tests"),
            (valid + 1, leaf, "child order and stack"),
            (leaf + 1, compress, "leaf tests"),
            (compress + 1, last, "child order and stack"),
            (loop + 1, nodes, "child order and stack"),
        ]
        if dispatch is not None:
            d0, d1 = brace_range(lines, dispatch)
            self.ranges[base].append((d0, d1, "query entry and exit"))
        i = find(lines, r"const uint32_t mask = _mm256_movemask_ps\( mask8 \);", start)
        if i is not None:
            self.markers["tinybvh node"] = (base, i + 1)
        i = find(lines, r"const __m128 hx4 = _mm_fmsub_ps", start)
        if i is not None:
            self.markers["tinybvh leaf"] = (base, i + 1)

    def category_of(self, path, line):
        """The category of one source line, or None when its file is not one of the kernels'."""
        base = os.path.basename(path)
        for first, last, category in self.ranges.get(base, ()):
            if first <= line <= last:
                return category
        return self.whole.get(base)

    def category(self, frames):
        """The innermost frame that lies in a kernel's function decides; 'other' if none does."""
        for path, line in frames:
            c = self.category_of(path or "", line)
            if c:
                return c
        return "other"


class Dump:
    """One callgrind dump: each instruction's events (by object file and address) and calls."""

    def __init__(self, path):
        self.events = []
        self.instr = defaultdict(lambda: [0] * 8)  # (object, address) -> events
        self.where = {}  # (object, address) -> (file, line) innermost, as callgrind saw it
        self.function = {}  # (object, address) -> its function (a template's instantiations apart)
        self.calls = defaultdict(int)
        ob = fl = fn = cur = callee = None
        skip = False
        with open(path) as f:
            for raw in f:
                line = raw.rstrip("\n")
                if not line:
                    continue
                if line.startswith("events:"):
                    self.events = line.split()[1:]
                elif line.startswith("ob="):
                    ob = line[3:]
                elif line.startswith("fl="):
                    fl = cur = line[3:]
                elif line.startswith(("fi=", "fe=")):
                    cur = line[3:]
                elif line.startswith("fn="):
                    fn, cur = line[3:], fl
                elif line.startswith("cfn="):
                    callee = line[4:]
                elif line.startswith("calls="):
                    self.calls[callee] += int(line.split()[0][6:])
                    skip = True  # the next line is the call's inclusive cost, not this instruction's own
                elif line.startswith("0x"):
                    if skip:
                        skip = False
                        continue
                    parts = line.split()
                    key = (ob, int(parts[0], 16))
                    acc = self.instr[key]
                    for i, v in enumerate(parts[2:]):
                        acc[i] += int(v)
                    self.where[key] = (cur, int(parts[1]))
                    self.function[key] = fn

    def total(self, event):
        i = self.events.index(event) if event in self.events else None
        return 0 if i is None else sum(v[i] for v in self.instr.values())

    def event(self, values, name):
        return values[self.events.index(name)] if name in self.events else 0

    def query(self):
        """The row kind this dump timed, and its number of queries."""
        for kind, pattern in (("accelviz", "accel::wide8_fast_avx2"), ("tinybvh", "cli::TinyBvhScene::intersect"),
                              ("embree", "rtcIntersect1")):
            n = sum(c for name, c in self.calls.items() if name and name.startswith(pattern))
            if n:
                return kind, n
        return None, 0


class InlineFrames:
    """Each instruction's chain of inlined source lines (innermost first), from addr2line -i:
    an intrinsic or glm line is put where it was written, in the kernel that called it."""

    def __init__(self):
        self.frames = {}

    def resolve(self, binary, addresses):
        todo = sorted(a for a in set(addresses) if (binary, a) not in self.frames)
        if not todo or not os.path.exists(binary):
            return
        out = subprocess.run(["addr2line", "-i", "-a", "-e", binary], input="\n".join(hex(a) for a in todo),
                             capture_output=True, text=True, check=True).stdout
        current = None
        for line in out.split("\n"):
            if line.startswith("0x"):
                current = (binary, int(line, 16))
                self.frames[current] = []
            elif current and ":" in line:
                file_, _, rest = line.rpartition(":")
                number = rest.split()[0] if rest.split() else "0"
                self.frames[current].append((file_, int(number) if number.isdigit() else 0))

    def of(self, key, fallback):
        return self.frames.get(key) or [fallback]


def dumps_of(work, tag):
    base = os.path.join(work, tag + ".cg")
    parts = []
    for name in os.listdir(work):
        if name.startswith(tag + ".cg"):
            suffix = name[len(tag) + 3:]
            parts.append((int(suffix[1:]) if suffix.startswith(".") and suffix[1:].isdigit() else 10**9,
                          os.path.join(work, name)))
    return [p for _, p in sorted(parts)] or [base]


def analyse_case(args, case, smap):
    tag, mesh, kind, small, full, native = case
    timed = {}
    if os.path.exists(native):
        for row in json.load(open(native)):
            name = row["structure"]
            if name == "bvh":
                name = "accelviz bvh"
            timed[name] = row.get("mrays_1t")
    rows = []
    seen = defaultdict(int)
    for path in dumps_of(args.work, tag):
        d = Dump(path)
        query, calls = d.query()
        if not query:
            continue
        index = seen[query]
        seen[query] += 1
        if query == "accelviz":
            name = "accelviz bvh"
        elif query == "tinybvh":
            name = TINYBVH_ROWS[index] if index < len(TINYBVH_ROWS) else f"tinybvh-{index}"
        else:
            name = EMBREE_ROWS[index] if index < len(EMBREE_ROWS) else f"embree-{index}"
        frames = InlineFrames()
        by_object = defaultdict(list)
        for (ob, addr) in d.instr:
            by_object[ob].append(addr)
        for ob, addrs in by_object.items():
            if ob and ob.endswith("accelviz-cli"):
                frames.resolve(ob, addrs)
        split, miss_split = defaultdict(int), defaultdict(int)
        # Times a line ran: its most executed instruction's count, in each function that has
        # a copy of it (tinybvh's traversal is one instantiation per ray octant), summed.
        per_copy = defaultdict(int)
        for key, values in d.instr.items():
            chain = frames.of(key, d.where.get(key, ("", 0)))
            category = smap.category(chain)
            split[category] += d.event(values, "Ir")
            miss_split[category] += d.event(values, "Bcm") + d.event(values, "Bim")
            for path_, ln in set(chain):
                k = (d.function.get(key), os.path.basename(path_ or ""), ln)
                per_copy[k] = max(per_copy[k], d.event(values, "Ir"))
        runs = defaultdict(int)
        for (_, base, ln), n in per_copy.items():
            runs[(base, ln)] += n
        ir = d.total("Ir")
        mispredicts = d.total("Bcm") + d.total("Bim")
        row = {"case": tag, "mesh": mesh, "rays": kind, "callgrind_rays": small, "timed_rays": full, "query": name,
               "calls": calls, "instr_per_ray": ir / calls, "mispredicts_per_ray": mispredicts / calls,
               "instr_split": {c: split.get(c, 0) / calls for c in CATEGORIES},
               "mispredict_split": {c: miss_split.get(c, 0) / calls for c in CATEGORIES}}
        row["split_known"] = query == "accelviz" or name in ("tinybvh-bvh8", "tinybvh-bvh8-hq")
        marks = smap.markers
        if query == "accelviz":
            row["inner_nodes_per_ray"] = runs.get(marks.get("accel node"), 0) / calls
            row["leaves_per_ray"] = runs.get(marks.get("accel leaf"), 0) / calls
            row["triangle_lanes_per_ray"] = 4 * runs.get(marks.get("accel block"), 0) / calls
            row["fallbacks_per_ray"] = sum(c for n, c in d.calls.items() if n and "TriangleTester::reference(" in n) / calls
        elif row["split_known"]:
            row["inner_nodes_per_ray"] = runs.get(marks.get("tinybvh node"), 0) / calls
            row["leaves_per_ray"] = runs.get(marks.get("tinybvh leaf"), 0) / calls
            row["triangle_lanes_per_ray"] = 4 * row["leaves_per_ray"]
        mrays = timed.get(name)
        if mrays:
            row["mrays_1t"] = mrays
            row["ns_per_ray"] = 1e3 / mrays
            row["cycles_per_ray"] = row["ns_per_ray"] * args.mhz / 1e3
        rows.append(row)
    return rows


def fmt(v, spec="{:,.0f}"):
    return "-" if v is None else spec.format(v)


def markdown(rows, label):
    out = [f"Profile `{label}`: per ray, callgrind counts on the smaller ray set, ns with one thread on the full one.", "",
           "| case | query | instr / ray | mispredicts / ray | inner nodes / ray | leaves / ray | triangle lanes / ray "
           "| fallbacks / ray | Mrays/s 1t | ns / ray | ≈ cycles / ray |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        out.append(f"| {r['case']} | {r['query']} | {fmt(r['instr_per_ray'])} | {fmt(r['mispredicts_per_ray'], '{:.1f}')} | "
                   f"{fmt(r.get('inner_nodes_per_ray'), '{:.2f}')} | {fmt(r.get('leaves_per_ray'), '{:.2f}')} | "
                   f"{fmt(r.get('triangle_lanes_per_ray'), '{:.1f}')} | {fmt(r.get('fallbacks_per_ray'), '{:.4f}')} | "
                   f"{fmt(r.get('mrays_1t'), '{:.2f}')} | {fmt(r.get('ns_per_ray'), '{:.1f}')} | "
                   f"{fmt(r.get('cycles_per_ray'))} |")
    out += ["", "Where the instructions go (per ray; Embree has no line tables and tinybvh-bvh4 runs another kernel, "
            "so only their totals, under 'other'):", "",
            "| case | query | " + " | ".join(CATEGORIES) + " |", "|---|---|" + "---:|" * len(CATEGORIES)]
    for r in rows:
        if not r.get("split_known"):
            cells = ["-"] * (len(CATEGORIES) - 1) + [fmt(r["instr_per_ray"])]
        else:
            cells = [fmt(r["instr_split"][c]) for c in CATEGORIES]
        out.append(f"| {r['case']} | {r['query']} | " + " | ".join(cells) + " |")
    out += ["", "Where the mispredicted branches are (per ray):", "",
            "| case | query | " + " | ".join(CATEGORIES) + " |", "|---|---|" + "---:|" * len(CATEGORIES)]
    for r in rows:
        if not r.get("split_known"):
            cells = ["-"] * (len(CATEGORIES) - 1) + [fmt(r["mispredicts_per_ray"], "{:.1f}")]
        else:
            cells = [fmt(r["mispredict_split"][c], "{:.2f}") for c in CATEGORIES]
        out.append(f"| {r['case']} | {r['query']} | " + " | ".join(cells) + " |")
    return "\n".join(out) + "\n"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--label", default="")
    p.add_argument("--root", required=True)
    p.add_argument("--tinybvh", default="")
    p.add_argument("--mhz", type=float, default=0.0)
    p.add_argument("--work", required=True)
    p.add_argument("--out-md")
    p.add_argument("--out-json")
    p.add_argument("--case", nargs=6, action="append", default=[],
                   metavar=("TAG", "MESH", "RAYS", "CALLGRIND_RAYS", "TIMED_RAYS", "TIMED_JSON"))
    p.add_argument("--peers-from", help="an earlier run's JSON: its peer rows join this run's accelviz rows")
    args = p.parse_args()
    smap = SourceMap(args.root, args.tinybvh)
    rows = [r for case in args.case for r in analyse_case(args, case, smap)]
    if args.peers_from:
        text = open(args.peers_from).read()
        earlier = json.loads(text)["rows"] if text.strip() else []  # /dev/null: accelviz alone
        cases = [c[0] for c in args.case]
        rows = [r for c in cases for r in earlier if r["case"] == c and r["query"] != "accelviz bvh"] + rows
        rows.sort(key=lambda r: (cases.index(r["case"]), r["query"] == "accelviz bvh"))
    text = markdown(rows, args.label)
    sys.stdout.write(text)
    if args.out_md:
        open(args.out_md, "w").write(text)
    if args.out_json:
        json.dump({"label": args.label, "mhz": args.mhz, "rows": rows}, open(args.out_json, "w"), indent=1)


if __name__ == "__main__":
    main()
