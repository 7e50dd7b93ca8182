#!/usr/bin/env python3
"""Faults around accelviz-cli (issue #16): outputs it cannot write (an unwritable or
read-only directory, a path under a regular file, /dev/full, a full tmpfs, a FIFO without a
reader), inputs that are FIFOs (growing while read, truncated, never written) and SIGINT /
SIGTERM during long runs. Every case: the documented exit code (2 for a fault, 130/143 for
a signal), one line on stderr (bench's progress lines aside) naming the path, and nothing
left behind: no output file and no temporary file (the directory is listed before and
after)."""
import argparse
import os
import random
import re
import shutil
import signal
import stat
import subprocess
import sys
import threading
import time

FAILURES = []
TIMEOUT = 60  # seconds any one run may take: a hang fails instead of blocking the test
PROGRESS = re.compile(r"^\[[# ]*\] \d+/\d+ ")  # bench's progress lines on stderr


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)
    return cond


def run(cmd, timeout=TIMEOUT, **kw):
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, **kw)
    except subprocess.TimeoutExpired:
        check(False, f"{cmd}: still running after {timeout} s (a hang)")
        return None, "", ""
    return p.returncode, p.stdout, p.stderr


def message_lines(stderr):
    """stderr's lines without bench's progress lines."""
    return [l for l in stderr.splitlines() if l.strip() and not PROGRESS.match(l)]


def expect_fault(what, result, must_contain, code_expected=2):
    """Exit `code_expected`, exactly one message line, containing every string of must_contain."""
    code, _, err = result
    lines = message_lines(err)
    check(code == code_expected, f"{what}: exit {code}, expected {code_expected}; stderr {err!r}")
    check(len(lines) == 1, f"{what}: expected one message line, got {lines!r}")
    for s in must_contain:
        check(s in err, f"{what}: message {err!r} lacks {s!r}")
    check("Sanitizer" not in err and "runtime error" not in err, f"{what}: sanitizer report {err!r}")


def listing(d):
    return sorted(os.listdir(d)) if os.path.isdir(d) else None


class Ctx:
    def __init__(self, cli, source, work):
        self.cli, self.source, self.work = cli, source, work
        self.steps = os.path.join(source, "scenes", "steps.obj")
        self.rays = os.path.join(work, "rays.txt")
        with open(self.rays, "w") as f:
            f.write("# steps.obj rays\n0.25 0.25 5 0 0 -1\n1.5 0.5 5 0 0 -1\n3 3 5 0 0 -1\n0.5 1.5 -1 0 0 1\n")
        self.root = os.geteuid() == 0

    def trace(self, out, rays=None, scene=None, *extra):
        return [self.cli, "trace", "--scene", scene or self.steps, "--rays", rays or self.rays, "--out", out, *extra]

    def bench(self, *extra):
        return [self.cli, "bench", "--scene", self.steps, "--structures", "grid", "--rays", "random:50:1",
                "--min-time", "0.001", "--no-embree", "--no-tinybvh", *extra]

    def stats(self, *extra):
        return [self.cli, "stats", "--scene", self.steps, "--structure", "bvh", *extra]

    def writers(self, out):
        """(name, command) of every subcommand that writes a file, all writing `out`."""
        return [("trace --out", self.trace(out)),
                ("bench --out-json", self.bench("--out-json", out)),
                ("bench --out-csv", self.bench("--out-csv", out)),
                ("bench --out-md", self.bench("--out-md", out)),
                ("stats --build-trace", self.stats("--build-trace", out))]


# ---------------------------------------------------------------------------------------
# Outputs that cannot be written


def private_mount_shell(mount_args, script):
    """The command running `script` (sh) after `mount mount_args` in a private mount
    namespace (root, or an unprivileged user namespace), or None when that is not possible
    here."""
    for prefix in (["unshare", "--mount", "--propagation", "private"],
                   ["unshare", "--user", "--map-root-user", "--mount", "--propagation", "private"]):
        if shutil.which("unshare") is None:
            return None
        probe = subprocess.run(prefix + ["sh", "-c", "mount " + mount_args + " && echo mounted"],
                               capture_output=True, text=True, timeout=30)
        if probe.returncode == 0 and "mounted" in probe.stdout:
            return prefix + ["sh", "-c", "mount " + mount_args + " || exit 99\n" + script]
    return None


