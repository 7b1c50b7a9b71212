#!/usr/bin/env bash
# Set up, build, and render the bundled Cornell box to EXR and PNG.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh --renderer
# Only the renderer: the test command builds the tests and benchmarks.
./scripts/build.sh pathspace
mkdir -p out
./build/pathspace render scenes/cornell-box.pbrt -o out/cornell-box.exr -o out/cornell-box.png
echo "images: $(pwd)/out/cornell-box.exr and $(pwd)/out/cornell-box.png"
