#!/usr/bin/env bash
# Configures and builds Faultline (Release with assertions) into build/ or $FAULTLINE_BUILD_DIR.
# Extra arguments go to the CMake configure step (e.g. -DFAULTLINE_SANITIZE=ON).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FAULTLINE_BUILD_DIR:-$here/build}"
# Paths relative to the checkout, so clones elsewhere (CI) hit the same ccache entries.
export CCACHE_BASEDIR="$here" CCACHE_NOHASHDIR=1
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
elif [ $# -gt 0 ]; then
    cmake -S "$here" -B "$build" "$@" >/dev/null
fi
cmake --build "$build" --parallel "$(nproc)"
