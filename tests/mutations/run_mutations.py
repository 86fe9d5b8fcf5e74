#!/usr/bin/env python3
"""The mutation suite: small deliberate bugs in critical lines, one at a time.

Each mutation of tests/mutations/mutations.txt replaces one exact piece of text
of one file (it must occur exactly once) and names the tests that must catch
it. The suite copies the source tree to a scratch directory, builds there once,
checks that the named tests pass unmutated, then for each mutation applies it,
rebuilds only the targets of its tests, runs them, and restores the file. It
prints a table (caught / survived / does not build / stale) and exits non-zero
unless every mutation is caught.

    tests/mutations/run_mutations.py [--scratch DIR] [--jobs N] [--only ID ...]
    tests/mutations/run_mutations.py --check-catalogue BUILD_DIR

--check-catalogue builds and runs nothing: it checks, in seconds, that every
mutation's text occurs exactly once in the tree and that every test it names
exists in BUILD_DIR, so that a change which moves a guarded line fails at once
instead of leaving its mutation stale (the default tier runs it).
"""

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
CATALOGUE = Path(__file__).resolve().parent / "mutations.txt"


def read_catalogue(path):
    """The mutations: blocks of 'key value' lines, each opened by 'mutation ID'.
    In find and replace, '\\n' stands for a line break."""
    mutations, current = [], None
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        key, _, value = line.strip().partition(" ")
        value = value.strip()
        if key == "mutation":
            current = {"id": value, "line": number}
            mutations.append(current)
        elif current is None or key not in ("file", "find", "replace", "tests", "why"):
            sys.exit(f"{path}:{number}: expected 'mutation ID' or file/find/replace/tests/why")
        else:
            if key in ("find", "replace"):
                value = value.replace("\\n", "\n")
            current[key] = value
    for m in mutations:
        missing = [k for k in ("file", "find", "replace", "tests") if k not in m]
        if missing:
            sys.exit(f"{path}:{m['line']}: mutation {m['id']} lacks {', '.join(missing)}")
        m["tests"] = m["tests"].split()
    return mutations


def run(command, cwd, log=None, timeout=None):
    """The exit code of command, or None if it ran out of time (then it and
    its children are killed). GoogleTest programs stop at their first failure."""
    environment = dict(os.environ, GTEST_FAIL_FAST="1")
    process = subprocess.Popen(command, cwd=cwd, stdout=subprocess.PIPE, env=environment,
                               stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        output, _ = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        output, _ = process.communicate()
        output += f"\n(killed after {timeout} s)"
    if log is not None:
        log.write(f"$ {' '.join(command)}\n{output}\n")
        log.flush()
    return process.returncode if process.returncode >= 0 else None


def sync_tree(source, destination):
    """Copy the project's files (tracked and new) into destination, writing only
    those whose content differs, so that an incremental build stays small."""
    files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=source,
                           stdout=subprocess.PIPE, text=True, check=True).stdout.split("\n")
    for name in filter(None, files):
        origin, copy = source / name, destination / name
        if not origin.is_file():
            continue
        data = origin.read_bytes()
        if not copy.is_file() or copy.read_bytes() != data:
            copy.parent.mkdir(parents=True, exist_ok=True)
            copy.write_bytes(data)


def test_targets(build):
    """Test name -> the build targets it needs: its executable's, or for a script estep_app
    and the libraries its environment names (lib<target>.so, as the plugins of
    unit/command_line)."""
    listing = subprocess.run(["ctest", "--show-only=json-v1"], cwd=build,
                             stdout=subprocess.PIPE, text=True, check=True).stdout
    targets = {}
    for test in json.loads(listing)["tests"]:
        # A test executable not built yet has no command in the listing.
        command = test.get("command") or ["test_" + test["name"].replace("/", "_")]
        executable = Path(command[0]).name
        if executable.startswith("test_"):
            targets[test["name"]] = [executable]
            continue
        needed = ["estep_app"]
        for prop in test.get("properties", []):
            if prop["name"] == "ENVIRONMENT":
                for entry in prop["value"]:
                    library = Path(entry.partition("=")[2]).name
                    if library.startswith("lib") and library.endswith(".so"):
                        needed.append(library[3:-3])
        targets[test["name"]] = needed
    return targets


def stale(mutation, source):
    """Why @p mutation cannot be applied to the tree at @p source, or None."""
    path = source / mutation["file"]
    if not path.is_file():
        return f"{mutation['file']} does not exist"
    count = path.read_text().count(mutation["find"])
    if count != 1:
        return f"its text occurs {count} times in {mutation['file']}, not once"
    return None


