#!/usr/bin/env bash
# Long fuzzing (issue 42): each libFuzzer target for FAULTLINE_FUZZ_MINUTES (default 10) on a
# corpus kept between runs (build-hardening/fuzz-corpus/<target>, seeded from tests/data,
# tests/replay and fuzz/corpus), with a dictionary for the text formats (fuzz/dict). Prints,
# per target, the executions, the edges covered (cov) and the corpus size, and fails on a crash
# (its input is kept in build-hardening/fuzz-artifacts/). Builds the hardening folder if needed.
#   scripts/fuzz-long.sh [target...]      e.g. scripts/fuzz-long.sh lammps_dump vtk_xml
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FAULTLINE_HARDENING_DIR:-$here/build-hardening}"
minutes="${FAULTLINE_FUZZ_MINUTES:-10}"
export CCACHE_BASEDIR="$here" CCACHE_NOHASHDIR=1
if [ ! -f "$build/CMakeCache.txt" ]; then
    "$here/scripts/setup.sh"
    CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DFAULTLINE_FUZZ=ON -DFAULTLINE_BUILD_GUI=OFF -DFAULTLINE_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$build" --parallel "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    for t in "$build"/fuzz/fuzz_*; do [ -x "$t" ] && targets+=("$(basename "$t" | sed 's/^fuzz_//')"); done
fi
artifacts="$build/fuzz-artifacts"
mkdir -p "$artifacts"
printf "%-14s %12s %8s %8s %6s\n" target executions "exec/s" cov corpus
for name in "${targets[@]}"; do
    target="$build/fuzz/fuzz_$name"
    corpus="$build/fuzz-corpus/fuzz_$name"
    mkdir -p "$corpus"
    seeds=("$here/tests/data" "$here/tests/replay")
    [ -d "$here/fuzz/corpus/$name" ] && seeds+=("$here/fuzz/corpus/$name")
    dict=()
    case "$name" in
        lammps_dump|data_file) dict=(-dict="$here/fuzz/dict/lammps_dump.dict") ;;
        vtk_legacy) dict=(-dict="$here/fuzz/dict/vtk_legacy.dict") ;;
        vtk_xml) dict=(-dict="$here/fuzz/dict/vtk_xml.dict") ;;
        table) dict=(-dict="$here/fuzz/dict/table.dict") ;;
        journal|session_file) dict=(-dict="$here/fuzz/dict/journal.dict") ;;
    esac
    log="$artifacts/fuzz_$name.long.log"
    "$target" -max_total_time=$((minutes * 60)) -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
        "${dict[@]}" -artifact_prefix="$artifacts/fuzz_$name-" -print_final_stats=1 \
        "$corpus" "${seeds[@]}" 2>"$log" || { tail -40 "$log"; echo "fuzz_$name: crash"; exit 1; }
    execs=$(grep -o "stat::number_of_executed_units: [0-9]*" "$log" | awk '{print $2}')
    rate=$(( ${execs:-0} / (minutes * 60) ))
    cov=$(grep -o "cov: [0-9]*" "$log" | tail -1 | awk '{print $2}')
    printf "%-14s %12s %8s %8s %6s\n" "$name" "$execs" "$rate" "$cov" "$(ls "$corpus" | wc -l)"
done
echo "fuzz-long: ${#targets[@]} targets, $minutes min each, no crash"
