#!/usr/bin/env bash
# Configures and builds the release tree (g++, warnings as errors) into build/release.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSM2_WERROR=ON >/dev/null
cmake --build build/release -j "$jobs"
