#!/usr/bin/env bash
# Builds oneTBB with ThreadSanitizer (TBB_SANITIZE=thread) from Debian's own source package of the
# TBB the project links (onetbb, the same version as libtbb-dev), for scripts/hardening.sh: with
# Debian's uninstrumented libtbb, TSan cannot see TBB's hand-offs between threads, so every
# parallel loop would look racy. Same soname, so the tests take it through LD_LIBRARY_PATH.
#   scripts/tsan-tbb.sh DIR      installs into DIR/install (nothing to do when it is there);
#                                prints the library folder; fails when the source cannot be had.
set -euo pipefail
dir="$(mkdir -p "$1" && cd "$1" && pwd)"
lib="$dir/install/lib"
if [ -f "$lib/libtbb.so.12" ]; then
    echo "$lib"
    exit 0
fi
version="$(dpkg-query -W -f '${source:Version}' libtbb-dev 2>/dev/null || true)"
mkdir -p "$dir/apt/lists/partial" "$dir/src"
# A private deb-src list: the machine's apt setup is left as it is.
cat >"$dir/apt/src.sources" <<SOURCES
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb-src
URIs: http://deb.debian.org/debian-security
Suites: bookworm-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SOURCES
apt=(apt-get -q -o "Dir::Etc::SourceList=$dir/apt/src.sources" -o Dir::Etc::SourceParts=/dev/null
     -o "Dir::State::Lists=$dir/apt/lists")
"${apt[@]}" update >"$dir/apt.log" 2>&1
(cd "$dir/src" && "${apt[@]}" source --download-only "onetbb${version:+=$version}" >>"$dir/apt.log" 2>&1 ||
    "${apt[@]}" source --download-only onetbb >>"$dir/apt.log" 2>&1)
orig="$(ls "$dir"/src/onetbb_*.orig.tar.* | head -1)"
rm -rf "$dir/src/tree" && mkdir -p "$dir/src/tree"
tar -xf "$orig" -C "$dir/src/tree" --strip-components=1
CC=clang CXX=clang++ cmake -S "$dir/src/tree" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF \
    -DCMAKE_INSTALL_PREFIX="$dir/install" -DCMAKE_INSTALL_LIBDIR=lib >"$dir/build.log" 2>&1
cmake --build "$dir/build" --parallel "$(nproc)" >>"$dir/build.log" 2>&1
cmake --install "$dir/build" >>"$dir/build.log" 2>&1
echo "$lib"