def test_unwritable_dir(ctx):
    """An output directory the CLI may not write into: exit 2, one line naming the output,
    nothing created there. chmod 0555 for a normal user; root ignores permissions, so it gets
    a read-only mount (when a private mount namespace is possible) instead."""
    d = os.path.join(ctx.work, "readonly")
    os.makedirs(d)
    out = os.path.join(d, "out.csv")
    if not ctx.root:
        os.chmod(d, 0o555)
        try:
            for name, cmd in ctx.writers(out):
                before = listing(d)
                expect_fault(f"{name} into a 0555 directory", run(cmd), [out, "Permission denied"])
                check(listing(d) == before, f"{name}: 0555 directory now holds {listing(d)}")
        finally:
            os.chmod(d, 0o755)
        return
    print("root: chmod 0555 does not stop root; a read-only tmpfs stands in")
    for name, cmd in ctx.writers(out):
        script = " ".join(f"'{c}'" for c in cmd) + " 2>&1; rc=$?; echo; echo LISTING; ls -A '" + d + "'; exit $rc"
        shell = private_mount_shell(f"-t tmpfs -o ro,size=64k tmpfs '{d}'", script)
        if shell is None:
            print("SKIP: no private mount namespace here (read-only directory case)")
            return
        code, stdout, _ = run(shell)
        err, _, left = stdout.partition("\nLISTING\n")
        expect_fault(f"{name} into a read-only directory", (code, "", err), [out, "Read-only file system"])
        check(left.split() == [], f"{name}: read-only directory now holds {left.split()}")


def test_paths_that_fail_for_everyone(ctx):
    """Paths no one can create, root included: under a regular file, under /proc, a
    directory as the output, a missing directory."""
    regular = os.path.join(ctx.work, "regular_file")
    with open(regular, "w") as f:
        f.write("not a directory\n")
    cases = [(os.path.join(regular, "out.csv"), "Not a directory"),
             ("/proc/accelviz-faults/out.csv", "No such file or directory"),
             (os.path.join(ctx.work, "no_such_dir", "out.csv"), "No such file or directory"),
             (ctx.work, "Is a directory")]
    for out, reason in cases:
        for name, cmd in ctx.writers(out):
            before = listing(ctx.work)
            expect_fault(f"{name} {out}", run(cmd), [out, reason])
            check(listing(ctx.work) == before, f"{name} {out}: work dir changed: {listing(ctx.work)}")
    with open(regular) as f:
        check(f.read() == "not a directory\n", "the regular file was changed")


def test_dev_full(ctx):
    """/dev/full: every write fails with ENOSPC. Exit 2, one line naming the path and the
    reason; /dev stays as it was (no temporary file beside the device, the device not
    replaced)."""
    if not os.path.exists("/dev/full"):
        print("SKIP: no /dev/full")
        return
    for name, cmd in ctx.writers("/dev/full") + [("stats > /dev/full", ctx.stats())]:
        before = listing("/dev")
        if name.startswith("stats >"):
            with open("/dev/full", "w") as full:
                p = subprocess.run(cmd, stdout=full, stderr=subprocess.PIPE, text=True, timeout=TIMEOUT)
            result = (p.returncode, "", p.stderr)
            expect_fault(name, result, ["standard output", "No space left on device"])
        else:
            expect_fault(f"{name} /dev/full", run(cmd), ["/dev/full", "No space left on device"])
        check(listing("/dev") == before, f"{name}: /dev changed: {set(listing('/dev')) ^ set(before)}")
        check(stat.S_ISCHR(os.stat("/dev/full").st_mode), f"{name}: /dev/full is no longer a device")


