#!/usr/bin/env bash
# Sharded replays give exactly the unsharded run's CSVs and frames: the journal runs whole, in
# 3 shards (--shard K/3) and in 2 frame ranges (--frames), `faultline merge` joins the CSVs, and
# each merged file must equal the whole run's byte for byte (PNG frames: same files, same bytes).
# usage: shards_match.sh FAULTLINE JOURNAL DATA OUTDIR LAST_FRAME
set -euo pipefail
faultline=$1 journal=$2 data=$3 out=$4 last=$5
rm -rf "$out"
mkdir -p "$out"
run() { "$faultline" replay "$journal" --data "$data" --out "$out/$1" "${@:2}" >/dev/null; }
run all
for k in 1 2 3; do run "shard$k" --shard "$k/3"; done
split=$((last / 2))
run range1 --frames "0:$split"
run range2 --frames "$((split + 1)):$last"
status=0
for csv in "$out"/all/*.csv; do
    name=$(basename "$csv")
    "$faultline" merge "$out/merged_shards_$name" "$out"/shard{1,2,3}/"$name" >/dev/null
    "$faultline" merge "$out/merged_ranges_$name" "$out"/range{1,2}/"$name" >/dev/null
    for merged in "$out/merged_shards_$name" "$out/merged_ranges_$name"; do
        if ! cmp -s "$merged" "$csv"; then
            echo "FAIL: $merged differs from the whole run's $name:" >&2
            diff "$csv" "$merged" | head -5 >&2
            status=1
        fi
    done
done
# Per-frame renders: each frame is drawn by exactly one shard, identical to the whole run's.
if [ -d "$out/all/frames" ]; then
    for png in "$out"/all/frames/*.png; do
        name=$(basename "$png")
        found=0
        for s in shard1 shard2 shard3; do
            if [ -f "$out/$s/frames/$name" ]; then
                found=$((found + 1))
                cmp -s "$png" "$out/$s/frames/$name" || { echo "FAIL: $s/frames/$name differs" >&2; status=1; }
            fi
        done
        [ "$found" -eq 1 ] || { echo "FAIL: $name drawn by $found shards, expected 1" >&2; status=1; }
    done
fi
# Overlapping shards are refused, naming the frame.
if "$faultline" merge "$out/overlap.csv" "$out/all/metrics.csv" "$out/shard1/metrics.csv" 2>"$out/overlap.err"; then
    echo "FAIL: merging overlapping shards succeeded" >&2
    status=1
elif ! grep -q "is also in" "$out/overlap.err"; then
    echo "FAIL: overlap error does not name the frame: $(cat "$out/overlap.err")" >&2
    status=1
fi
[ "$status" -eq 0 ] && echo "shards match the whole run: $(ls "$out"/all/*.csv | wc -l) CSVs"
exit "$status"
