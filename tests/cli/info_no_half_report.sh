#!/usr/bin/env bash
# Issue 37: `faultline info` on a file whose first frame reads and a later frame is cut short
# fails naming the place, and prints no half report before the error.
# Usage: info_no_half_report.sh FAULTLINE MULTIFRAME_DUMP
set -euo pipefail
faultline="$1" source="$2"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
size=$(stat -c %s "$source")
head -c $((size - 40)) "$source" > "$dir/cut.lammpstrj"
if "$faultline" info "$dir/cut.lammpstrj" > "$dir/out" 2> "$dir/err"; then
    echo "FAIL: info accepted a truncated file"; exit 1
fi
if [ -s "$dir/out" ]; then
    echo "FAIL: info printed a report before its error:"; cat "$dir/out"; exit 1
fi
grep -q "cut.lammpstrj:" "$dir/err" || { echo "FAIL: the error names no place:"; cat "$dir/err"; exit 1; }
# A good file still gets its whole report.
"$faultline" info "$source" | grep -q "frames:" || { echo "FAIL: no report for a good file"; exit 1; }
echo "1 passed, 0 failed"