def test_full_tmpfs(ctx):
    """A real full disk: a 64 KiB tmpfs (private mount namespace) and a CSV of 20000 rows.
    The partial temporary file must be gone afterwards."""
    d = os.path.join(ctx.work, "small_disk")
    os.makedirs(d)
    out = os.path.join(d, "hits.csv")
    cmds = [("trace --out", ctx.trace(out, "random:20000:1")),
            ("bench --out-json", [ctx.cli, "bench", "--scene", "procedural:cornell", "--structures", "all", "--kernel",
                                  "watertight,moller,double", "--rays", "random:20:1", "--min-time", "0.001",
                                  "--no-embree", "--no-tinybvh", "--out-json", out])]
    for name, cmd in cmds:
        # The bench JSON is about 10 KB: fill the disk to 4 KB from full first.
        script = ("head -c 60000 /dev/zero > '" + d + "/filler' 2>/dev/null; " +
                  " ".join(f"'{c}'" for c in cmd) + " 2>&1 >/dev/null; rc=$?; echo; echo LISTING; ls -A '" + d +
                  "'; exit $rc")
        shell = private_mount_shell(f"-t tmpfs -o size=64k tmpfs '{d}'", script)
        if shell is None:
            print("SKIP: no private mount namespace here (full tmpfs case; /dev/full covers the error)")
            return
        code, stdout, _ = run(shell)
        err, _, left = stdout.partition("\nLISTING\n")
        expect_fault(f"{name} on a full tmpfs", (code, "", err), [out, "No space left on device"])
        check(left.split() == ["filler"], f"{name}: full tmpfs holds {left.split()} (a temporary file left?)")


def test_fifo_output(ctx):
    """--out a FIFO: without a reader a clean error (no wait); with one, the reader gets the CSV."""
    fifo = os.path.join(ctx.work, "out.fifo")
    os.mkfifo(fifo)
    expect_fault("trace --out FIFO without a reader", run(ctx.trace(fifo)), [fifo, "No such device or address"])
    got = []
    # Opened for reading first (O_NONBLOCK: without waiting for a writer), so the CLI finds a
    # reader; the CSV (5 lines) fits the pipe's buffer, and the reader drains it afterwards.
    fd = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)

    def reader():
        os.set_blocking(fd, True)
        chunks = []
        while True:
            b = os.read(fd, 65536)
            if not b:
                break
            chunks.append(b)
        got.append(b"".join(chunks).decode())

    t = threading.Thread(target=reader, daemon=True)
    code, _, err = run(ctx.trace(fifo))
    t.start()
    t.join(10)
    os.close(fd)
    check(code == 0, f"trace --out FIFO with a reader: exit {code}, {err!r}")
    check(got and got[0].startswith("ray,prim,t,u,v\n") and got[0].count("\n") == 5,
          f"trace --out FIFO: reader got {got!r}")
    os.remove(fifo)


# ---------------------------------------------------------------------------------------
# Inputs that are FIFOs


def feed_fifo(path, chunks, pause, close=True):
    """A thread that opens the FIFO for writing, writes the chunks with pauses, then closes
    it. Opening blocks until the CLI opens the FIFO for reading."""
    def writer():
        try:
            with open(path, "wb") as f:
                for c in chunks:
                    f.write(c)
                    f.flush()
                    time.sleep(pause)
        except BrokenPipeError:
            pass
    t = threading.Thread(target=writer, daemon=True)
    t.start()
    return t


def split_bytes(data, n, rng):
    cuts = sorted(rng.sample(range(1, len(data)), n - 1))
    return [data[a:b] for a, b in zip([0] + cuts, cuts + [len(data)])]


