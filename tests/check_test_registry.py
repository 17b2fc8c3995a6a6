#!/usr/bin/env python3
"""Checks the test suite as CTest sees it (ctest --show-only=json-v1):

- every test has at least one of the labels README's "Tests" section lists;
- every test named in tests/slow_tests.cmake exists (a renamed test would
  otherwise silently lose its label and slow down `ctest -L unit`);
- no two tests name the same file or folder under the build folder's test
  output folders, or one inside the other: tests run in parallel (-j2 in CI),
  and two that wrote one file would read each other's.

    check_test_registry.py CTEST BUILD_DIR SLOW_LIST OUTPUT_ROOT...
"""
import json
import os
import re
import subprocess
import sys

LABELS = {"unit", "render", "robustness", "cli", "viewer", "oclgrind", "gpu-portability", "fuzz", "slow"}


def main():
    ctest, build, slow_list, roots = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    shown = subprocess.run([ctest, "--show-only=json-v1"], cwd=build, check=True, capture_output=True, text=True)
    tests = json.loads(shown.stdout)["tests"]
    problems = []

    names = {t["name"] for t in tests}
    for t in tests:
        labels = next((p["value"] for p in t.get("properties", []) if p["name"] == "LABELS"), [])
        if not LABELS.intersection(labels):
            problems.append(f"{t['name']}: no label of {sorted(LABELS)} (has {labels})")

    # The slow list: clpath_slow_tests(KIND_OR_PROGRAM name...) calls, # comments. A
    # program's cases are checked where the program is registered (the viewer's
    # recorded runs are not registered where Xvfb is missing); a configured
    # test's name is checked by CMake itself.
    programs = {os.path.basename(t["command"][0]) for t in tests if t.get("command")}
    text = re.sub(r"#[^\n]*", "", open(slow_list).read())
    for call in re.findall(r"clpath_slow_tests\(([^)]*)\)", text):
        kind, *listed = call.split()
        if kind not in programs:
            continue
        for name in listed:
            if name not in names:
                problems.append(f"{slow_list}: {name} is not a test of {kind} (renamed or removed?)")

    # Output paths: every word of a test's command line (split on the separators
    # the test scripts use) that lies under an output root.
    roots = [os.path.normpath(r) for r in roots]
    used = {}
    for t in tests:
        words = set()
        for arg in t.get("command", []) or []:
            for w in re.split(r"[;|= ]", arg):
                w = os.path.normpath(w) if w.startswith("/") else ""
                if any(w == r or w.startswith(r + os.sep) for r in roots) and w not in roots:
                    words.add(w)
        for w in words:
            used.setdefault(w, set()).add(t["name"])
    paths = sorted(used)
    for i, p in enumerate(paths):
        if len(used[p]) > 1:
            problems.append(f"{p}: named by {len(used[p])} tests: {', '.join(sorted(used[p]))}")
        for q in paths[i + 1:]:
            if not q.startswith(p + os.sep):
                continue
            others = used[q] - used[p]
            if others:
                problems.append(f"{q} (named by {', '.join(sorted(others))}) is inside {p} "
                                f"(named by {', '.join(sorted(used[p]))})")

    for p in problems:
        print(p)
    print(f"{len(tests)} tests, {len(used)} output paths: "
          + ("all labelled, no output shared" if not problems else f"{len(problems)} problems"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
