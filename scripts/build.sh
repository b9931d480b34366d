#!/usr/bin/env bash
# Configures and builds the release tree (g++, warnings as errors) into build/release.
#   scripts/build.sh            everything (libraries, sm2, the Python module, tests, benchmarks)
#   scripts/build.sh TARGET...  only those targets and what they need (demo.sh: sm2)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSM2_WERROR=ON >/dev/null
if [ $# -gt 0 ]; then
  cmake --build build/release -j "$jobs" --target "$@"
else
  cmake --build build/release -j "$jobs"
fi
