#!/usr/bin/env bash
# Installs the Debian 12 packages pathspace needs to build, test and benchmark; with
# --renderer, only those the renderer needs (the quickstart: the test command installs the rest).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libopenexr-dev libstb-dev zlib1g-dev
  libcli11-dev nlohmann-json3-dev
  libopenmpi-dev openmpi-bin  # rendering across machines (mpirun -n K pathspace render ...)
)
if [ "${1:-}" != "--renderer" ]; then
  packages+=(
    libgtest-dev libbenchmark-dev
    clang-14 libclang-rt-14-dev llvm-14  # sanitizer and fuzz builds (llvm-14: symbolized reports)
    pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib  # the Python module, its tests and examples
  )
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all packages present"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
