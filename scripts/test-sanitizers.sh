#!/usr/bin/env bash
# Builds everything with clang and AddressSanitizer + UndefinedBehaviorSanitizer in
# build-asan/ and runs the tests under them. Any finding aborts its test, so CTest reports it.
#   scripts/test-sanitizers.sh          the CI-sized subset (CTest label "sanitize")
#   scripts/test-sanitizers.sh --all    the whole suite (about N minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cxx=${CXX:-$(command -v clang++-14 || command -v clang++)}
label=(-L sanitize)
[ "${1:-}" = --all ] && label=()
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
  -DPATHSPACE_NATIVE=OFF -DPATHSPACE_SANITIZE=address,undefined >/dev/null
cmake --build build-asan -j"$jobs"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
cd build-asan
ctest --output-on-failure -j"$jobs" --timeout 3600 "${label[@]}"
