#!/bin/bash
# Frames per second of every sample scene: `sm2 bench --threads N --repeat R` on
# samples/scenes/*.sm2cs (the median run), one line per scene, against issue 9's goals (60
# frames/s, 27_final_combine 30). A measurement: exit 0 whether or not the goals are met.
#
#   bench/scenes_fps.sh [--sm2 PATH] [--threads N] [--repeat R] [-- SM2-BENCH-FLAGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
sm2=build/release/tools/sm2 threads=2 repeat=5
while [ $# -gt 0 ]; do
    case "$1" in
        --sm2) sm2=$2; shift 2 ;;
        --threads) threads=$2; shift 2 ;;
        --repeat) repeat=$2; shift 2 ;;
        --) shift; break ;;
        *) sed -n '2,6p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 2 ;;
    esac
done
below=0
for scene in samples/scenes/*.sm2cs; do
    name=$(basename "$scene" .sm2cs)
    # "frames/s: 3.075 k": the unit prefix (k, M) applied.
    fps=$("$sm2" bench "$scene" --threads "$threads" --repeat "$repeat" "$@" |
        awk '/^frames\/s:/ { v = $2; if ($3 == "k") v *= 1e3; else if ($3 == "M") v *= 1e6; printf "%.1f", v }')
    goal=60
    [ "$name" = 27_final_combine ] && goal=30
    verdict=ok
    awk -v f="$fps" -v g="$goal" 'BEGIN { exit !(f < g) }' && { verdict="below $goal"; below=$((below + 1)); }
    printf '%-28s %10s frames/s  %s\n' "$name" "$fps" "$verdict"
done
echo "$below scene(s) below their goal ($threads threads, median of $repeat runs)"
