#!/usr/bin/env python3
"""The judge against hostile submissions (issue #48), through `accelviz-cli grade-class`: a class
of the lecturer's solutions, the worked example, a planted bug and every submission of
tests/student/hostile/ is graded in the sandbox. Asserts that

- every hostile submission fails, each with what happened named where it can be (an exit, the
  time limit, the output limit, a compile error), and the judge lives and writes its reports;
- nothing was written outside the sandbox, no connection arrived, no secret reached a report;
- the example and the solutions pass, and the planted bug is caught with its trap;
- the class report holds every student (HTML, CSV, JSON), and a second run reuses the
  unchanged reports while a changed submission is graded again;
- `check --submission` quotes what a submission printed, never as the judge's words, and
  writes Gradescope's and PrairieLearn's results.

    python3 tests/student/test_hostile.py --cli build/bin/accelviz-cli --work /tmp/hostile
"""
import argparse
import csv
import json
import os
import secrets
import shutil
import socket
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(HERE, "..", "app"))
from viewer_harness import FAILURES, check, run  # noqa: E402

PORT = 47321  # tests/student/hostile/socket: the port it tries when no variable says otherwise
# Where the hostile submissions write when nothing stops them (hostile/README.md).
MARKERS = ["/tmp/accelviz-hostile-wrote.txt", "/var/tmp/accelviz-hostile-wrote.txt", "/tmp/report.json",
           os.path.expanduser("~/accelviz-hostile-wrote.txt"), os.path.expanduser("~/report.json")]
SECRET_FILE = "/tmp/accelviz-hostile-secret.txt"


class Listener:
    """TCP and UDP on 127.0.0.1:PORT, noting whatever arrives."""

    def __init__(self):
        self.arrived = []
        self.ok = True
        try:
            self.tcp = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            self.tcp.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            self.tcp.bind(("127.0.0.1", PORT))
            self.tcp.listen(8)
            self.tcp.settimeout(0.2)
            self.udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            self.udp.bind(("127.0.0.1", PORT))
            self.udp.settimeout(0.2)
        except OSError as e:
            print(f"port {PORT} is taken ({e}): the socket attack is not watched")
            self.ok = False
            return
        self.stop = False
        self.thread = threading.Thread(target=self.loop, daemon=True)
        self.thread.start()

    def loop(self):
        while not self.stop:
            try:
                conn, _ = self.tcp.accept()
                self.arrived.append("tcp")
                conn.close()
            except OSError:
                pass
            try:
                self.udp.recvfrom(100)
                self.arrived.append("udp")
            except OSError:
                pass

    def close(self):
        if self.ok:
            self.stop = True
            self.thread.join()
            self.tcp.close()
            self.udp.close()


def all_text(folder):
    """Every file under `folder`, as bytes, joined."""
    out = b""
    for dirpath, _, files in os.walk(folder):
        for f in files:
            with open(os.path.join(dirpath, f), "rb") as fh:
                out += fh.read()
    return out


