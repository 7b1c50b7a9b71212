#!/usr/bin/env bash
# Runs one libFuzzer campaign: scripts/fuzz.sh TARGET SECONDS [libFuzzer options...]
#   TARGET: scene_fuzzer | ply_fuzzer | image_fuzzer | nvdb_fuzzer (or "all": each for SECONDS).
# Builds the clang fuzz build in build-fuzz/, grows build-fuzz/corpus/TARGET from the seeds
# in fuzz/corpus/TARGET, and writes crashing inputs to build-fuzz/artifacts/TARGET/. A crash
# ends the campaign with a non-zero status; minimise it, fix it, and copy the input to
# fuzz/regressions/TARGET/ (replayed by tests/scene/fuzz_regressions_test.cpp).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: $0 scene_fuzzer|ply_fuzzer|image_fuzzer|nvdb_fuzzer|all SECONDS [libFuzzer options...]" >&2
  exit 2
fi
target=$1 seconds=$2
shift 2
targets=("$target")
[ "$target" = all ] && targets=(scene_fuzzer ply_fuzzer image_fuzzer nvdb_fuzzer)
cxx=${CXX:-$(command -v clang++-14 || command -v clang++)}
# On the shared development machine builds take /tmp/ps-build.lock (unless the caller holds it).
lock=()
[ -e /tmp/ps-build.lock ] && [ -z "${PS_BUILD_LOCK_HELD:-}" ] && lock=(flock /tmp/ps-build.lock)
if [ ! -f build-fuzz/build.ninja ]; then
  "${lock[@]}" cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_COMPILER="$cxx" -DPATHSPACE_NATIVE=OFF -DPATHSPACE_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
fi
"${lock[@]}" cmake --build build-fuzz -j"$(nproc 2>/dev/null || echo 2)" --target "${targets[@]}"
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/artifacts/$t"
  dict=()
  [ "$t" = scene_fuzzer ] && dict=(-dict=fuzz/scene.dict)
  # One process at a time, at the lowest priority: the machine is shared.
  nice -n 19 "build-fuzz/fuzz/$t" "build-fuzz/corpus/$t" "fuzz/corpus/${t%_fuzzer}" "${dict[@]}" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/artifacts/$t/" "$@"
done
