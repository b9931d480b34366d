#!/bin/bash
# Start-up time of the sm2 command line: the wall time of one `sm2 asm` of a small shader (and of
# `sm2 --version`), each run N times, as the median, best and worst of the runs in milliseconds,
# and the shared libraries the process loads. Goal: `sm2 asm` of a small shader <= 20 ms
# (docs/performance.md, "Start-up"). Exit 0 whether or not the goal is met (a measurement).
#
#   bench/startup.sh [--sm2 PATH] [--runs N]      (defaults: build/release/tools/sm2, 50)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sm2=$root/build/release/tools/sm2
runs=50
while [ $# -gt 0 ]; do
    case "$1" in
        --sm2) sm2=$2; shift 2 ;;
        --runs) runs=$2; shift 2 ;;
        -h|--help) sed -n '2,7p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "startup.sh: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
shader=$(mktemp --suffix=.asm)
trap 'rm -f "$shader"' EXIT
printf 'ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmul r0, r0, c0\nmov oC0, r0\n' > "$shader"

# Times `$@` $runs times (nanoseconds from date, around a fork+exec) and prints median/best/worst.
time_command() {
    local label=$1; shift
    local times=()
    for _ in $(seq "$runs"); do
        local t0 t1
        t0=$(date +%s%N)
        "$@" > /dev/null
        t1=$(date +%s%N)
        times+=($(( (t1 - t0) / 1000 )))
    done
    printf '%s\n' "${times[@]}" | sort -n | awk -v label="$label" -v n="$runs" '
        { t[NR] = $1 }
        END { printf "%-28s median %6.2f ms, best %6.2f ms, worst %6.2f ms (%d runs)\n",
                     label, t[int((n + 1) / 2)] / 1000, t[1] / 1000, t[n] / 1000, n }'
}

echo "sm2: $sm2"
echo "shared libraries loaded by sm2 asm: $(LD_DEBUG=files "$sm2" asm "$shader" 2>&1 >/dev/null | grep -c 'calling init:')"
time_command "sm2 asm (small shader)" "$sm2" asm "$shader"
time_command "sm2 --version" "$sm2" --version
time_command "/bin/true (fork+exec alone)" /bin/true
