#!/usr/bin/env bash
# Sets up (installs missing Debian packages), builds, and runs every test. GUI tests run under
# Xvfb with Mesa's llvmpipe, so no display or GPU is needed.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
"$here/scripts/build.sh"
build="${FAULTLINE_BUILD_DIR:-$here/build}"
cd "$build"
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe
xvfb-run -a -s "-screen 0 1920x1080x24" \
    ctest --output-on-failure --parallel "$(nproc)" --timeout 600 "$@"