def test_fifo_inputs(ctx):
    rng = random.Random(16)
    lines = ["# rays that grow while they are read"]
    for _ in range(300):
        lines.append(" ".join(f"{rng.uniform(-0.5, 2.5):.6g}" for _ in range(2)) + " 5 " +
                     " ".join(f"{rng.uniform(-0.2, 0.2):.4g}" for _ in range(2)) + " -1")
    text = ("\n".join(lines) + "\n").encode()
    regular = os.path.join(ctx.work, "grow_rays.txt")
    with open(regular, "wb") as f:
        f.write(text)
    ref_out = os.path.join(ctx.work, "grow_ref.csv")
    code, _, err = run(ctx.trace(ref_out, regular))
    if not check(code == 0, f"trace of the regular rays file: exit {code} {err!r}"):
        return
    with open(ref_out) as f:
        reference = f.read()
    # (a) the rays arrive in pieces cut anywhere (mid-number, mid-line) with pauses.
    fifo = os.path.join(ctx.work, "rays.fifo")
    os.mkfifo(fifo)
    out = os.path.join(ctx.work, "grow_fifo.csv")
    t = feed_fifo(fifo, split_bytes(text, 7, rng), 0.3)
    code, _, err = run(ctx.trace(out, fifo), timeout=30)
    t.join(5)
    check(code == 0, f"trace of a growing FIFO: exit {code} {err!r}")
    if code == 0:
        with open(out) as f:
            check(f.read() == reference, "trace of a growing FIFO: CSV differs from the regular file's")
    # (b) half a line, then the writer closes.
    out = os.path.join(ctx.work, "trunc_fifo.csv")
    t = feed_fifo(fifo, [b"0.25 0.25 5 0 0 -1\n", b"1.5 0.5 5 0 0"], 0.3)
    result = run(ctx.trace(out, fifo), timeout=30)
    t.join(5)
    expect_fault("truncated FIFO", result, [f"{fifo}:2:"])
    check(not os.path.exists(out), "truncated FIFO: output file written")
    # Half a number: a dangling "-" is malformed, not a shorter ray.
    t = feed_fifo(fifo, [b"0.25 0.25 5 0 0 -"], 0.1)
    result = run(ctx.trace(out, fifo), timeout=30)
    t.join(5)
    expect_fault("FIFO cut mid-number", result, [f"{fifo}:1:"])
    check(not os.path.exists(out), "FIFO cut mid-number: output file written")
    # (c) the scene itself through a FIFO, in pieces.
    scene_fifo = os.path.join(ctx.work, "scene.obj")
    os.mkfifo(scene_fifo)
    with open(ctx.steps, "rb") as f:
        obj = f.read()
    out = os.path.join(ctx.work, "scene_fifo.csv")
    t = feed_fifo(scene_fifo, split_bytes(obj, 4, rng), 0.2)
    code, _, err = run(ctx.trace(out, regular, scene_fifo), timeout=30)
    t.join(5)
    check(code == 0, f"trace with the scene from a FIFO: exit {code} {err!r}")
    if code == 0:
        with open(out) as f:
            check(f.read() == reference, "scene from a FIFO: CSV differs from the regular file's")
    # (d) a FIFO nobody ever writes: the CLI waits (as cat would), but SIGINT ends it at once.
    out = os.path.join(ctx.work, "never.csv")
    before = listing(ctx.work)
    p = subprocess.Popen(ctx.trace(out, fifo), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)
    check(p.poll() is None, "FIFO without a writer: the CLI did not wait for it")
    interrupt_and_check("trace blocked on a FIFO", p, signal.SIGINT, ctx.work, before)
    os.remove(fifo)
    os.remove(scene_fifo)


# ---------------------------------------------------------------------------------------
# Signals during long runs


