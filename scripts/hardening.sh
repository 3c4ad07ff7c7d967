#!/usr/bin/env bash
# Hardening checks: the core unit and replay tests under ASan + UBSan (clang, separate build
# folder), the core and workbench tests under ThreadSanitizer (another folder), then every libFuzzer target
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

# ThreadSanitizer (issue 42): the core and workbench tests in one clang TSan build (its own
# folder), against a TBB built with TSan from Debian's own source package (scripts/tsan-tbb.sh:
# Debian's libtbb is not instrumented, so TSan could not see its hand-offs between threads).
# Every test runs inside an arena of 8 TBB threads (FAULTLINE_TBB_THREADS=8, even on 2 cores),
# beside our own threads (background jobs, the prefetcher, caches). Any report fails the run
# (cmake/tsan-suppressions.txt names what is not ours: OpenVDB's and Mesa's own). Where the TBB source cannot be had, TBB runs inline against
# Debian's library (FAULTLINE_TBB_THREADS=1) and the run says so.
tsan="${FAULTLINE_TSAN_DIR:-$here/build-tsan}"
tbbThreads=8
suppressions="$here/cmake/tsan-suppressions.txt"
if tbbLib="$("$here/scripts/tsan-tbb.sh" "$tsan/tbb")"; then
    export LD_LIBRARY_PATH="$tbbLib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    tbbConfig=(-DTBB_DIR="$tsan/tbb/install/lib/cmake/TBB")
else
    echo "tsan: no TBB source to build with TSan (see $tsan/tbb/apt.log); TBB runs inline"
    tbbThreads=1
    suppressions="$here/cmake/tsan-suppressions-debian-tbb.txt"
    tbbConfig=()
fi
if [ ! -f "$tsan/CMakeCache.txt" ]; then
    CC=clang CXX=clang++ cmake -S "$here" -B "$tsan" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DFAULTLINE_TSAN=ON -DFAULTLINE_BUILD_BENCH=OFF "${tbbConfig[@]}" >/dev/null
fi
cmake --build "$tsan" --parallel "$(nproc)" --target faultline_core_tests faultline_ui_tests
start=$(date +%s)
export TSAN_OPTIONS="halt_on_error=1 abort_on_error=1 second_deadlock_stack=1 suppressions=$suppressions"
export FAULTLINE_TBB_THREADS=$tbbThreads XDG_CACHE_HOME="$tsan/xdg-cache"
pids=()
for shard in 0 1; do
    GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=$shard "$tsan/tests/faultline_core_tests" \
        >"$tsan/tsan-shard-$shard.log" 2>&1 &
    pids+=($!)
done
for k in 0 1; do
    wait "${pids[$k]}" || { tail -80 "$tsan/tsan-shard-$k.log"; echo "tsan: shard $k failed"; exit 1; }
done
# The workbench's tests (panels, background jobs, the soak's random use; GL under Xvfb).
(cd "$tsan/tests" && FAULTLINE_SOAK_ACTIONS=4000 FAULTLINE_REQUIRE_GL=1 FAULTLINE_GL_CHECKS=1 \
    LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe xvfb-run -a -s "-screen 0 1920x1080x24 -noreset" \
    "$tsan/tests/faultline_ui_tests" >"$tsan/tsan-ui.log" 2>&1) ||
    { tail -80 "$tsan/tsan-ui.log"; echo "tsan: workbench tests failed"; exit 1; }
echo "tsan: $(grep -h "tests from .* test suites ran" "$tsan"/tsan-shard-*.log "$tsan/tsan-ui.log" |
    awk '{s += $2} END {print s}') core and workbench tests with $tbbThreads TBB threads, no report, $(( $(date +%s) - start )) s"
unset LD_LIBRARY_PATH TSAN_OPTIONS FAULTLINE_TBB_THREADS XDG_CACHE_HOME

artifacts="$build/fuzz-artifacts"
mkdir -p "$artifacts"
# Each target for $seconds, as many at once as there are cores (2 here: 7 targets in 2 min, not
# 3.5), each reported as it ends, in order.
fuzzOne() {
    local target="$1" name corpus
    name="$(basename "$target")"
    corpus="$build/fuzz-corpus/$name"
    mkdir -p "$corpus"
    local seeds=("$here/tests/data" "$here/tests/replay")
    [ -d "$here/fuzz/corpus/${name#fuzz_}" ] && seeds+=("$here/fuzz/corpus/${name#fuzz_}")
    "$target" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
        -artifact_prefix="$artifacts/$name-" -print_final_stats=1 "$corpus" "${seeds[@]}" \
        2>"$artifacts/$name.log"
}
fuzzReport() {
    local name
    name="$(basename "$1")"
    wait "$2" || { tail -40 "$artifacts/$name.log"; echo "fuzz: $name failed"; exit 1; }
    echo "fuzz: $name for ${seconds}s"
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$artifacts/$name.log" | sed "s/^/  /"
}
targets=() pids=()
for target in "$build"/fuzz/fuzz_*; do
    [ -x "$target" ] || continue
    if [ "${#pids[@]}" -ge "$(nproc)" ]; then
        fuzzReport "${targets[0]}" "${pids[0]}"
        targets=("${targets[@]:1}") pids=("${pids[@]:1}")
    fi
    fuzzOne "$target" &
    targets+=("$target") pids+=($!)
done
for k in "${!pids[@]}"; do
    fuzzReport "${targets[$k]}" "${pids[$k]}"
done
echo "hardening: sanitizer tests (ASan, UBSan, TSan) and fuzzing passed"
