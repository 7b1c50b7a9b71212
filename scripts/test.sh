#!/usr/bin/env bash
# Set up, build and run the whole test suite; then the same suite under ASan+UBSan, and a short
# seeded fuzz run of each fuzz target (about 15 minutes in all on 2 cores; see README "Hardening").
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc 2>/dev/null || echo 2)" --timeout 1200
cd ..
./scripts/test-sanitizers.sh
# Whoever runs this script holds the shared build lock, if any, for all of it.
PS_BUILD_LOCK_HELD=1 ./scripts/fuzz.sh all 60 -seed=1
