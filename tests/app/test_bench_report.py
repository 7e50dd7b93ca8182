#!/usr/bin/env python3
"""scripts/bench_report.py on small synthetic bench JSON files: the speed table's Embree and
fastest-peer columns and geometric means, the error table's ratio columns, with tinybvh rows and peer_ratio_* keys, and with
an older file that has neither (its peer columns fall back to the Embree rows); --builds with a
cold-build file (its ratios to the warm build and to Embree medium)."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "bench_report.py")


def row(scene, structure, kernel, mt, t1, **extra):
    r = {"scene": scene, "structure": structure, "params": "", "kernel": kernel, "rays": "random:100:1",
         "n_rays": 100, "build_ms": 1.0, "memory_bytes": 1000, "mrays_1t": t1, "mrays_mt": mt, "threads": 2,
         "false_miss": 0, "false_hit": 0, "wrong_prim": 0, "wrong_t": 0, "max_rel_t_err": 1e-7,
         "mean_rel_t_err": 1e-8}
    r.update(extra)
    return r


def report(*files, options=()):
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i, rows in enumerate(files):
            paths.append(os.path.join(tmp, f"{i}.json"))
            with open(paths[-1], "w") as f:
                json.dump(rows, f)
        return subprocess.run([sys.executable, SCRIPT, *options, *paths], capture_output=True, text=True, check=True).stdout


def table_row(text, mesh):
    line = next(l for l in text.splitlines() if l.startswith(f"| {mesh} |"))
    return [c.strip() for c in line.strip("|").split("|")]


class BenchReport(unittest.TestCase):
    def test_peers_with_tinybvh(self):
        rows = [
            row("a.obj", "embree-medium", "embree", 10.0, 5.0),
            row("a.obj", "embree-high", "embree", 9.0, 5.5),
            row("a.obj", "tinybvh-bvh8", "tinybvh", 20.0, 8.0, embree_ratio_mt=2.0, embree_ratio_1t=1.4545),
            row("a.obj", "bvh", "watertight", 8.0, 4.0, embree_ratio_mt=0.8, embree_ratio_1t=0.7273,
                peer_ratio_mt=0.4, peer_ratio_1t=0.5),
            row("a.obj", "bvh", "watertight", 16.0, 6.0, params="width=8", embree_ratio_mt=1.6,
                embree_ratio_1t=1.0909, peer_ratio_mt=0.8, peer_ratio_1t=0.75),
            row("b.obj", "embree-medium", "embree", 4.0, 2.0),
            row("b.obj", "tinybvh-bvh4", "tinybvh", 3.0, 2.5, embree_ratio_mt=0.75, embree_ratio_1t=1.25),
            row("b.obj", "bvh", "watertight", 2.0, 1.25, embree_ratio_mt=0.5, embree_ratio_1t=0.625,
                peer_ratio_mt=0.5, peer_ratio_1t=0.5),
        ]
        text = report(rows)
        header = table_row(text, "mesh")
        self.assertEqual(header[-3:], ["fastest peer 1t / mt", "bvh / peer 1t", "bvh / peer mt"])
        a = table_row(text, "a.obj")
        self.assertEqual(a[header.index("Embree 1t / mt")], "5.50 / 10.00")
        self.assertEqual(a[-3], "8.00 / 20.00 (tinybvh-bvh8)")
        # The fastest bvh row (width=8): its own peer ratios.
        self.assertEqual(a[-2:], ["0.75", "0.80"])
        b = table_row(text, "b.obj")
        self.assertEqual(b[-3], "2.50 / 4.00 (tinybvh-bvh4 / embree-medium)")
        self.assertEqual(b[-2:], ["0.50", "0.50"])
        # Geometric means: sqrt(0.75 * 0.5) = 0.61, sqrt(0.8 * 0.5) = 0.63.
        self.assertIn("bvh / the fastest peer over the 2 meshes: geometric mean 0.61 (1 thread), 0.63 (all "
                      "threads); all threads min 0.50, max 0.80. Fastest peer with all threads: tinybvh-bvh8 on 1, "
                      "embree-medium on 1.", text)
        self.assertIn("bvh / Embree over the 2 meshes", text)
        # The error table: geometric mean of the rows' peer_ratio_mt, (0.4 * 0.8 * 0.5)^(1/3).
        errors = next(l for l in text.splitlines() if l.startswith("| bvh | watertight |"))
        self.assertTrue(errors.endswith("| 0.54 |"), errors)
        tiny = next(l for l in text.splitlines() if l.startswith("| tinybvh-bvh8 | tinybvh |"))
        self.assertTrue(tiny.endswith("| 2.00 | peer |"), tiny)

    def test_old_file_without_peer_keys(self):
        rows = [row("a.obj", "embree-medium", "embree", 10.0, 5.0),
                row("a.obj", "bvh", "watertight", 5.0, 4.0, embree_ratio_mt=0.5)]
        text = report(rows)
        a = table_row(text, "a.obj")
        self.assertEqual(a[-3], "5.00 / 10.00 (embree-medium)")
        self.assertEqual(a[-2:], ["0.80", "0.50"])  # computed from the Embree row
        self.assertIn("bvh / the fastest peer over the 1 meshes: geometric mean 0.80 (1 thread), 0.50", text)
        errors = next(l for l in text.splitlines() if l.startswith("| bvh | watertight |"))
        self.assertTrue(errors.endswith("| 0.50 | 0.50 |"), errors)

    def test_no_peers(self):
        text = report([row("a.obj", "bvh", "watertight", 5.0, 4.0, embree_ratio_mt=None, peer_ratio_mt=None,
                           peer_ratio_1t=None)])
        a = table_row(text, "a.obj")
        self.assertEqual(a[-3:], ["", "", ""])
        self.assertNotIn("fastest peer over", text)

    def test_cold_builds(self):
        default = [row("crytek_sponza.obj", "embree-medium", "embree", 10.0, 5.0, build_ms=40.0),
                   row("crytek_sponza.obj", "bvh", "watertight", 10.0, 5.0, build_ms=50.0)]
        sweep = [row("crytek_sponza.obj", "bvh", "watertight", 10.0, 5.0, build_ms=90.0)]
        cold = [{"scene": "../shared/scenes/crytek_sponza.obj", "structure": "bvh", "cold_ms": [70.0, 60.0, 80.0],
                 "cold_median_ms": 70.0}]
        text = report(default, sweep, cold, options=("--builds",))
        line = next(l for l in text.splitlines() if l.startswith("| crytek_sponza.obj | bvh |"))
        cells = [c.strip() for c in line.strip("|").split("|")]
        # cold, warm, cold / warm, Embree medium, cold / Embree, target
        self.assertEqual(cells[2:], ["70.0", "50.0", "1.40", "40.0", "1.75", "cold / Embree <= 1"])


if __name__ == "__main__":
    unittest.main()
