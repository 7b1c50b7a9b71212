#!/usr/bin/env bash
# Configure and build pathspace (Release) into build/. Arguments name the targets to build
# (default: all of them, tests and benchmarks included); the quick start builds only the
# renderer: ./scripts/build.sh pathspace
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build build -j"$jobs" "${targets[@]}"
