#!/usr/bin/env bash
# Sets up, builds, and opens Faultline on the built-in demo model.
# (Until the workbench lands it prints what `faultline info` reads from a real LIGGGHTS file.)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
"$here/scripts/build.sh"
build="${FAULTLINE_BUILD_DIR:-$here/build}"
if [ $# -eq 0 ]; then
    exec "$build/app/faultline" info "$here/tests/data/liggghts_packing_22410.particles"
fi
exec "$build/app/faultline" "$@"
