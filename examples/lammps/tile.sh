#!/usr/bin/env bash
# Makes dump.tiled525k (two frames, 527,310 grains, ~36 MB) from the extension run's frames at
# timesteps 150000 and 200000 (tests/data/real_runs/lammps/dump.extension.gz, or DUMP=...), tiled
# 70 times along y by LAMMPS (in.tiled525k), on two ranks, so the rows come in the order two
# processes write them. Then: build/bench/bench_strain --dump examples/lammps/dump.tiled525k
# COPIES=1328 makes dump.tiled10m instead (10,003,824 grains, ~720 MB, half a minute); other counts,
# dump.tiled<COPIES>. Needs Debian's lammps package. A few seconds for the default.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dump="${DUMP:-$here/../../tests/data/real_runs/lammps/dump.extension.gz}"
copies="${COPIES:-70}"
case "$copies" in
70) out="$here/dump.tiled525k" ;;
1328) out="$here/dump.tiled10m" ;;
*) out="$here/dump.tiled$copies" ;;
esac
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# read_dump's `add` wants each atom's type: a type column (1) after the id.
zcat -f "$dump" | awk '/^ITEM: ATOMS/ { print "ITEM: ATOMS id type x y z radius"; atoms = 1; next }
                       /^ITEM:/ { atoms = 0 }
                       atoms { print $1, 1, $2, $3, $4, $5; next } { print }' > "$work/dump.typed"
root=()
[ "$(id -u)" -eq 0 ] && root=(--allow-run-as-root)
for step in 150000 200000; do
    (cd "$work" && mpirun "${root[@]}" -np 2 lmp -in "$here/in.tiled525k" -var step "$step" \
        -var in dump.typed -var copies "$copies" -log none -screen none)
done
cat "$work/tiled.150000" "$work/tiled.200000" > "$out"
echo "wrote $out"
