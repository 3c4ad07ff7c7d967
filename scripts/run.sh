#!/usr/bin/env bash
# Sets up, builds, and opens the Faultline workbench: on the built-in demo model (generated once
# into ~/.local/share/faultline/demo, with progress), or on the data or session given.
# Without a display it says so and names the headless commands.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
"$here/scripts/build.sh"
build="${FAULTLINE_BUILD_DIR:-$here/build}"
exec "$build/app/faultline" "$@"
