#!/usr/bin/env python3
"""The course platforms' autograder bundles (scripts/make_autograder.sh): each bundle is made
under --work, the platform's folders are laid out beside it, and its entry point (Gradescope's
run_autograder, PrairieLearn's grade.sh, GitHub Classroom's .github/accelviz-grade.sh) grades
with a prebuilt CLI (ACCELVIZ_GRADER) on

- the worked example: full marks (Gradescope: score == the tests' points; PrairieLearn: 1.0,
  gradable; GitHub: exit 0);
- the bvh skeleton: less than full marks (GitHub: a non-zero exit);
- tests/student/hostile/forged_report, told (ACCELVIZ_FORGE_PATH) where the real results file
  is, and (since the judge passes the student's code no such variable) a copy with the real
  results paths written into its code, with the sandbox and without: results.json is the
  judge's failing one, never the forgery, and nothing else appears in the results folder; a
  control run shows the same code does write where anyone may;
- a compile error: score 0 with the compiler's error (PrairieLearn: gradable);
- no sandbox here (a grader that answers exit 3 without --no-sandbox, as on the platforms):
  the entry point grades again with --no-sandbox, and the student's code, as nobody when
  this runs as root, cannot write into the results folder;
- a grader that does not exist: results.json still comes, score 0, saying the grader failed.

Also the script's bad uses (exit 2, one line), the bundle's files, and shellcheck where it is
installed. No network, no apt: nothing is built here.

    python3 tests/student/test_bundles.py --cli build/bin/accelviz-cli --work /tmp/bundles
"""
import argparse
import json
import os
import shlex
import shutil
import stat
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(HERE, "..", "app"))
from viewer_harness import FAILURES, check, run  # noqa: E402

MAKE = os.path.join(ROOT, "scripts", "make_autograder.sh")
EXTRA_ARGS = "--ray-scale 0.02 --no-time"
ENTRY = {"gradescope": "run_autograder", "prairielearn": "grade.sh", "github": ".github/accelviz-grade.sh"}
# What every bundle holds besides its source copy (paths relative to the bundle).
FILES = {
    "gradescope": ["README.md", "setup.sh", "run_autograder", "packages.txt", "build_grader.sh"],
    "prairielearn": ["README.md", "Dockerfile", "grade.sh", "packages.txt", "build_grader.sh"],
    "github": ["README.md", ".github/workflows/classroom.yml", ".github/accelviz-grade.sh",
               ".github/accelviz/packages.txt", ".github/accelviz/build_grader.sh"],
}
SOURCE = {"gradescope": "source", "prairielearn": "source", "github": "accelviz"}
SCRIPTS = {
    "gradescope": ["setup.sh", "run_autograder", "build_grader.sh"],
    "prairielearn": ["grade.sh", "build_grader.sh"],
    "github": [".github/accelviz-grade.sh", ".github/accelviz/build_grader.sh"],
}


def load(path):
    """The JSON object in `path`, or None when it is missing or not JSON."""
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def copy_files(src, dst):
    """The files (not the folders) of `src` into `dst`."""
    os.makedirs(dst, exist_ok=True)
    for name in os.listdir(src):
        if os.path.isfile(os.path.join(src, name)):
            shutil.copy(os.path.join(src, name), dst)


