#!/usr/bin/env bash
# Hardening checks: the core unit and replay tests under ASan + UBSan (clang, separate build
# folder), then every libFuzzer target for FAULTLINE_FUZZ_SECONDS (default 30) on its seed
# corpus (tests/data, tests/replay, fuzz/corpus/<target>). Crashes fail the run; their inputs
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
echo "hardening: sanitizer tests and fuzzing passed"
