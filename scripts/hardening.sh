#!/usr/bin/env bash
# Hardening checks: the core unit and replay tests under ASan + UBSan (clang, separate build
# folder), the core tests under ThreadSanitizer (another folder), then every libFuzzer target
# for FAULTLINE_FUZZ_SECONDS (default 30) on its seed corpus (tests/data, tests/replay,
# fuzz/corpus/<target>). Crashes fail the run; their inputs
# are kept in build-hardening/fuzz-artifacts/.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FAULTLINE_HARDENING_DIR:-$here/build-hardening}"
seconds="${FAULTLINE_FUZZ_SECONDS:-30}"
export CCACHE_BASEDIR="$here" CCACHE_NOHASHDIR=1
"$here/scripts/setup.sh"

if [ ! -f "$build/CMakeCache.txt" ]; then
    CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DFAULTLINE_FUZZ=ON -DFAULTLINE_BUILD_GUI=OFF -DFAULTLINE_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$build" --parallel "$(nproc)"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd "$build" && ctest --output-on-failure --parallel "$(nproc)" --timeout 600)

# ThreadSanitizer (issue 42): the core tests in one clang TSan build (its own folder), in two
# shards at once. TBB runs inline (FAULTLINE_TBB_THREADS=1: Debian's libtbb is not built with
# TSan, so its own hand-offs would look like races); our threads (background jobs, the
# prefetcher, caches) are checked. Any report fails the run (cmake/tsan-suppressions.txt says
# what is not ours).
tsan="${FAULTLINE_TSAN_DIR:-$here/build-tsan}"
if [ ! -f "$tsan/CMakeCache.txt" ]; then
    CC=clang CXX=clang++ cmake -S "$here" -B "$tsan" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DFAULTLINE_TSAN=ON -DFAULTLINE_BUILD_GUI=OFF -DFAULTLINE_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$tsan" --parallel "$(nproc)" --target faultline_core_tests
start=$(date +%s)
pids=()
for shard in 0 1; do
    FAULTLINE_TBB_THREADS=1 XDG_CACHE_HOME="$tsan/xdg-cache" GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=$shard \
        TSAN_OPTIONS="halt_on_error=1 abort_on_error=1 second_deadlock_stack=1 suppressions=$here/cmake/tsan-suppressions.txt" \
        "$tsan/tests/faultline_core_tests" >"$tsan/tsan-shard-$shard.log" 2>&1 &
    pids+=($!)
done
for k in 0 1; do
    wait "${pids[$k]}" || { tail -80 "$tsan/tsan-shard-$k.log"; echo "tsan: shard $k failed"; exit 1; }
done
echo "tsan: $(grep -h "tests from .* test suites ran" "$tsan"/tsan-shard-*.log | awk '{s += $2} END {print s}') core tests, no report, $(( $(date +%s) - start )) s"

artifacts="$build/fuzz-artifacts"
mkdir -p "$artifacts"
for target in "$build"/fuzz/fuzz_*; do
    [ -x "$target" ] || continue
    name="$(basename "$target")"
    corpus="$build/fuzz-corpus/$name"
    mkdir -p "$corpus"
    seeds=("$here/tests/data" "$here/tests/replay")
    [ -d "$here/fuzz/corpus/${name#fuzz_}" ] && seeds+=("$here/fuzz/corpus/${name#fuzz_}")
    echo "fuzz: $name for ${seconds}s"
    "$target" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
        -artifact_prefix="$artifacts/$name-" -print_final_stats=1 "$corpus" "${seeds[@]}" \
        2>"$artifacts/$name.log" || { tail -40 "$artifacts/$name.log"; exit 1; }
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$artifacts/$name.log" | sed "s/^/  /"
done
echo "hardening: sanitizer tests (ASan, UBSan, TSan) and fuzzing passed"