def make_bundles(work):
    """Makes the three bundles, checks the script's bad uses and each bundle's files."""
    for argv, what in (([], "no platform"), (["moodle"], "an unknown platform"),
                       (["gradescope", os.path.join(work, "x"), "extra"], "an extra argument"),
                       (["gradescope", ""], "an empty output folder name")):
        code, said, err = run([MAKE, *argv], cwd=work)
        check(code == 2 and len(err.strip().splitlines()) == 1 and not os.path.exists(os.path.join(work, "x")),
              f"make_autograder.sh with {what}: exit {code}, expected 2 and one line: {err!r}")
    bundles = {}
    for platform in ENTRY:
        out = os.path.join(work, "bundle-" + platform)
        start = time.monotonic()
        code, said, err = run([MAKE, platform, out], cwd=work)
        print(f"make_autograder.sh {platform}: exit {code} in {time.monotonic() - start:.1f} s: {said.strip()}")
        check(code == 0, f"make_autograder.sh {platform}: exit {code}: {err}")
        bundles[platform] = out
        for f in FILES[platform]:
            check(os.path.isfile(os.path.join(out, f)), f"{platform} bundle: no {f}")
        for f in SCRIPTS[platform] + [ENTRY[platform]]:
            path = os.path.join(out, f)
            check(os.path.isfile(path) and os.stat(path).st_mode & stat.S_IXUSR,
                  f"{platform} bundle: {f} not executable")
        src = os.path.join(out, SOURCE[platform])
        for f in ("CMakeLists.txt", "app/CMakeLists.txt", "app/cli/main.cpp", "app/worker/CMakeLists.txt",
                  "student/accelviz_student.h", "student/example/median_bvh.cpp",
                  "student/skeletons/bvh/bvh.cpp", "cmake/student.cmake", "third_party/CMakeLists.txt"):
            check(os.path.isfile(os.path.join(src, f)), f"{platform} bundle: the source copy has no {f}")
        for f in ("tests", "docs", "app/viewer", "build", "shaders", "bench"):
            check(not os.path.exists(os.path.join(src, f)), f"{platform} bundle: the source copy holds {f}")
        with open(os.path.join(out, "README.md"), encoding="utf-8") as f:
            check("--no-sandbox" in f.read(), f"{platform} bundle: README.md does not explain the sandbox fallback")
        # Again into the same folder: refused, the bundle left as it is.
        code, _, err = run([MAKE, platform, out], cwd=work)
        check(code == 2 and os.path.isfile(os.path.join(out, FILES[platform][1])),
              f"make_autograder.sh {platform} into a non-empty folder: exit {code}: {err}")
    listed = subprocess.run(["git", "-C", ROOT, "ls-files", "--", "CMakeLists.txt", "cmake", "core", "app/cli",
                             "app/worker", "app/CMakeLists.txt", "student", "third_party", "scenes"],
                            capture_output=True, text=True).stdout.split()
    present = sorted(f for f in listed if os.path.exists(os.path.join(ROOT, f)))
    copied = sorted(os.path.relpath(os.path.join(d, f), os.path.join(bundles["gradescope"], "source"))
                    for d, _, files in os.walk(os.path.join(bundles["gradescope"], "source")) for f in files)
    check(copied == present, f"the source copy is not the tracked files: {len(copied)} copied, {len(present)} tracked")
    with open(os.path.join(bundles["gradescope"], "source", "student", "accelviz_student.h"), "rb") as a, \
            open(os.path.join(ROOT, "student", "accelviz_student.h"), "rb") as b:
        check(a.read() == b.read(), "the source copy's accelviz_student.h differs from the working tree's")
    if shutil.which("shellcheck"):
        scripts = [os.path.join(bundles[p], f) for p in ENTRY for f in SCRIPTS[p]] + [MAKE]
        code, said, err = run(["shellcheck", *scripts])
        check(code == 0, f"shellcheck: {said}{err}")
    else:
        print("shellcheck is not installed: the scripts are not linted")
    try:
        import yaml  # noqa: PLC0415 (optional: the workflow is parsed where PyYAML is installed)
    except ImportError:
        yaml = None
    if yaml:
        with open(os.path.join(bundles["github"], ".github", "workflows", "classroom.yml"), encoding="utf-8") as f:
            flow = yaml.safe_load(f)
        steps = flow.get("jobs", {}).get("run-autograding-tests", {}).get("steps", [])
        commands = " ".join(str(s.get("run", "")) + str(s.get("with", {}).get("command", "")) for s in steps)
        check("accelviz-grade.sh" in commands and "build_grader.sh" in commands,
              f"classroom.yml: no build or grade step: {commands[:300]}")
    return bundles


def forging_submission(work, case, paths):
    """tests/student/hostile/forged_report aimed at `paths` written into its code: the judge
    hands the student's code only PATH, HOME and LANG, so ACCELVIZ_FORGE_PATH never reaches it,
    and the results folders under --work are not /autograder or /grade. None when the hostile
    file no longer has the line this replaces."""
    with open(os.path.join(HERE, "hostile", "forged_report", "forged_report.cpp"), encoding="utf-8") as f:
        code = f.read()
    line = 'if (const char* forge_path = std::getenv("ACCELVIZ_FORGE_PATH")) paths.push_back(forge_path);'
    if line not in code:
        return None
    literal = ", ".join(json.dumps(p) for p in paths)
    folder = os.path.join(work, "subs", case)
    os.makedirs(folder)
    with open(os.path.join(folder, "forged_here.cpp"), "w", encoding="utf-8") as f:
        f.write(code.replace(line, "for (const char* p : {" + literal + "}) paths.push_back(p);"))
    return folder


def no_sandbox_grader(work, cli):
    """A grader that answers as the real one does where bubblewrap cannot run (exit 3, nothing
    graded) unless --no-sandbox is given: then it is the real one."""
    path = os.path.join(work, "grader-without-sandbox.sh")
    with open(path, "w") as f:
        f.write("#!/usr/bin/env bash\n"
                'for a in "$@"; do if [ "$a" = --no-sandbox ]; then exec ' + shlex.quote(cli) + ' "$@"; fi; done\n'
                'echo "accelviz-cli: check: refusing to grade: bubblewrap cannot make a sandbox here" >&2\n'
                "exit 3\n")
    os.chmod(path, 0o755)
    return path