def interrupt_and_check(what, p, sig, out_dir, before, allow_progress=False):
    """Sends `sig` to the running CLI `p`; it must stop within 10 s with 128 + sig, one line
    'accelviz-cli: interrupted (SIG...)', and `out_dir` as it was."""
    running = p.poll() is None
    check(running, f"{what}: finished before the signal (the run is too short to test it)")
    sent = time.monotonic()
    p.send_signal(sig)
    try:
        _, err = p.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        p.kill()
        _, err = p.communicate()
        check(False, f"{what}: still running 10 s after {sig.name}")
        return
    took = time.monotonic() - sent
    name = "SIGINT" if sig == signal.SIGINT else "SIGTERM"
    lines = message_lines(err) if allow_progress else [l for l in err.splitlines() if l.strip()]
    if running:
        check(p.returncode == 128 + sig, f"{what}: exit {p.returncode} after {name}, expected {128 + sig}; {err!r}")
        check(lines == [f"accelviz-cli: interrupted ({name})"], f"{what}: stderr {lines!r}")
    check(listing(out_dir) == before, f"{what}: left {sorted(set(listing(out_dir)) - set(before))} behind")
    print(f"{what}: {name} -> exit {p.returncode} in {took:.2f} s")


def long_soup_obj(path, n=100000):
    """Big overlapping random triangles: the kd-tree's SAH build takes seconds."""
    rng = random.Random(7)
    with open(path, "w") as f:
        for _ in range(n):
            c = [rng.random() * 100 for _ in range(3)]
            for _ in range(3):
                f.write("v %.3f %.3f %.3f\n" % tuple(x + rng.random() * 20 for x in c))
        for i in range(n):
            f.write(f"f {3 * i + 1} {3 * i + 2} {3 * i + 3}\n")


def test_signals(ctx):
    d = os.path.join(ctx.work, "signals")
    os.makedirs(d)
    # trace: 200000 rays through brute force on the 20624-triangle stadium, 2 threads (~30 s).
    for sig in (signal.SIGINT, signal.SIGTERM):
        before = listing(d)
        p = subprocess.Popen([ctx.cli, "trace", "--scene", "procedural:stadium", "--structure", "brute", "--rays",
                              "random:200000:1", "--threads", "2", "--out", os.path.join(d, "hits.csv")],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(1.5)
        interrupt_and_check("long trace", p, sig, d, before)
    # bench: one structure, timing samples of 10 s each; signals at 1.5 s (the reference
    # queries) and 4 s (the timing loop).
    for sig, delay in ((signal.SIGINT, 1.5), (signal.SIGINT, 4.0), (signal.SIGTERM, 2.5)):
        before = listing(d)
        p = subprocess.Popen([ctx.cli, "bench", "--scene", "procedural:stadium", "--structures", "bvh", "--rays",
                              "random:200000:1", "--threads", "2", "--min-time", "10", "--no-embree", "--no-tinybvh",
                              "--out-json", os.path.join(d, "b.json"), "--out-csv", os.path.join(d, "b.csv"),
                              "--out-md", os.path.join(d, "b.md")],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(delay)
        interrupt_and_check(f"long bench (signal at {delay} s)", p, sig, d, before, allow_progress=True)
    # A build: the kd-tree over big overlapping triangles (~10 s), with --build-trace.
    soup = os.path.join(ctx.work, "soup.obj")
    long_soup_obj(soup)
    before = listing(d)
    p = subprocess.Popen([ctx.cli, "stats", "--scene", soup, "--structure", "kdtree", "--build-trace",
                          os.path.join(d, "build.jsonl")], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(2.0)
    interrupt_and_check("long kd-tree build", p, signal.SIGINT, d, before)
    before = listing(d)
    p = subprocess.Popen([ctx.cli, "trace", "--scene", soup, "--structure", "kdtree", "--rays", "random:100:1",
                          "--out", os.path.join(d, "soup.csv")], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    time.sleep(2.0)
    interrupt_and_check("trace during its kd-tree build", p, signal.SIGTERM, d, before)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    ctx = Ctx(a.cli, a.source, a.work)
    start = time.monotonic()
    for test in (test_unwritable_dir, test_paths_that_fail_for_everyone, test_dev_full, test_full_tmpfs,
                 test_fifo_output, test_fifo_inputs, test_signals):
        t0 = time.monotonic()
        test(ctx)
        print(f"{test.__name__}: {time.monotonic() - t0:.1f} s")
    print(f"{'FAILED' if FAILURES else 'OK'}: {len(FAILURES)} failures in {time.monotonic() - start:.1f} s")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
