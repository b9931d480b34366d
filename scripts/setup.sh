#!/usr/bin/env bash
# Installs every build and test dependency of sm2emu from Debian packages.
# Safe to run twice: apt-get skips what is already installed.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  clang libclang-rt-14-dev          # libFuzzer and sanitizers for the fuzz targets
  llvm-14-dev clang-14              # the shader JIT (emu/src/jit): LLVM ORC, clang++-14 for its kernels
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev
  nlohmann-json3-dev                # sm2 run --json
  libsnappy-dev                     # apitrace trace files (runtime/src/apitrace_reader.cpp)
  libglm-dev
  pybind11-dev python3-dev python3-numpy python3-pytest   # the Python module sm2emu and its tests
  libopenimageio-dev
  glslang-dev glslang-tools spirv-tools   # sm2 compile (hlsl/): HLSL front end, SPIR-V optimizer and its headers
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all dependencies present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
