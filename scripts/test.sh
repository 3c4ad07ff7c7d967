#!/usr/bin/env bash
# Sets up (installs missing Debian packages), builds, and runs every test: unit, CLI, replay
# and GUI tests (GUI under Xvfb with Mesa's llvmpipe: no display or GPU needed), then the
# hardening checks (tests under ASan + UBSan, each fuzz target for 20 s; scripts/hardening.sh).
# FAULTLINE_QUICK=1 skips the hardening part.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh"
"$here/scripts/build.sh"
build="${FAULTLINE_BUILD_DIR:-$here/build}"
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe
# Under the test command OpenGL must work: GL tests fail instead of skipping without a context,
# and a missing uniform or a GL error after a render pass fails the test that drew it.
export FAULTLINE_REQUIRE_GL=1 FAULTLINE_GL_CHECKS=1
# As root (the machine setup.sh installs on) the Slurm example test must run, not skip.
[ "$(id -u)" -eq 0 ] && export FAULTLINE_REQUIRE_SLURM=1
(cd "$build" && xvfb-run -a -s "-screen 0 1920x1080x24 -noreset" \
    ctest --output-on-failure --parallel "$(nproc)" --timeout 600 "$@")
if [ "${FAULTLINE_QUICK:-0}" != 1 ]; then
    "$here/scripts/hardening.sh"
fi
