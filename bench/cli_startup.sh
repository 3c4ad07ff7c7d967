#!/usr/bin/env bash
# Whole-process start-up and read speed of the command line, as a user meets it: the median of
# repeated runs of `faultline --help` and of `faultline info` on a 525,000-sphere LAMMPS dump
# (written here once: id type x y z radius, ~23 MB), against faultline-app doing the same.
# usage: bench/cli_startup.sh [BUILD_DIR]   (default build)
set -euo pipefail
build=${1:-build}
dump=${TMPDIR:-/tmp}/faultline-bench-525k.dump
if [ ! -s "$dump" ]; then
    awk 'BEGIN { srand(1); n = 525000;
        print "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n" n "\nITEM: BOX BOUNDS pp pp ff\n0 300\n0 100\n0 100\nITEM: ATOMS id type x y z radius";
        for (i = 1; i <= n; i++) printf "%d %d %.5f %.5f %.5f %.4f\n", i, 1 + i % 3, 300 * rand(), 100 * rand(), 100 * rand(), 0.5 + 0.1 * rand() }' >"$dump"
fi
bytes=$(stat -c %s "$dump")
median() { # command... -> median wall seconds of 15 runs
    for _ in $(seq 15); do
        s=$(date +%s%N); "$@" >/dev/null 2>&1; e=$(date +%s%N)
        echo $(((e - s) / 1000))
    done | sort -n | sed -n 8p
}
for exe in faultline faultline-app; do
    help=$(median "$build/app/$exe" --help)
    info=$(median "$build/app/$exe" info "$dump")
    printf '%-14s --help %6.1f ms   info %6.1f ms = %5.0f MB/s (%d MB file)\n' "$exe" \
        "$(echo "$help / 1000" | bc -l)" "$(echo "$info / 1000" | bc -l)" \
        "$(echo "$bytes / $info" | bc -l)" $((bytes / 1000000))
done