class Platform:
    """One platform's layout under --work and its entry point."""

    def __init__(self, name, bundle, work):
        self.name, self.bundle, self.work = name, bundle, work

    def grade(self, case, submission, grader, forge=None):
        """Lays out a fresh folder for `case` with the files of `submission`, runs the entry
        point: (exit code, stdout + stderr, results.json or None, the results folder)."""
        root = os.path.join(self.work, f"{self.name}-{case}")
        env = dict(os.environ, ACCELVIZ_GRADER=grader, ACCELVIZ_EXTRA_ARGS=EXTRA_ARGS)
        env.pop("ACCELVIZ_FORGE_PATH", None)
        cwd = self.work
        if self.name == "gradescope":
            # Gradescope unpacks the zip into /autograder/source, and runs run_autograder.
            os.makedirs(root)
            os.symlink(self.bundle, os.path.join(root, "source"))
            copy_files(submission, os.path.join(root, "submission"))
            env["ACCELVIZ_AUTOGRADER_ROOT"] = root
            results = os.path.join(root, "results")
            entry = os.path.join(self.bundle, "run_autograder")
        elif self.name == "prairielearn":
            copy_files(submission, os.path.join(root, "student"))
            os.makedirs(os.path.join(root, "results"))
            env["ACCELVIZ_GRADE_ROOT"] = root
            results = os.path.join(root, "results")
            entry = os.path.join(self.bundle, "grade.sh")
        else:
            # The student's repository: the template (the bundle) and the student's files at its root.
            shutil.copytree(self.bundle, root, symlinks=True)
            copy_files(submission, root)
            env.pop("ACCELVIZ_SUBMISSION", None)
            results = None
            entry = ENTRY["github"]
            cwd = root
        if forge:
            env["ACCELVIZ_FORGE_PATH"] = os.path.join(results or root, forge)
        start = time.monotonic()
        # As the platform starts it: Gradescope and PrairieLearn run the file, the workflow runs bash on it.
        code, said, err = run(["bash", entry] if self.name == "github" else [entry], timeout=600, env=env, cwd=cwd)
        print(f"{self.name} {case}: exit {code} in {time.monotonic() - start:.1f} s")
        result = load(os.path.join(results, "results.json")) if results else None
        return code, said + err, result, results


def full_marks(platform, code, said, result):
    if platform == "gradescope":
        tests = (result or {}).get("tests", [])
        return (result is not None and tests and all({"name", "score", "max_score"} <= set(t) for t in tests)
                and result.get("score") == sum(t["max_score"] for t in tests) > 0)
    if platform == "prairielearn":
        return result is not None and result.get("gradable") is True and result.get("score") == 1.0
    return code == 0


def less_than_full(platform, code, result):
    if platform == "gradescope":
        tests = (result or {}).get("tests", [])
        return result is not None and tests and result.get("score", 0) < sum(t.get("max_score", 0) for t in tests)
    if platform == "prairielearn":
        return result is not None and result.get("gradable") is True and result.get("score", 1) < 1.0
    return code != 0


