#!/usr/bin/env python3
"""End-to-end fuzz of accelviz-cli trace (issue #16): mutated small OBJ scenes and rays files
through every structure. Each run must end in exactly one of
  exit 0: a complete hits CSV (header, one well-formed row per ray line of the rays file,
          docs/hits.md), nothing on stderr;
  exit 2: exactly one line on stderr, no output file (and no temporary file).
Each case also picks the kernel (mostly watertight) and 1 or 2 threads; the regressions
run with every kernel. A hang (the per-run timeout), another exit code, a signal, a sanitizer report, more lines or a
partial file fail. The regressions (tests/cli/regressions/) are replayed first, every run.

Reproducible: case K of seed S is always the same input, whatever ran before it.
  fuzz_cli.py --cli build/bin/accelviz-cli --source . --work /tmp/fuzz --seconds 60 --seed 16
  fuzz_cli.py ... --seed 16 --case 1234        # replay one case
A failing input is saved under WORK/failures/ and the line to replay it is printed.
ACCEL_FUZZ_CLI, when set, names the CLI instead of --cli (e.g. an ASan build's);
ACCEL_FUZZ_SECONDS overrides --seconds."""
import argparse
import math
import os
import random
import shutil
import subprocess
import sys
import time

RUN_TIMEOUT = 20  # seconds per CLI run: longer is a hang

# ---------------------------------------------------------------------------------------
# Seeds: small valid inputs. steps.obj comes from the repository; these cover the rest of the
# OBJ syntax the loader accepts.

