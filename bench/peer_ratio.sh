#!/bin/bash
# Peer benchmark: the time per frame of sm2 against Wine's Direct3D 9 on Mesa llvmpipe (the d3d9ref
# player in ../shared/d3d9ref), on the same scene and with the same number of threads. Runs R rounds
# back to back (peer, then `sm2 bench`), prints one line per round and the medians, and the ratio
# sm2/peer against the goal (<= 0.30). Exit 0 whether or not the goal is met (it is a measurement).
# Without Wine/Xvfb/mingw it says what is missing and times sm2 alone.
#
#   bench/peer_ratio.sh [--sm2 PATH] [--threads N] [--rounds R] [--frames K] [--scene FILE] [-- SM2-BENCH-FLAGS...]
#   e.g. bench/peer_ratio.sh --rounds 3 -- --engine jit
#
# Defaults: --sm2 build/release/tools/sm2, --threads 2, --rounds 3, --frames 11,
#           --scene ../shared/d3d9ref/scenes/bench_1024.scene (both relative to the repository root).
# Both sides are timed per frame in the steady state: the peer times each of its 20 frames after a
# warm-up frame (render states, clear, draws, read-back; textures and shaders already made); sm2's
# frame is (T(K) - T(1)) / (K - 1), with T(n) the median time of `sm2 bench` on the scene translated
# with n frames, so device, texture and shader creation cancel out. T(1) alone (a whole run of one
# frame, creation included) is printed too.
# The peer needs these Debian packages (tested with Debian 12: Wine 8.0, Mesa 22.3):
#   apt-get update && apt-get install -y --no-install-recommends \
#       wine64 wine libwine gcc-mingw-w64-x86-64 xvfb libgl1 libglx-mesa0 libgl1-mesa-dri
# (wine64+libwine: the loader /usr/lib/wine/wine64; wine: wineserver on PATH; mingw: builds player.exe;
#  xvfb: the X server; libgl1/libglx-mesa0/libgl1-mesa-dri: OpenGL on llvmpipe for wined3d.)
# Files: everything (player.exe, the Wine prefix, wineserver's socket folder, logs, the .sm2cs) goes
# into one mktemp -d folder, removed on exit; only Xvfb keeps its socket/lock in /tmp while it runs.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sm2=$root/build/release/tools/sm2
threads=2
rounds=3
frames=11
scene=$root/../shared/d3d9ref/scenes/bench_1024.scene
extra=()
goal=0.30

usage() { sed -n '2,17p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        --sm2) [ $# -ge 2 ] || usage; sm2=$2; shift 2 ;;
        --threads) [ $# -ge 2 ] || usage; threads=$2; shift 2 ;;
        --rounds) [ $# -ge 2 ] || usage; rounds=$2; shift 2 ;;
        --frames) [ $# -ge 2 ] || usage; frames=$2; shift 2 ;;
        --scene) [ $# -ge 2 ] || usage; scene=$2; shift 2 ;;
        --) shift; extra=("$@"); break ;;
        -h|--help) usage ;;
        *) echo "peer_ratio.sh: unknown argument '$1'" >&2; usage ;;
    esac