def forged(result):
    """results.json holds what forged_report plants: Gradescope's {"score": 100}, PrairieLearn's
    {"gradable": true, "score": 1.0}, or its own report with "passed": true."""
    if not isinstance(result, dict):
        return False
    return (result.get("score") in (100, 1.0) and "tests" not in result) or result.get("passed") is True


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    cli = os.path.abspath(args.cli)
    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chmod(work, 0o755)  # the judge hands nobody its worker's folder under here without the sandbox
    start = time.monotonic()

    bundles = make_bundles(work)
    example = os.path.join(ROOT, "student", "example")
    skeleton = os.path.join(ROOT, "student", "skeletons", "bvh")
    hostile = os.path.join(HERE, "hostile", "forged_report")
    broken = os.path.join(work, "subs", "compile_error")
    os.makedirs(broken)
    with open(os.path.join(broken, "broken.cpp"), "w") as f:
        f.write('#include "accelviz_student.h"\n\nint broken( {\n  return 1\n}\n')
    without_sandbox = no_sandbox_grader(work, cli)
    missing = os.path.join(work, "no-such-grader", "accelviz-cli")

    for name, bundle in bundles.items():
        p = Platform(name, bundle, work)

        code, said, result = p.grade("example", example, cli)[:3]
        check(full_marks(name, code, said, result), f"{name} example: exit {code}, {result}: {said[-1500:]}")

        code, said, result = p.grade("skeleton", skeleton, cli)[:3]
        check(less_than_full(name, code, result), f"{name} skeleton: exit {code}, {result}: {said[-800:]}")

        # The forgery aimed at the very file the platform reads, through the variable the
        # hostile submission reads (the judge gives its code only PATH, HOME and LANG: the
        # literal paths below are the attack that arrives).
        code, said, result, results = p.grade("forged", hostile, cli, forge="results.json")
        if results:
            check(result is not None and not forged(result) and less_than_full(name, code, result),
                  f"{name} forged_report: results.json is not the judge's failing one: {result}")
            with open(os.path.join(results, "results.json"), encoding="utf-8") as f:
                text = f.read()
            check('{"score": 100}' not in text and '"passed": true' not in text,
                  f"{name} forged_report: the forgery is in results.json: {text[:300]}")
        else:
            check(code != 0, f"{name} forged_report: exit {code}, expected a failure: {said[-800:]}")
            check(not os.path.exists(os.path.join(p.work, f"{name}-forged", "results.json")),
                  f"{name} forged_report: wrote results.json into the repository")

        code, said, result = p.grade("compile-error", broken, cli)[:3]
        if name == "gradescope":
            out = json.dumps(result or {})
            check(result is not None and result.get("score") == 0 and "broken.cpp" in out and "error" in out,
                  f"gradescope compile error: {result}")
        elif name == "prairielearn":
            check(result is not None and result.get("score") == 0 and result.get("gradable") is True
                  and "broken.cpp" in json.dumps(result), f"prairielearn compile error: {result}")
        else:
            check(code != 0 and "broken.cpp" in said, f"github compile error: exit {code}: {said[-800:]}")

        # No sandbox here: graded again with --no-sandbox, the example in full.
        code, said, result = p.grade("fallback", example, without_sandbox)[:3]
        check(full_marks(name, code, said, result) and "--no-sandbox" in said,
              f"{name} without a sandbox: exit {code}, {result}: {said[-1500:]}")
        if results:
            # The forgery written into the code, aimed at results.json and at a new file
            # beside it, with the sandbox and without it (the student's code unconfined, as
            # nobody when this runs as root): results.json is the judge's, the new file absent.
            for case, grader in (("forged-here", cli), ("fallback-forged-here", without_sandbox)):
                case_results = os.path.join(work, f"{name}-{case}", "results")
                sub = forging_submission(work, f"{name}-{case}", [os.path.join(case_results, "results.json"),
                                                                  os.path.join(case_results, "forged.json")])
                if not check(sub, "forged_report.cpp no longer reads ACCELVIZ_FORGE_PATH: update forging_submission"):
                    break
                code, said, result = p.grade(case, sub, grader)[:3]
                check(result is not None and not forged(result) and less_than_full(name, code, result),
                      f"{name} {case}: results.json is not the judge's failing one: {result}")
                if os.geteuid() != 0 and "--no-sandbox" in said:
                    print(f"{name} {case}: graded without the sandbox and not as root: the student's code ran as "
                          "this user, who owns the results folder (on the platforms it runs as nobody): not checked")
                    continue
                held = sorted(os.listdir(case_results))
                check(held == ["results.json"], f"{name} {case}: the student's code wrote there: {held}")
        if name == "gradescope" and os.geteuid() == 0:
            # The control: the same code, without the sandbox, aimed at a folder anyone may
            # write: the file appears, so the attack above was real and the folder's owner
            # (root, not nobody) is what stopped it.
            open_folder = os.path.join(work, "anyone-may-write")
            os.makedirs(open_folder)
            os.chmod(open_folder, 0o777)
            sub = forging_submission(work, "control", [os.path.join(open_folder, "forged.json")])
            if sub:
                p.grade("control", sub, without_sandbox)
                check(os.path.exists(os.path.join(open_folder, "forged.json")),
                      "control: the forging code wrote nothing even where anyone may write: the checks above "
                      "prove nothing")

        code, said, result = p.grade("grader-missing", example, missing)[:3]
        if name == "gradescope":
            check(result is not None and result.get("score") == 0 and "grader failed" in result.get("output", ""),
                  f"gradescope with no grader: exit {code}, {result}: {said[-500:]}")
        elif name == "prairielearn":
            check(result is not None and result.get("score") == 0 and result.get("gradable") is False
                  and "grader failed" in result.get("message", ""), f"prairielearn with no grader: {result}")
        else:
            check(code != 0, f"github with no grader: exit {code}")

    print(f"{time.monotonic() - start:.0f} s")
    print(f"{len(FAILURES)} failed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