SEED_OBJS = {
    "triangle.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "quad_negative.obj": b"# relative indices\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf -4 -3 -2 -1\n",
    "slashes.obj": (b"mtllib none.mtl\no box\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                    b"vn 0 0 1\ng top\nusemtl red\ns 1\nf 1/1/1 2/2/1 3/3/1\nf 1//1 3//1 4//1\n"),
    "pentagon.obj": b"v 0 0 1\nv 1 0 1\nv 1.5 1 1\nv 0.5 1.8 1\nv -0.5 1 1\nf 1 2 3 4 5\nl 1 2\np 3\n",
    "degenerate.obj": (b"v 0 0 0\nv 1 1 1\nv 2 2 2\nv 0 0 0.5\nv 1 0 0.5\nv 0 1 0.5\n"
                       b"f 1 2 3\nf 4 5 6\nf 4 5 6\nf 1 1 1\n"),
    "exponents.obj": b"v 1e-3 -2.5E+0 +3\nv 0 1 0\nv 1 0 0\nv 4e1 0 0\nf 1 3 4\nf 2 3 4\n",
}

SEED_RAYS = {
    "steps.rays": (b"# hand-checked rays for scenes/steps.obj\n0.25 0.25 5 0 0 -1\n1.5 0.5 5 0 0 -1\n"
                   b"3 3 5 0 0 -1\n\n0.25 0.25 5 0 0 -1 0 3\n0.3 0.2 5 0 0 -1 4.5 inf\n"
                   b"0x1p-2 0x1p-2 0x1.4p+2 0 0 -1\n-1 1 0 1 0 0\n0.5 1.5 -1 0 0 1\n1 1 5 0 0 -1\n"),
    "around.rays": (b"0 0 -5 0.1 0.1 1\n0.5 0.5 0.5 1 0 0\n-3 0.2 0.2 1 0.01 0\n0.2 -3 0.3 0 1 0 -inf inf\n"
                    b"0.1 0.1 10 -0.01 0 -1 1 1e30\n"),
    "one.rays": b"0.3 0.3 3 0 0 -1\n",
}

HUGE_NUMBERS = [b"1e38", b"3.4028235e38", b"3.5e38", b"-3.4e38", b"1e300", b"1e-45", b"1e-300", b"-0", b"0",
                b"0x1p127", b"0x1.fffffep+127", b"0x1p-149", b"1e39", b"123456789012345678901234567890", b"1e-38",
                b"16777217", b"0.1", b"-1e20", b"1e20"]
SPECIAL_NUMBERS = [b"nan", b"-nan", b"NaN", b"inf", b"-inf", b"INF", b"infinity", b"+inf", b"0x", b"1e", b"--1",
                   b"+-1", b"1.2.3", b"0x1p", b"1e+", b".", b"-", b"+", b"1,5"]
INDICES = [b"0", b"-1", b"-2", b"-100", b"-2147483648", b"-2147483649", b"2147483647", b"2147483648",
           b"4294967295", b"4294967296", b"99999999999999999999", b"1/", b"1//", b"/1", b"1/2/3/4", b"1/-1/1",
           b"1/0/1", b"1/99/1", b"+1", b"1.5", b"x"]
KEYWORDS = [b"v", b"f", b"vt", b"vn", b"vp", b"l", b"p", b"o", b"g", b"s", b"usemtl", b"mtllib", b"#", b"\\", b"f\t"]


def mutate(data, rng, kind=None):
    """One random mutation of `data` (bytes)."""
    lines = data.split(b"\n")
    kinds = ["flip", "bit", "truncate", "dup_line", "del_line", "swap_lines", "huge", "special", "index",
             "long_line", "empty", "garbage", "bom", "crlf", "nul", "many_corners", "keyword", "many_lines",
             "splice", "whitespace", "cr_only", "trailing", "extreme_value", "extreme_value", "far_triangle",
             "same_triangles"]
    kind = kind or rng.choice(kinds)
    if kind == "flip" and data:
        i = rng.randrange(len(data))
        return data[:i] + bytes([rng.randrange(256)]) + data[i + 1:]
    if kind == "bit" and data:
        i = rng.randrange(len(data))
        return data[:i] + bytes([data[i] ^ (1 << rng.randrange(8))]) + data[i + 1:]
    if kind == "truncate":
        return data[:rng.randrange(len(data) + 1)]
    if kind == "dup_line":
        i = rng.randrange(len(lines))
        return b"\n".join(lines[:i + 1] + [lines[i]] * rng.choice([1, 2, 10]) + lines[i + 1:])
    if kind == "del_line":
        i = rng.randrange(len(lines))
        return b"\n".join(lines[:i] + lines[i + 1:])
    if kind == "swap_lines" and len(lines) > 1:
        i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
        return b"\n".join(lines)
    if kind in ("huge", "special", "index", "keyword"):
        pool = {"huge": HUGE_NUMBERS, "special": SPECIAL_NUMBERS, "index": INDICES, "keyword": KEYWORDS}[kind]
        i = rng.randrange(len(lines))
        toks = lines[i].split(b" ")
        j = rng.randrange(len(toks))
        toks[j] = rng.choice(pool)
        lines[i] = b" ".join(toks)
        return b"\n".join(lines)
    if kind == "long_line":
        i = rng.randrange(len(lines))
        filler = rng.choice([b"1" * 100000, b" " * 100000, b"0.5 " * 30000, b"#" + b"x" * 200000,
                             b"f" + b" 1" * 20000, b"v" + b" 1" * 20000, b"1" * 400 + b"e-400"])
        lines.insert(i, filler)
        return b"\n".join(lines)
    if kind == "empty":
        return rng.choice([b"", b"\n", b"\n\n\n", b"   ", b"#", b"# only a comment\n"])
    if kind == "garbage":
        return bytes(rng.randrange(256) for _ in range(rng.randrange(1, 600)))
    if kind == "bom":
        return rng.choice([b"\xef\xbb\xbf", b"\xff\xfe", b"\xfe\xff"]) + data
    if kind == "crlf":
        return data.replace(b"\n", b"\r\n")
    if kind == "cr_only":
        return data.replace(b"\n", b"\r")
    if kind == "nul" and data:
        i = rng.randrange(len(data))
        return data[:i] + b"\0" + data[i:]
    if kind == "many_corners":
        n = rng.choice([4, 100, 254, 255, 256, 300, 1000])
        return data + b"\nf " + b" ".join(str(rng.randrange(1, 4)).encode() for _ in range(n)) + b"\n"
    if kind == "many_lines":
        i = rng.randrange(len(lines))
        return b"\n".join(lines[:i + 1] + [lines[i]] * 3000 + lines[i + 1:])
    if kind == "splice":
        other = rng.choice(list(SEED_OBJS.values()) + list(SEED_RAYS.values()))
        return data[:rng.randrange(len(data) + 1)] + other[rng.randrange(len(other) + 1):]
    if kind == "whitespace":
        return data.replace(b" ", rng.choice([b"\t", b"  ", b"\v", b"\f", b" \t "]))
    if kind == "extreme_value":
        # One number of a vertex or ray line: values that still parse (so the structures see them).
        numeric = [i for i, l in enumerate(lines) if l.split()[:1] == [b"v"] or
                   (l.split() and l.split()[0][:1] in b"-+0123456789.")]
        if numeric:
            i = rng.choice(numeric)
            toks = lines[i].split()
            j = rng.randrange(1 if toks[0] == b"v" else 0, len(toks))
            toks[j] = rng.choice([b"1e38", b"-3.4e38", b"3.4028234e38", b"1e-38", b"1e-45", b"-1e-45", b"1e30",
                                  b"-1e30", b"1e15", b"16777216.5", b"0", b"-0", b"0x1p-126", b"1e-30"])
            lines[i] = b" ".join(toks)
        return b"\n".join(lines)
    if kind == "far_triangle":
        far = rng.choice([b"1e30", b"-1e37", b"3e38", b"1e20", b"1e-30"])
        return data + b"\nv " + far + b" " + far + b" 0\nv 0 0 0\nv 1 0 0\nf -1 -2 -3\n"
    if kind == "same_triangles":
        return data + b"\nv 0.5 0.5 0.5\nv 0.6 0.5 0.5\nv 0.5 0.6 0.5\n" + b"f -1 -2 -3\n" * rng.choice([50, 700])
    if kind == "trailing":
        return data.rstrip(b"\n") + rng.choice([b"", b" ", b"\\", b"\n\n", b" \\\n"])
    return data


# ---------------------------------------------------------------------------------------
# The CLI's answer, judged


def ray_line_count(rays_bytes):
    """Ray lines as the CLI counts them (docs/hits.md): lines split at '\\n', C isspace()
    tokens, blank lines and lines whose first token starts with '#' skipped."""
    n = 0
    for line in rays_bytes.split(b"\n"):
        toks = line.split()  # bytes.split(): space, \t, \n, \r, \v, \f, as isspace() in the C locale
        if toks and not toks[0].startswith(b"#"):
            n += 1
    return n


def check_csv(path, expected_rows):
    """None when the file is a complete hits CSV of expected_rows rows, else what is wrong."""
    with open(path, "rb") as f:
        data = f.read()
    if not data.endswith(b"\n"):
        return "does not end in a newline (partial?)"
    lines = data.decode("ascii", "replace").split("\n")[:-1]
    if not lines or lines[0] != "ray,prim,t,u,v":
        return f"header {lines[:1]!r}"
    rows = lines[1:]
    if len(rows) != expected_rows:
        return f"{len(rows)} rows for {expected_rows} rays"
    for i, row in enumerate(rows):
        f = row.split(",")
        if len(f) != 5:
            return f"row {i}: {row!r}"
        try:
            ray, prim, t, u, v = int(f[0]), int(f[1]), float(f[2]), float(f[3]), float(f[4])
        except ValueError:
            return f"row {i}: {row!r} does not parse"
        if ray != i or prim < -1:
            return f"row {i}: {row!r}"
        if prim == -1 and (f[2] != "inf" or u != 0 or v != 0):
            return f"row {i}: a miss must be 'inf,0,0': {row!r}"
        if prim >= 0 and not (math.isfinite(t) and math.isfinite(u) and math.isfinite(v)):
            return f"row {i}: a hit with a non-finite value: {row!r}"
    return None


def judge(code, stderr, out, out_dir, before, expected_rows):
    """None when the run is one of the two allowed outcomes, else why not."""
    if code is None:
        return f"hang: no exit within {RUN_TIMEOUT} s"
    if code < 0:
        return f"killed by signal {-code}"
    if "Sanitizer" in stderr or "runtime error:" in stderr or "LeakSanitizer" in stderr:
        return "sanitizer report"
    left = sorted(set(os.listdir(out_dir)) - before - {os.path.basename(out)})
    if left:
        return f"files left behind: {left}"
    lines = stderr.splitlines()
    if code == 0:
        if not os.path.exists(out):
            return "exit 0 without an output file"
        if stderr:
            return f"exit 0 with stderr {stderr!r}"
        problem = check_csv(out, expected_rows)
        return f"exit 0, bad CSV: {problem}" if problem else None
    if code == 2:
        if os.path.exists(out):
            return "exit 2 but the output file exists"
        if len(lines) != 1 or not stderr.endswith("\n") or not lines[0].strip():
            return f"exit 2 with {len(lines)} stderr lines: {stderr[:2000]!r}"
        # One line for a terminal too: no control characters (a \v, an escape sequence) or
        # undecoded bytes quoted from the input, and short.
        if any(not (0x20 <= ord(c) < 0x7f) for c in lines[0]):
            return f"exit 2 with unprintable characters in the message: {stderr[:2000]!r}"
        if len(lines[0]) > 1000:
            return f"exit 2 with a message of {len(lines[0])} characters: {stderr[:300]!r}..."
        return None
    return f"exit code {code}"


class Fuzzer:
    def __init__(self, cli, work, seed):
        self.cli, self.work, self.seed = cli, work, seed
        self.structures = self.list_structures()
        self.case_dir = os.path.join(work, "case")
        self.failures_dir = os.path.join(work, "failures")
        os.makedirs(self.case_dir, exist_ok=True)
        self.failures = 0
        self.runs = 0
        self.outcomes = {0: 0, 2: 0}

    def list_structures(self):
        """Every structure, from `accelviz-cli params` (one unindented 'name: ...' line each)."""
        p = subprocess.run([self.cli, "params"], capture_output=True, text=True, timeout=60)
        names = [l.split(":")[0] for l in p.stdout.splitlines() if l and not l[0].isspace() and ":" in l]
        if p.returncode != 0 or not names:
            sys.exit(f"cannot list the structures: accelviz-cli params exit {p.returncode}: {p.stderr}")
        return names

    def run_pair(self, label, obj_bytes, rays_bytes, replay, threads="1", kernel="watertight"):
        """Runs trace for every structure on one scene/rays pair; True when all passed."""
        scene = os.path.join(self.case_dir, "scene.obj")
        rays = os.path.join(self.case_dir, "rays.txt")
        out = os.path.join(self.case_dir, "hits.csv")
        with open(scene, "wb") as f:
            f.write(obj_bytes)
        with open(rays, "wb") as f:
            f.write(rays_bytes)
        expected = ray_line_count(rays_bytes)
        ok = True
        for structure in self.structures:
            if os.path.exists(out):
                os.remove(out)
            before = set(os.listdir(self.case_dir))
            cmd = [self.cli, "trace", "--scene", scene, "--structure", structure, "--rays", rays, "--out", out,
                   "--threads", threads, "--kernel", kernel]
            try:
                p = subprocess.run(cmd, capture_output=True, timeout=RUN_TIMEOUT)
                code, stderr = p.returncode, p.stderr.decode("utf-8", "replace")
            except subprocess.TimeoutExpired as e:
                code, stderr = None, (e.stderr or b"").decode("utf-8", "replace")
            self.runs += 1
            if code in self.outcomes:
                self.outcomes[code] += 1
            problem = judge(code, stderr, out, self.case_dir, before, expected)
            if problem:
                ok = False
                self.report(label, structure, cmd, problem, stderr, obj_bytes, rays_bytes, replay)
        return ok

    def report(self, label, structure, cmd, problem, stderr, obj_bytes, rays_bytes, replay):
        self.failures += 1
        d = os.path.join(self.failures_dir, f"{label}_{structure}".replace("/", "_"))
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "scene.obj"), "wb") as f:
            f.write(obj_bytes)
        with open(os.path.join(d, "rays.txt"), "wb") as f:
            f.write(rays_bytes)
        with open(os.path.join(d, "stderr.txt"), "w") as f:
            f.write(stderr)
        print(f"FAIL {label} structure={structure}: {problem}")
        print(f"  input saved in {d}/ (scene.obj, rays.txt, stderr.txt)")
        print(f"  command: {' '.join(cmd)}")
        print(f"  replay: {replay}")
        if stderr:
            print("  stderr: " + stderr[:1500].replace("\n", "\n          "))

    def make_case(self, k):
        """Case k of this seed: a mutated scene/rays pair (its own RNG, so it never depends on
        the cases before it)."""
        rng = random.Random(f"{self.seed}:{k}")
        obj_name = rng.choice(sorted(self.seed_objs))
        rays_name = rng.choice(sorted(SEED_RAYS))
        obj, rays = self.seed_objs[obj_name], SEED_RAYS[rays_name]
        target = rng.choice(["obj", "rays", "both"])
        kinds = []
        for _ in range(rng.choice([1, 1, 2, 3])):
            if target in ("obj", "both"):
                obj = mutate(obj, rng)
            if target in ("rays", "both"):
                rays = mutate(rays, rng)
        threads = rng.choice(["1", "1", "1", "2"])
        kernel = rng.choice(["watertight", "watertight", "watertight", "moller", "double"])
        return f"{obj_name}+{rays_name}/{target}", obj, rays, threads, kernel

    def replay_regressions(self, regressions_dir, default_obj, default_rays):
        """Every file of regressions_dir: NAME.obj (with NAME.rays, else the default rays),
        NAME.rays (with NAME.obj, else steps.obj)."""
        if not os.path.isdir(regressions_dir):
            return 0
        stems = sorted({os.path.splitext(n)[0] for n in os.listdir(regressions_dir)
                        if n.endswith((".obj", ".rays"))})
        for stem in stems:
            def read(ext, default):
                path = os.path.join(regressions_dir, stem + ext)
                if not os.path.exists(path):
                    return default
                with open(path, "rb") as f:
                    return f.read()
            for kernel in ("watertight", "moller", "double"):
                self.run_pair(f"regression_{stem}_{kernel}", read(".obj", default_obj), read(".rays", default_rays),
                              f"the regression {regressions_dir}/{stem}.*", threads="2", kernel=kernel)
        return len(stems)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", help="accelviz-cli to fuzz (ACCEL_FUZZ_CLI overrides)")
    ap.add_argument("--source", required=True, help="the repository (scenes/, tests/cli/regressions/)")
    ap.add_argument("--work", required=True, help="scratch directory; failing inputs go to WORK/failures/")
    ap.add_argument("--seconds", type=float, default=60.0, help="start no new case after this many seconds")
    ap.add_argument("--seed", type=int, default=16)
    ap.add_argument("--case", type=int, help="run only this case of the seed")
    a = ap.parse_args()
    cli = os.environ.get("ACCEL_FUZZ_CLI") or a.cli
    if not cli:
        sys.exit("no CLI: pass --cli or set ACCEL_FUZZ_CLI")
    seconds = float(os.environ.get("ACCEL_FUZZ_SECONDS", a.seconds))
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    fz = Fuzzer(cli, a.work, a.seed)
    with open(os.path.join(a.source, "scenes", "steps.obj"), "rb") as f:
        steps = f.read()
    fz.seed_objs = dict(SEED_OBJS, **{"steps.obj": steps})
    print(f"fuzz_cli: {cli}, seed {a.seed}, {seconds:g} s, structures {','.join(fz.structures)}")
    start = time.monotonic()

    if a.case is not None:
        label, obj, rays, threads, kernel = fz.make_case(a.case)
        fz.run_pair(f"case{a.case}", obj, rays, f"--seed {a.seed} --case {a.case}", threads, kernel)
        print(f"{'FAILED' if fz.failures else 'OK'}: case {a.case} ({label})")
        return 1 if fz.failures else 0

    regressions = fz.replay_regressions(os.path.join(a.source, "tests", "cli", "regressions"), steps,
                                        SEED_RAYS["steps.rays"])
    # The seeds themselves must trace cleanly (exit 0 with a complete CSV).
    rejected = fz.outcomes[2]
    for obj_name in sorted(fz.seed_objs):
        for rays_name in sorted(SEED_RAYS):
            fz.run_pair(f"seed_{obj_name}+{rays_name}", fz.seed_objs[obj_name], SEED_RAYS[rays_name], "the seeds")
    if fz.outcomes[2] != rejected:
        print("FAIL: a seed input was rejected (exit 2): the seeds must be valid")
        fz.failures += 1
    k = 0
    while time.monotonic() - start < seconds and fz.failures < 20:
        label, obj, rays, threads, kernel = fz.make_case(k)
        fz.run_pair(f"case{k}", obj, rays, f"--seed {a.seed} --case {k}", threads, kernel)
        k += 1
    took = time.monotonic() - start
    print(f"fuzz_cli: {regressions} regressions, {k} cases, {fz.runs} runs ({fz.outcomes[0]} exit 0, "
          f"{fz.outcomes[2]} exit 2) in {took:.1f} s, seed {a.seed}")
    print(f"{'FAILED' if fz.failures else 'OK'}: {fz.failures} failures"
          + (f" (inputs in {fz.failures_dir})" if fz.failures else ""))
    return 1 if fz.failures else 0


if __name__ == "__main__":
    sys.exit(main())
