#!/usr/bin/env bash
# The long statistical tier, outside the README's test command and CI: the tests labelled
# `long` in tests/CMakeLists.txt (92 tests, about 22 minutes of test time; docs/testing.md).
# Run it before changing the chains, the mutations or the spectral sampling.
# Builds first (scripts/build.sh); extra arguments go to ctest (e.g. -R VeachMLT).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
cd build
ctest --output-on-failure --no-tests=error -j"$(nproc 2>/dev/null || echo 2)" --timeout 1200 -L long "$@"
