#!/usr/bin/env bash
# Formatting check (STYLE: .clang-format, LLVM base, 4 spaces, 100 columns): clang-format
# --dry-run --Werror over the C++ sources of app/ core/ ui/ tests/ python/ bench/. Fails naming
# each file and line that differs; `clang-format -i <file>` fixes it. A CTest test runs this.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
format="${CLANG_FORMAT:-clang-format}"
if ! command -v "$format" >/dev/null; then
    echo "check-format: $format not found (scripts/setup.sh installs clang-format)" >&2
    exit 1
fi
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    mapfile -t files < <(git ls-files -- 'app/*.cpp' 'app/*.hpp' 'core/*.cpp' 'core/*.hpp' \
        'ui/*.cpp' 'ui/*.hpp' 'tests/*.cpp' 'tests/*.hpp' 'python/*.cpp' 'bench/*.cpp' 'bench/*.hpp')
else
    mapfile -t files < <(find app core ui tests python bench -name '*.cpp' -o -name '*.hpp' | sort)
fi
status=0
out="$("$format" --dry-run --Werror "${files[@]}" 2>&1)" || status=1
[ -n "$out" ] && status=1 && printf '%s\n' "$out" | grep "error:" | head -50
if [ $status -ne 0 ]; then
    echo "check-format: files above differ from .clang-format; run clang-format -i on them" >&2
else
    echo "check-format: ${#files[@]} files formatted"
fi
exit $status
