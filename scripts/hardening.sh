#!/usr/bin/env bash
# Hardening checks: the core unit and replay tests under ASan + UBSan (clang, separate build
# folder), the core and workbench tests under ThreadSanitizer (another folder), then every
# libFuzzer target for FAULTLINE_FUZZ_SECONDS (default 20) on its seed corpus (tests/data,
# tests/replay, fuzz/corpus/<target>). Crashes fail the run; their inputs are kept in
# build-hardening/fuzz-artifacts/. In both sanitizer trees the test programs' own sources
# compile at -O0 (tests/CMakeLists.txt), the library under test at -O2.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FAULTLINE_HARDENING_DIR:-$here/build-hardening}"
seconds="${FAULTLINE_FUZZ_SECONDS:-20}"
export CCACHE_BASEDIR="$here" CCACHE_NOHASHDIR=1

# Runs each of the jobs named after the first two arguments with `launch JOB` (its output in
# LOGS-JOB.log), as many at once as there are cores, the next as soon as one ends; a job that
# fails prints its log's tail and stops the run. A GoogleTest program's tests go as 16 shares
# (GoogleTest's sharding, GTEST_SHARD_INDEX): two halves left one core idle for minutes, as the
# slowest tests fell in one of them.
runPool() {
    local logs="$1" launch="$2" job id status
    shift 2
    local -a queue=("$@")
    local -A jobOf=()
    rm -f "$logs"-*.log
    while ((${#queue[@]} > 0 || ${#jobOf[@]} > 0)); do
        if ((${#queue[@]} > 0 && ${#jobOf[@]} < $(nproc))); then
            job="${queue[0]}"
            queue=("${queue[@]:1}")
            "$launch" "$job" >"$logs-$job.log" 2>&1 &
            jobOf[$!]="$job"
            continue
        fi
        status=0
        wait -n -p id "${!jobOf[@]}" || status=$?
        if ((status != 0)); then
            tail -80 "$logs-${jobOf[$id]}.log"
            echo "$(basename "$logs"): ${jobOf[$id]} failed"
            exit 1
        fi
        unset "jobOf[$id]"
    done
}
kShares=16
shares() { # the jobs of one program's shares: PREFIX0 .. PREFIX15 (PREFIX: name-)
    local k
    for ((k = 0; k < kShares; ++k)); do echo "$1$k"; done
}
testsRan() { # how many tests the logs say ran
    grep -h "tests from .* test suites ran" "$@" | awk '{s += $2} END {print s}'
}
"$here/scripts/setup.sh"

if [ ! -f "$build/CMakeCache.txt" ]; then
    CC=clang CXX=clang++ cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DFAULTLINE_FUZZ=ON -DFAULTLINE_BUILD_GUI=OFF -DFAULTLINE_BUILD_BENCH=OFF >/dev/null
fi
cmake --build "$build" --parallel "$(nproc)"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
start=$(date +%s)
# The core unit tests (label unit) as shares of the program, not one process a test (under ASan
# a process costs 0.4 s to start and check for leaks at exit); then the rest (replay,
# command-line and script tests) through CTest.
asanShare() {
    cd "$build/tests" && XDG_CACHE_HOME="$build/tests/xdg-cache" GTEST_TOTAL_SHARDS=$kShares \
        GTEST_SHARD_INDEX="${1#*-}" ./faultline_core_tests
}
runPool "$build/asan" asanShare $(shares core-)
echo "asan: $(testsRan "$build"/asan-core-*.log) core unit tests, no report, $(( $(date +%s) - start )) s"
(cd "$build" && ctest --output-on-failure --parallel "$(nproc)" --timeout 600 -LE unit)

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
# The core tests and the workbench's (panels, background jobs, the soak's random use; GL under
# Xvfb, a server for each share) in one pool.
tsanShare() {
    export GTEST_TOTAL_SHARDS=$kShares GTEST_SHARD_INDEX="${1#*-}"
    if [ "${1%-*}" = core ]; then
        "$tsan/tests/faultline_core_tests"
    else
        cd "$tsan/tests" && FAULTLINE_SOAK_ACTIONS=2500 FAULTLINE_REQUIRE_GL=1 FAULTLINE_GL_CHECKS=1 \
            LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe xvfb-run -a -n $((200 + 4 * GTEST_SHARD_INDEX)) \
            -s "-screen 0 1920x1080x24 -noreset" "$tsan/tests/faultline_ui_tests"
    fi
}
runPool "$tsan/tsan" tsanShare $(shares core-) $(shares ui-)
echo "tsan: $(testsRan "$tsan"/tsan-*.log) core and workbench tests with $tbbThreads TBB threads, no report, $(( $(date +%s) - start )) s"
unset LD_LIBRARY_PATH TSAN_OPTIONS FAULTLINE_TBB_THREADS XDG_CACHE_HOME

artifacts="$build/fuzz-artifacts"
mkdir -p "$artifacts"
# Each target for $seconds, in the pool (2 cores: 7 targets in 2 min, not 3.5).
fuzzOne() {
    local target="$build/fuzz/$1" corpus="$build/fuzz-corpus/$1"
    local seeds=("$here/tests/data" "$here/tests/replay")
    mkdir -p "$corpus"
    [ -d "$here/fuzz/corpus/${1#fuzz_}" ] && seeds+=("$here/fuzz/corpus/${1#fuzz_}")
    "$target" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
        -artifact_prefix="$artifacts/$1-" -print_final_stats=1 "$corpus" "${seeds[@]}"
}
targets=()
for target in "$build"/fuzz/fuzz_*; do
    if [ -x "$target" ]; then targets+=("$(basename "$target")"); fi
done
runPool "$artifacts/fuzz" fuzzOne "${targets[@]}"
for name in "${targets[@]}"; do
    echo "fuzz: $name for ${seconds}s"
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$artifacts/fuzz-$name.log" | sed "s/^/  /"
done
echo "hardening: sanitizer tests (ASan, UBSan, TSan) and fuzzing passed"