def structure(record):
    return record["structures"][0] if record.get("structures") else {}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    no_sandbox = ["--no-sandbox"] if os.environ.get("ACCEL_TEST_NO_SANDBOX") else []
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    subs, out = os.path.join(args.work, "class"), os.path.join(args.work, "out")
    code, said, err = run([sys.executable, os.path.join(ROOT, "scripts", "make_class.py"), subs, "--students", "7",
                           "--hostile"])
    check(code == 0, f"make_class.py: {said} {err}")
    # The planted bug, beside the solutions: alan_sol_grid ... grace_bug_grid_tie is the 7th.
    # The lecturer's files: readable by their owner only, as a grading machine keeps them.
    # Without the sandbox that is what keeps them from the student's code (run as nobody).
    secret = "accelviz-secret-" + secrets.token_hex(8)
    for path in (SECRET_FILE, os.path.join(args.work, "secret.txt")):  # ../secret.txt from the class folder
        with open(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600), "w") as f:
            f.write(secret)
    for m in MARKERS:
        if os.path.exists(m):
            os.remove(m)
    listener = Listener()
    start = time.monotonic()
    try:
        code, said, err = run([args.cli, "grade-class", subs, "--out", out, "--ray-scale", "0.02", "--timeout", "20",
                               "--no-time", *no_sandbox], timeout=900, cwd=args.work)
    finally:
        listener.close()
    seconds = time.monotonic() - start
    print(f"grade-class: exit {code} in {seconds:.0f} s: {said.strip()}")
    check(code == 0, f"grade-class: exit {code}: {err[-2000:]}")
    cls = json.load(open(os.path.join(out, "class.json")))
    records = {r["student"]: r for r in cls["students"]}
    check(sorted(records) == sorted(os.listdir(subs)), f"class.json students {sorted(records)}")

    # The attacks.
    check(listener.arrived == [], f"a connection reached 127.0.0.1:{PORT}: {listener.arrived}")
    for m in MARKERS:
        # Without the sandbox the student's code sees the machine's files: it may write where
        # anyone may (/tmp), never where only the grader may.
        shared = no_sandbox and m.startswith(("/tmp/", "/var/tmp/")) and os.geteuid() == 0
        check(shared or not os.path.exists(m), f"a hostile submission wrote {m}")
        if shared and os.path.exists(m):
            os.remove(m)
    for f in os.listdir(args.work):
        check(f in ("class", "out", "secret.txt"), f"a hostile submission wrote {os.path.join(args.work, f)}")
    check(secret.encode() not in all_text(out) + said.encode() + err.encode(), "the secret reached a report")
    os.remove(SECRET_FILE)

    def hostile(name):
        return records.get("hostile_" + name, {})

    for name in [n for n in os.listdir(os.path.join(HERE, "hostile")) if os.path.isdir(os.path.join(HERE, "hostile", n))]:
        r = hostile(name)
        check(r and not r["passed"], f"hostile {name}: not graded as failed: {json.dumps(r)[:500]}")
    expect_failure = {
        "exit_static": "exited with code 0",
        "exit_build": "exited with code 0",
        "exit_intersect": "exited with code 0",
        "sleep_build": "no answer within the time limit",
        "flood_output": "printed more than",
        "forge_channel": "broke the kit's channel",
    }
    for name, text in expect_failure.items():
        failure = structure(hostile(name)).get("failure", "")
        check(text in failure, f"hostile {name}: failure {failure!r}, expected {text!r}")
    # A build log without end: stopped by the judge's own bound on what it mirrors.
    flood = structure(hostile("flood_log"))
    check(any("the kit keeps at most that many" in f for f in flood.get("faults", [])) or
          "no answer within the time limit" in flood.get("failure", ""),
          f"hostile flood_log: {json.dumps(flood)[:600]}")
    core = hostile("core_headers").get("compile", {})
    check(not core.get("ok", True) and "structures/kd_tree.h" in core.get("error", ""),
          f"hostile core_headers: compiled, or no error naming the header: {core}")
    fork = structure(hostile("fork_bomb"))
    check(any("forked 0 children" in f for f in fork.get("faults", [])), f"hostile fork_bomb forked: {fork.get('faults')}")
    for name in ("forged_report", "fake_stdout", "const_cast_scene", "socket", "write_outside", "kill_parent"):
        s = structure(hostile(name))
        check(s.get("wrong", 0) > 0 and not s.get("failure"), f"hostile {name}: expected false misses: {json.dumps(s)[:300]}")
    fake = structure(hostile("fake_stdout"))
    check("PASSED" in fake.get("output", ""), f"fake_stdout's output was not kept for the report: {fake.get('output')!r}")

    # The honest submissions.
    for student, r in records.items():
        if "_sol_" in student or student.endswith("_example"):
            check(r["passed"], f"{student}: expected to pass: {json.dumps(r)[:600]}")
    bug = next((r for s, r in records.items() if s.endswith("_bug_grid_tie")), None)
    check(bug and not bug["passed"] and any(c["name"] == "hard" and sum(c["wrong"].values())
                                            for c in structure(bug).get("categories", [])),
          f"the planted bug was not caught on the hard cases: {json.dumps(bug)[:600]}")

    # The class report.
    html = open(os.path.join(out, "class.html"), encoding="utf-8").read()
    for section in ("Students", "traps", "Speed", "Faults"):
        check(section in html, f"class.html has no {section!r} section")
    for student in records:
        check(student in html, f"class.html does not name {student}")
    rows = list(csv.DictReader(open(os.path.join(out, "class.csv"), newline="")))
    check(len(rows) == len(records) and {r["student"] for r in rows} == set(records)
          and all(r["passed"] in ("passed", "failed", "true", "false", "yes", "no", "1", "0") for r in rows),
          f"class.csv: {rows[:2]}")

    # Again: nothing changed, nothing graded; one file changed, that one graded again.
    changed = next(s for s in records if s.endswith("_example"))
    with open(os.path.join(subs, changed, "median_bvh.cpp"), "a") as f:
        f.write("\n// changed\n")
    start = time.monotonic()
    code, said, err = run([args.cli, "grade-class", subs, "--out", out, "--ray-scale", "0.02", "--timeout", "20",
                           "--no-time", *no_sandbox], timeout=600, cwd=args.work)
    again = {r["student"]: r for r in json.load(open(os.path.join(out, "class.json")))["students"]}
    reused = sorted(s for s, r in again.items() if r.get("skipped_unchanged"))
    print(f"second run: {time.monotonic() - start:.1f} s, {len(reused)} of {len(again)} reports reused")
    check(code == 0 and changed not in reused and len(reused) == len(again) - 1,
          f"second run: exit {code}, reused {reused} (changed: {changed})")

    # No sandbox to be had (a bubblewrap that cannot make namespaces, as in a container that
    # forbids them): one line, exit 3, nothing graded.
    if not no_sandbox:
        fake = os.path.join(args.work, "bwrap-without-namespaces")
        with open(fake, "w") as f:
            f.write("#!/bin/sh\necho 'bwrap: No permissions to create new namespace' >&2\nexit 1\n")
        os.chmod(fake, 0o755)
        env = dict(os.environ, ACCELVIZ_BWRAP=fake)
        for cmd in (["check", "--submission", os.path.join(subs, changed)], ["grade-class", subs, "--out", out]):
            code, said, err = run([args.cli, *cmd], env=env, cwd=args.work)
            check(code == 3 and len(err.strip().splitlines()) == 1 and "refusing to grade" in err and not said,
                  f"{cmd[0]} without a sandbox: exit {code}, stdout {said[-300:]!r}, stderr {err!r}")

    # check --submission: the printed output quoted; the platforms' result files.
    fake_dir = os.path.join(subs, "hostile_fake_stdout")
    code, said, err = run([args.cli, "check", "--submission", fake_dir, "--ray-scale", "0.02", "--no-time",
                           "--out-dir", os.path.join(args.work, "check"), *no_sandbox], cwd=args.work)
    judged = [l for l in said.splitlines() if "PASSED" in l and not l.startswith("  | ")]
    check(code == 1 and not judged and "hostile_fake_stdout: FAILED" in said,
          f"check --submission fake_stdout: exit {code}, unquoted PASSED lines {judged}: {said[-800:]}")
    for fmt, key in (("gradescope", "tests"), ("prairielearn", "score")):
        code, said, err = run([args.cli, "check", "--submission", os.path.join(subs, changed), "--ray-scale", "0.02",
                               "--no-time", "--format", fmt, "--out-dir", os.path.join(args.work, "check"), *no_sandbox],
                              cwd=args.work)
        try:
            results = json.loads(said)
        except ValueError:
            results = {}
        check(code == 0 and key in results, f"check --format {fmt}: exit {code}: {said[-500:]} {err[-500:]}")
        if fmt == "prairielearn":
            check(results.get("score") == 1.0 and results.get("gradable") is True, f"prairielearn: {results}")
        else:
            check(results.get("score") == sum(t["max_score"] for t in results.get("tests", [])) > 0, f"gradescope: {results}")

    print(f"{len(FAILURES)} failed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
