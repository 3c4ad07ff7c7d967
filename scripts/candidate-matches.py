#!/usr/bin/env python3
"""Issue 37's figure: per real run and kinematic fault, the thresholds at which a candidate
matches it (dip within 5 degrees, dip direction within 15, centroid within 2 mean diameters of
the truth plane, as the test judges the unrounded errors, and no other fault in the same
candidate).

Runs the core tests' real-run candidate checks (tests/core/fault_candidates_real_runs_test.cpp),
which print one line per run, threshold and fault whether or not they assert it, and sums them up:

    scripts/candidate-matches.py [build/tests/faultline_core_tests | saved-output.txt]

Standard library only. Exits 1 when the tests' output holds no run.
"""
import os
import re
import subprocess
import sys
from collections import OrderedDict

HEADER = re.compile(r"^(?P<run>.+), p(?P<p>[\d.]+) \(.*\): (?P<n>\d+) candidates$")
MATCH = re.compile(
    r"^  truth dip (?P<truth>[\d.]+/\d+): (?:C(?P<c>\d+) \(\d+ spheres\) .*; "
    r"(?P<verdict>within|outside)$|no candidate$)")


def read_lines(source):
    if not (os.path.isfile(source) and os.access(source, os.X_OK)):
        with open(source, encoding="utf-8") as f:  # saved output
            return f.read().splitlines()
    run = subprocess.run([source, "--gtest_filter=CandidatesOnRealRuns.*"], capture_output=True,
                         text=True, check=False)
    return run.stdout.splitlines()


def main():
    source = sys.argv[1] if len(sys.argv) > 1 else "build/tests/faultline_core_tests"
    # (run, threshold) -> [(truth, candidate or None, within tolerances)]
    checks = OrderedDict()
    current = None
    try:
        lines = read_lines(source)
    except OSError as e:
        print(f"{source}: {e.strerror}", file=sys.stderr)
        return 1
    for line in lines:
        if m := HEADER.match(line):
            current = (m["run"], float(m["p"]))
            checks[current] = []  # a threshold printed twice counts once, as printed last
        elif current and (m := MATCH.match(line)):
            ok = m["c"] is not None and m["verdict"] == "within"
            checks[current].append((m["truth"], m["c"], ok))
    if not checks:
        print(f"{source}: no real-run candidate checks in the output", file=sys.stderr)
        return 1
    faults = OrderedDict()  # (run, truth) -> [thresholds matched], [thresholds tried]
    matched = total = 0
    for (run, p), rows in checks.items():
        for truth, cand, ok in rows:
            shared = cand is not None and sum(1 for _, c, _ in rows if c == cand) > 1
            hit = ok and not shared
            entry = faults.setdefault((run, truth), ([], []))
            entry[1].append(p)
            if hit:
                entry[0].append(p)
            matched += hit
            total += 1
    for (run, truth), (hit, tried) in faults.items():
        shown = ", ".join(f"{p:g}" for p in sorted(hit)) or "none"
        verdict = "" if len(hit) >= 3 else "   (fewer than 3)"
        print(f"{run}, fault {truth}: matched at {len(hit)} of {len(tried)} thresholds "
              f"({shown}){verdict}")
    print(f"matched: {matched} of {total} (run, threshold, fault) checks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