def check_catalogue(mutations, build):
    """0 if every mutation applies to this tree and names existing tests."""
    targets = test_targets(build)
    problems = []
    for m in mutations:
        reason = stale(m, SOURCE)
        if reason:
            problems.append(f"mutation {m['id']} (line {m['line']}): {reason}")
        unknown = [t for t in m["tests"] if t not in targets]
        if unknown:
            problems.append(f"mutation {m['id']} (line {m['line']}): no test named "
                            f"{', '.join(unknown)}")
    for problem in problems:
        print(f"{CATALOGUE}: {problem}")
    print(f"{len(mutations)} mutations checked, {len(problems)} problems")
    return 1 if problems else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scratch", default=os.path.join(
        os.environ.get("TMPDIR", "/tmp"), "estep-mutations"),
        help="scratch directory (source copy and build; reused between runs)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count())
    parser.add_argument("--only", nargs="*", help="run only these mutation ids")
    parser.add_argument("--time-limit", type=float, default=240.,
                        help="seconds the tests of one mutation may run; a mutation that makes "
                        "them run longer counts as caught (timed out)")
    parser.add_argument("--check-catalogue", metavar="BUILD_DIR",
                        help="only check that every mutation applies and names existing tests")
    args = parser.parse_args()

    mutations = read_catalogue(CATALOGUE)
    if args.check_catalogue:
        return check_catalogue(mutations, Path(args.check_catalogue))
    if args.only:
        mutations = [m for m in mutations if m["id"] in args.only]
    scratch = Path(args.scratch)
    source, build = scratch / "source", scratch / "build"
    source.mkdir(parents=True, exist_ok=True)
    sync_tree(SOURCE, source)
    data = SOURCE.parent / "shared"
    if data.is_dir() and not (scratch / "shared").exists():
        (scratch / "shared").symlink_to(data)  # the data beside the copy, as beside the tree

    log = open(scratch / "mutations.log", "w")
    configure = ["cmake", "-S", str(source), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                 "-DESTEP_BUILD_BENCHMARKS=OFF"]
    if shutil.which("ccache"):
        configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    if run(configure, scratch, log) != 0:
        sys.exit(f"configuring the scratch build failed: see {scratch}/mutations.log")
    targets = test_targets(build)
    unknown = sorted({t for m in mutations for t in m["tests"] if t not in targets})
    if unknown:
        sys.exit(f"unknown tests in {CATALOGUE.name}: {', '.join(unknown)}")

    def build_and_test(tests, time_limit=None):
        wanted = sorted({target for t in tests for target in targets[t]} | {"estep_app"})
        if run(["cmake", "--build", str(build), "-j", str(args.jobs), "--target", *wanted],
               scratch, log) != 0:
            return "does not build"
        pattern = "^(" + "|".join(t.replace("+", "\\+") for t in tests) + ")$"
        code = run(["ctest", "-R", pattern, "-j", str(args.jobs), "--output-on-failure"],
                   build, log, time_limit)
        return "timed out" if code is None else "passed" if code == 0 else "failed"

    start = time.time()
    print(f"Baseline: building and running the {len({t for m in mutations for t in m['tests']})} "
          "named tests unmutated ...", flush=True)
    baseline = build_and_test(sorted({t for m in mutations for t in m["tests"]}))
    if baseline != "passed":
        sys.exit(f"the named tests do not pass unmutated ({baseline}): see {scratch}/mutations.log")

    rows = []
    for m in mutations:
        path = source / m["file"]
        original = path.read_text() if path.is_file() else ""
        t0 = time.time()
        if stale(m, source):
            verdict = "stale"  # the text is gone or ambiguous: the catalogue needs updating
        else:
            path.write_text(original.replace(m["find"], m["replace"]))
            try:
                outcome = build_and_test(m["tests"], args.time_limit)
            finally:
                path.write_text(original)
            verdict = {"failed": "caught", "timed out": "caught (timed out)",
                       "passed": "SURVIVED"}.get(outcome, outcome)
        rows.append((m["id"], verdict, time.time() - t0, " ".join(m["tests"])))
        print(f"  {m['id']:<48} {verdict:<15} {time.time() - t0:6.1f} s", flush=True)

    print(f"\n| mutation | verdict | seconds | tests |\n|---|---|---|---|")
    for row in rows:
        print(f"| {row[0]} | {row[1]} | {row[2]:.0f} | {row[3]} |")
    caught = sum(1 for r in rows if r[1].startswith("caught"))
    print(f"\n{caught} of {len(rows)} mutations caught in {time.time() - start:.0f} s "
          f"(log: {scratch}/mutations.log)")
    return 0 if caught == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
