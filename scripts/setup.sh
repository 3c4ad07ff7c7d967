#!/usr/bin/env bash
# Installs the Debian packages Faultline builds and tests with. Idempotent: silent when nothing
# is missing. Needs root (or sudo) only when something must be installed.
set -euo pipefail

packages=(
    build-essential cmake ninja-build ccache pkg-config git
    libglfw3-dev libglm-dev libopenvdb-dev libboost-iostreams-dev libtinygltf-dev libimgui-dev libstb-dev
    nlohmann-json3-dev libtbb-dev libepoxy-dev libfast-float-dev zlib1g-dev liblz4-dev liblzma-dev
    libgtest-dev libgmock-dev libbenchmark-dev clang clang-format libclang-rt-14-dev nodejs
    xvfb xauth libgl1-mesa-dri libglx-mesa0 libegl1 libegl-mesa0 mesa-utils
    libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
    slurm-wlm munge bc fonts-dejavu-core
    pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-pandas
)

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
# The Khronos glTF-Validator for the export tests (tools/gltf-validator): npm ci once, quietly.
install_gltf_validator() {
    local dir
    dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/gltf-validator"
    [ -d "$dir/node_modules" ] && return 0
    if ! command -v npm >/dev/null; then
        echo "faultline setup: installing npm"
        ${sudo:-} apt-get install -y -qq --no-install-recommends npm >/dev/null
    fi
    (cd "$dir" && npm ci --silent --no-audit --no-fund >/dev/null)
}

[ ${#missing[@]} -eq 0 ] && { install_gltf_validator; exit 0; }

echo "faultline setup: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null; then sudo="sudo"; else
        echo "faultline setup: need root to install: ${missing[*]}" >&2; exit 1
    fi
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
install_gltf_validator
