#!/usr/bin/env bash
# Sets up, builds, and runs the main job on the built-in samples:
#  1. every sample scene (samples/scenes/*.sm2cs, the demos of ../shared/scenes.md) is replayed
#     through the emulated GPU into out/scenes/<name>/frame_NNNN.png;
#  2. every sample shader is validated, assembled to bytecode (out/shaders/*.bin, *.hex) and
#     disassembled back to text.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
sm2=build/release/tools/sm2

bash scripts/replay_scenes.sh "$sm2"

mkdir -p out/shaders
for src in samples/shaders/*.asm; do
  name=$(basename "$src" .asm)
  "$sm2" validate "$src"
  "$sm2" asm "$src" -o "out/shaders/$name.bin"
  "$sm2" asm "$src" --format hex -o "out/shaders/$name.hex"
  "$sm2" dis "out/shaders/$name.bin" -o "out/shaders/$name.dis.asm"
  echo "== $name: $(($(stat -c %s "out/shaders/$name.bin") / 4)) tokens"
done
echo "demo: frames in out/scenes/, shader bytecode in out/shaders/"
