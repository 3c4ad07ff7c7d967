#!/usr/bin/env bash
# The long soak (issue 42): the workbench driven at random (tests/ui/soak_test.cpp) for
# FAULTLINE_SOAK_MINUTES (default 30), seed after seed (FAULTLINE_SOAK_ACTIONS actions each,
# default 2000), checking after every 50 actions that the session saves and reopens as it is,
# that undo all + redo all gives it back, and that the autosave opens. Prints each seed's
# actions per minute; a failing seed is printed with its last actions and reproduces with
#   FAULTLINE_SOAK_SEED=<seed> FAULTLINE_SOAK_ACTIONS=<n> build/tests/faultline_ui_tests --gtest_filter=Soak.*
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FAULTLINE_BUILD_DIR:-$here/build}"
minutes="${FAULTLINE_SOAK_MINUTES:-30}"
export FAULTLINE_SOAK_ACTIONS="${FAULTLINE_SOAK_ACTIONS:-2000}"
[ -x "$build/tests/faultline_ui_tests" ] || "$here/scripts/build.sh"
end=$(( $(date +%s) + minutes * 60 ))
seed=1 total=0 failures=0
while [ "$(date +%s)" -lt "$end" ]; do
    if out=$(FAULTLINE_SOAK_SEED=$seed "$build/tests/faultline_ui_tests" --gtest_filter='Soak.*' 2>&1); then
        echo "$out" | grep "^soak:"
        total=$(( total + FAULTLINE_SOAK_ACTIONS ))
    else
        echo "$out" | tail -60
        failures=$(( failures + 1 ))
    fi
    seed=$(( seed + 1 ))
done
echo "soak: $((seed - 1)) seeds, $total actions in $minutes min, $failures failing seeds"
[ "$failures" -eq 0 ]
