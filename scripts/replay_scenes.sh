#!/usr/bin/env bash
# Replays every samples/scenes/*.sm2cs into out/scenes/<name>/ (frame_NNNN.png per Present,
# SaveSurface files beside them) with a built sm2, and fails if any replay fails.
#   scripts/replay_scenes.sh [path/to/sm2]     (default: build/release/tools/sm2)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
sm2="${1:-build/release/tools/sm2}"
case "$sm2" in /*) ;; *) sm2="$root/$sm2" ;; esac
if [ ! -x "$sm2" ]; then
    echo "replay_scenes.sh: no sm2 at $sm2 (build it first, or pass its path)" >&2
    exit 2
fi
cd "$root"
failed=()
count=0
for stream in samples/scenes/*.sm2cs; do
    name="$(basename "$stream" .sm2cs)"
    out="out/scenes/$name"
    rm -rf "$out"
    mkdir -p "$out"
    count=$((count + 1))
    if "$sm2" replay "$stream" -o "$out" > "$out/replay.log" 2>&1; then
        echo "ok    $name ($(ls "$out"/*.png 2>/dev/null | wc -l) images)"
    else
        echo "FAIL  $name (see $out/replay.log)"
        tail -n 5 "$out/replay.log" | sed 's/^/      /'
        failed+=("$name")
    fi
done
if [ "$count" -eq 0 ]; then
    echo "replay_scenes.sh: no streams in samples/scenes" >&2
    exit 1
fi
if [ "${#failed[@]}" -ne 0 ]; then
    echo "replay_scenes.sh: ${#failed[@]} of $count scenes failed: ${failed[*]}" >&2
    exit 1
fi
echo "replay_scenes.sh: all $count scenes replayed into out/scenes/"
