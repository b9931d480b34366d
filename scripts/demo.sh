#!/usr/bin/env bash
# Sets up, builds what it runs (the sm2 tool only), and runs the main job on the built-in samples:
#  1. every sample scene (samples/scenes/*.sm2cs, the demos of ../shared/scenes.md) is replayed
#     through the emulated GPU into OUT/scenes/<name>/frame_NNNN.png;
#  2. every sample shader is validated, assembled to bytecode (OUT/shaders/*.bin, *.hex) and
#     disassembled back to text;
#  3. the probe pixels of samples/scenes/probes.txt are checked against the frames, a one-screen
#     summary is printed (scenes, frames, time per scene, probes passed) and OUT/index.html, a
#     contact sheet of every frame (relative links, no external resources), is written;
#  4. a real apitrace capture (tests/data/traces/ff_lit_cube.trace, fixed-function) is imported
#     and replayed into OUT/trace/ and each frame checked with `sm2 diff` against Wine's frame:
#     every channel within 0.008 (2/255) but at most 0.01% of the pixels (triangle-edge pixels).
#
#   scripts/demo.sh [--scenes PATTERN] [--out DIR] [--sm2 PATH]
#     --scenes PATTERN  only the scenes whose name matches the shell pattern, e.g. '0[12]_*' or '*lake*'
#     --out DIR         where everything goes (default: out)
#     --sm2 PATH        use this sm2 and skip setup and build
# Exit status: 0 when every scene replayed, every shader assembled, every probe passed and the
# trace's frames matched.
set -euo pipefail
cd "$(dirname "$0")/.."
pattern='*'
out=out
sm2=""
usage() { sed -n '12,16p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --scenes) [ $# -ge 2 ] || usage; pattern="$2"; shift 2 ;;
    --out) [ $# -ge 2 ] || usage; out="$2"; shift 2 ;;
    --sm2) [ $# -ge 2 ] || usage; sm2="$2"; shift 2 ;;
    -h|--help) usage ;;
    *) echo "demo.sh: unknown argument '$1'" >&2; usage ;;
  esac
done

if [ -z "$sm2" ]; then
  bash scripts/setup.sh
  bash scripts/build.sh sm2
  sm2=build/release/tools/sm2
fi
[ -x "$sm2" ] || { echo "demo.sh: no sm2 at $sm2" >&2; exit 2; }

streams=()
for stream in samples/scenes/*.sm2cs; do
  name="$(basename "$stream" .sm2cs)"
  # shellcheck disable=SC2053  # $pattern is a pattern on purpose
  [[ "$name" == $pattern ]] && streams+=("$stream")
done
if [ ${#streams[@]} -eq 0 ]; then
  echo "demo.sh: no scene in samples/scenes matches '$pattern'" >&2
  exit 2
fi

mkdir -p "$out/scenes" "$out/shaders"
runs="$out/scenes/runs.tsv"   # name, status, seconds: read by demo_report.py
: > "$runs"
echo "demo: replaying ${#streams[@]} scenes into $out/scenes/"
for stream in "${streams[@]}"; do
  name="$(basename "$stream" .sm2cs)"
  dir="$out/scenes/$name"
  rm -rf "$dir"
  mkdir -p "$dir"
  status=ok
  "$sm2" replay "$stream" -o "$dir" > "$dir/replay.log" 2>&1 || status=FAIL
  # The replay's own time, from its summary ("N frames, M calls in S s: ...").
  seconds=$(sed -n 's/.* calls in \([0-9.]*\) s.*/\1/p' "$dir/replay.log" | tail -n 1)
  printf '%s\t%s\t%s\n' "$name" "$status" "${seconds:-0}" >> "$runs"
  if [ "$status" = ok ]; then
    frames=$(ls "$dir"/frame_*.png 2>/dev/null | wc -l)
    echo "ok    $dir/ ($frames frame$([ "$frames" = 1 ] || echo s), ${seconds} s)"
  else
    echo "FAIL  $name (see $dir/replay.log)"
    tail -n 5 "$dir/replay.log" | sed 's/^/      /'
  fi
done

shaders=0
shader_failures=0
for src in samples/shaders/*.asm; do
  name=$(basename "$src" .asm)
  if "$sm2" validate "$src" > /dev/null &&
     "$sm2" asm "$src" -o "$out/shaders/$name.bin" &&
     "$sm2" asm "$src" --format hex -o "$out/shaders/$name.hex" &&
     "$sm2" dis "$out/shaders/$name.bin" -o "$out/shaders/$name.dis.asm"; then
    shaders=$((shaders + 1))
  else
    echo "FAIL  shader $src"
    shader_failures=$((shader_failures + 1))
  fi
done

trace=tests/data/traces/ff_lit_cube
trace_failures=0
rm -rf "$out/trace"
mkdir -p "$out/trace"
if "$sm2" replay "$trace.trace" -o "$out/trace" > "$out/trace/replay.log" 2>&1; then
  for expected in "$trace"/frame_*.png; do
    n=$(basename "$expected" .png)
    n=${n#frame_}
    frame=$(printf '%s/trace/frame_%04d.png' "$out" "$n")
    # sm2 diff: 0 PASS, 1 WARNING (failing pixels within --failpercent), 2 FAILURE.
    verdict=0
    "$sm2" diff "$frame" "$expected" --tolerance 0.008 --failpercent 0.01 > "$frame.diff.txt" 2>&1 || verdict=$?
    if [ "$verdict" -le 1 ]; then
      echo "ok    trace $(basename "$trace") frame $n matches Wine's (tolerance 0.008, 0.01% of pixels)"
    else
      echo "FAIL  trace $(basename "$trace") frame $n (see $frame.diff.txt)"
      trace_failures=$((trace_failures + 1))
    fi
  done
else
  echo "FAIL  trace $trace.trace (see $out/trace/replay.log)"
  trace_failures=1
fi

status=0
python3 scripts/demo_report.py --out "$out" --runs "$runs" --shaders "$shaders" \
  --shader-failures "$shader_failures" || status=$?
[ "$trace_failures" -eq 0 ] || status=1
exit "$status"
