#!/bin/bash
# Two builds of sm2 on one stream, alternated round by round so that both see the same machine:
# prints each build's median pixel-stage time and median run time (`sm2 bench`), and B / A.
#
#   bench/ab.sh --snapshot BUILD DIR     copy BUILD's sm2 and its modules to DIR (a build to keep)
#   bench/ab.sh [--threads N] [--rounds R] [--repeat K] [--cpus LIST] DIR_A DIR_B STREAM
#   e.g. bench/ab.sh --snapshot build/release /tmp/before; (change, rebuild)
#        bench/ab.sh --rounds 7 /tmp/before build/release samples/scenes/27_final_combine.sm2cs
#
# A DIR is a build tree or a snapshot: DIR/tools/sm2 with DIR/lib/sm2emu/ beside it. The JIT and
# the image I/O are modules that sm2 finds relative to its own file (docs/embedding.md), so a
# lone copy of tools/sm2 loads the build tree's JIT: compare whole snapshots, never binaries.
# --cpus LIST runs both sides under `taskset -c LIST`: on this machine one core has been 15%
# slower than the other for hours at a time, and a one-thread run lands on either.
set -euo pipefail
usage() { sed -n '2,15p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 2; }

if [ "${1:-}" = "--snapshot" ]; then
    [ $# -eq 3 ] || usage
    build=$2 dir=$3
    [ -x "$build/tools/sm2" ] || { echo "ab.sh: no $build/tools/sm2" >&2; exit 2; }
    mkdir -p "$dir/tools" "$dir/lib/sm2emu"
    cp "$build/tools/sm2" "$dir/tools/"
    if [ -d "$build/lib/sm2emu" ]; then cp "$build"/lib/sm2emu/*.so "$dir/lib/sm2emu/" 2>/dev/null || true; fi
    echo "snapshot of $build in $dir"
    exit 0
fi

threads=1 rounds=5 repeat=3 cpus=""
while [ $# -gt 0 ]; do
    case "$1" in
        --threads) threads=$2; shift 2 ;;
        --rounds) rounds=$2; shift 2 ;;
        --repeat) repeat=$2; shift 2 ;;
        --cpus) cpus=$2; shift 2 ;;
        -h|--help) usage ;;
        --*) echo "ab.sh: unknown option '$1'" >&2; usage ;;
        *) break ;;
    esac
done
[ $# -eq 3 ] || usage
a=$1 b=$2 stream=$3
for dir in "$a" "$b"; do
    [ -x "$dir/tools/sm2" ] || { echo "ab.sh: no $dir/tools/sm2" >&2; exit 2; }
    [ -d "$dir/lib/sm2emu" ] || echo "ab.sh: warning: no $dir/lib/sm2emu: that sm2 loads the JIT of another build" >&2
done
[ -f "$stream" ] || { echo "ab.sh: no stream $stream" >&2; exit 2; }

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for round in $(seq "$rounds"); do
    for side in A B; do
        dir=$a
        [ "$side" = B ] && dir=$b
        pin=()
        [ -n "$cpus" ] && pin=(taskset -c "$cpus")
        out=$(env -u SM2EMU_JIT -u SM2EMU_IMAGE_IO "${pin[@]}" "$dir/tools/sm2" bench "$stream" --threads "$threads" --repeat "$repeat")
        echo "$out" | sed -n 's/.*pixel \([0-9.]*\) ms.*/\1/p' >> "$work/$side.pixel"
        echo "$out" | sed -n 's/^time per run: median \([0-9.]*\) ms.*/\1/p' >> "$work/$side.run"
    done
    echo "round $round/$rounds: A pixel $(tail -1 "$work/A.pixel") ms, B pixel $(tail -1 "$work/B.pixel") ms"
done
pa=$(median < "$work/A.pixel") pb=$(median < "$work/B.pixel")
ra=$(median < "$work/A.run") rb=$(median < "$work/B.run")
# The best round too: on a machine whose speed jumps between two levels for seconds at a time
# (this one, some hours), the medians mix the levels and the minima compare like with like.
ma=$(sort -g "$work/A.pixel" | head -1) mb=$(sort -g "$work/B.pixel" | head -1)
echo "A ($a): median pixel stage $pa ms (best $ma), run $ra ms"
echo "B ($b): median pixel stage $pb ms (best $mb), run $rb ms"
awk -v pa="$pa" -v pb="$pb" -v ra="$ra" -v rb="$rb" -v ma="$ma" -v mb="$mb" \
    'BEGIN { printf "B / A: pixel stage %.3f (best %.3f), run %.3f (%d threads, %s)\n", pb / pa, mb / ma, rb / ra, '"$threads"', "'"$stream"'" }'
