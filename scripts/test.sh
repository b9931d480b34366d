#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite:
#  1. g++ build with warnings as errors, every test;
#  2. clang build under AddressSanitizer + UndefinedBehaviorSanitizer, every test again, plus a
#     short seeded libFuzzer run of each fuzz target (set SM2_SKIP_SANITIZERS=1 to skip).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)

bash scripts/build.sh
ctest --test-dir build/release --output-on-failure -j "$jobs"

if [ "${SM2_SKIP_SANITIZERS:-0}" != 1 ]; then
  cmake -S . -B build/sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_COMPILER=clang++ -DSM2_SANITIZE=ON -DSM2_FUZZ=ON \
        -DSM2_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build build/sanitize -j "$jobs"
  # clang 14's LeakSanitizer can crash at exit on a garbage dynamic-TLS block ("Tracer caught
  # signal 11"); not intercepting __tls_get_addr avoids it (tools/main.cpp does the same for sm2).
  ASAN_OPTIONS="${ASAN_OPTIONS:-intercept_tls_get_addr=0}" ctest --test-dir build/sanitize --output-on-failure -j "$jobs"
fi