done
[[ $threads =~ ^[1-9][0-9]*$ ]] || { echo "peer_ratio.sh: --threads needs a positive integer" >&2; exit 2; }
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "peer_ratio.sh: --rounds needs a positive integer" >&2; exit 2; }
[[ $frames =~ ^[1-9][0-9]*$ ]] && [ "$frames" -ge 2 ] || { echo "peer_ratio.sh: --frames needs an integer >= 2" >&2; exit 2; }
[ -x "$sm2" ] || { echo "peer_ratio.sh: no sm2 binary at $sm2 (build it, or pass --sm2 PATH)" >&2; exit 1; }
[ -f "$scene" ] || { echo "peer_ratio.sh: no scene file $scene" >&2; exit 1; }
scene=$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")
ref=$(dirname "$(dirname "$scene")")          # .../d3d9ref (the scene lives in d3d9ref/scenes/)
[ -x "$ref/run.sh" ] || ref=$root/../shared/d3d9ref
to_sm2cs=$ref/to_sm2cs.py
[ -f "$to_sm2cs" ] || { echo "peer_ratio.sh: $to_sm2cs not found" >&2; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/peer_ratio.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM

for n in 1 "$frames"; do
    python3 "$to_sm2cs" "$scene" -o "$tmp/bench_$n.sm2cs" --frames "$n" >"$tmp/to_sm2cs.log" 2>&1 || {
        cat "$tmp/to_sm2cs.log" >&2; echo "peer_ratio.sh: to_sm2cs.py failed" >&2; exit 1; }
done

# --- the peer's prerequisites
missing=()
wine=$(command -v wine64 || true)
[ -n "$wine" ] || { [ -x /usr/lib/wine/wine64 ] && wine=/usr/lib/wine/wine64; } || true
[ -n "$wine" ] || missing+=("wine64 (package wine64)")
command -v Xvfb >/dev/null || missing+=("Xvfb (package xvfb)")
command -v x86_64-w64-mingw32-gcc >/dev/null || missing+=("x86_64-w64-mingw32-gcc (package gcc-mingw-w64-x86-64)")
[ -x "$ref/run.sh" ] || missing+=("$ref/run.sh (the d3d9ref player)")

# sm2 bench prints "time per run: median 1715.973 ms, best 1688.712 ms": the median run of STREAM, in s.
sm2_run_seconds() {
    local out
    out=$("$sm2" bench "$1" --threads "$threads" --repeat 5 ${extra[@]+"${extra[@]}"} 2>&1) || {
        echo "$out" >&2; echo "peer_ratio.sh: sm2 bench failed" >&2; return 1; }
    echo "$out" >"$tmp/sm2.log"
    awk '/^time per run: median / { printf "%.6f\n", $5 / 1000; found = 1 } END { exit !found }' "$tmp/sm2.log" || {
        echo "$out" >&2; echo "peer_ratio.sh: no 'time per run: median' line in sm2 bench output" >&2; return 1; }
}

# "FRAME RUN": the steady-state frame, (T(K) - T(1)) / (K - 1), and T(1), in s.
sm2_seconds() {
    local one many
    one=$(sm2_run_seconds "$tmp/bench_1.sm2cs") || return 1
    many=$(sm2_run_seconds "$tmp/bench_$frames.sm2cs") || return 1
    awk -v a="$one" -v b="$many" -v k="$frames" 'BEGIN { printf "%.6f %.6f\n", (b - a) / (k - 1), a }'
}

# player.c prints "time: frames=20 mean_ms=... median_ms=M min_ms=... max_ms=... readback_ms=..."
# (per-frame times of `time 20`, each frame including the render-target readback).
peer_seconds() {
    local log=$tmp/peer/player.log
    # TMPDIR: Debian's wineserver puts its socket folder (wine-XXXXXX) there instead of /tmp
    TMPDIR=$tmp LP_NUM_THREADS=$threads D3D9REF_BUILD=$tmp/build D3D9REF_WINEPREFIX=$tmp/wineprefix D3D9REF_WINE=$wine \
        "$ref/run.sh" "$scene" "$tmp/peer" >"$tmp/run.log" 2>&1 || {
        tail -n 30 "$tmp/run.log" >&2; echo "peer_ratio.sh: $ref/run.sh failed" >&2; return 1; }
    sed -n 's/^time: .*median_ms=\([0-9.]*\).*/\1/p' "$log" | awk 'NR == 1 { printf "%.6f\n", $1 / 1000; found = 1 } END { exit !found }' || {
        tail -n 30 "$tmp/run.log" >&2; echo "peer_ratio.sh: no 'time: ... median_ms=' line in $log" >&2; return 1; }
}

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) printf "%.6f", v[(NR + 1) / 2]; else printf "%.6f", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

flags=${extra[*]+" ${extra[*]}"}
echo "scene: $scene"
echo "threads: $threads for both (sm2 bench --threads $threads$flags; llvmpipe LP_NUM_THREADS=$threads)"

if [ ${#missing[@]} -gt 0 ]; then
    echo "peer not run: missing $(printf '%s; ' "${missing[@]}" | sed 's/; $//')"
    echo "install with: apt-get update && apt-get install -y --no-install-recommends wine64 wine libwine gcc-mingw-w64-x86-64 xvfb libgl1 libglx-mesa0 libgl1-mesa-dri"
    read -r s one <<<"$(sm2_seconds)"
    printf 'sm2 alone: %.4f s/frame in the steady state (%d-frame and 1-frame runs, median of 5 each); a whole 1-frame run %.4f s\n' "$s" "$frames" "$one"
    exit 0
fi

peer_all=() sm2_all=() one_all=()
for r in $(seq "$rounds"); do
    p=$(peer_seconds)
    read -r s one <<<"$(sm2_seconds)"
    peer_all+=("$p") sm2_all+=("$s") one_all+=("$one")
    awk -v r="$r" -v n="$rounds" -v p="$p" -v s="$s" -v o="$one" \
        'BEGIN { printf "round %d/%d: peer %.4f s/frame  sm2 %.4f s/frame  ratio %.3f  (sm2 whole 1-frame run %.4f s, ratio %.3f)\n", r, n, p, s, s / p, o, o / p }'
done
pm=$(printf '%s\n' "${peer_all[@]}" | median)
sm=$(printf '%s\n' "${sm2_all[@]}" | median)
om=$(printf '%s\n' "${one_all[@]}" | median)
awk -v p="$pm" -v s="$sm" -v o="$om" -v g="$goal" -v r="$rounds" 'BEGIN {
    ratio = s / p
    printf "median of %d rounds: peer (Wine d3d9 + llvmpipe) %.4f s/frame, sm2 %.4f s/frame (steady state; a whole 1-frame run %.4f s, ratio %.3f)\n", r, p, s, o, o / p
    printf "ratio sm2/peer = %.3f (goal <= %.2f): %s\n", ratio, g, ratio <= g ? "goal met" : "goal not met"
}'
exit 0
