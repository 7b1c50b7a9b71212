#!/usr/bin/env bash
# Builds everything with clang and AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/
# and runs the test suite under them, but for its longest statistical renders.
# Any finding aborts its test, so CTest reports it. Extra arguments go to ctest (e.g. -L scene).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cxx=${CXX:-$(command -v clang++-14 || command -v clang++)}
# Without MPI: Open MPI's own allocations, live at exit, would be reported as leaks; the
# multi-process renders are tested in the Release build (their tests skip here, saying so).
# Nor the Python module: an instrumented extension would need the sanitizer runtime preloaded.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
  -DPATHSPACE_NATIVE=OFF -DPATHSPACE_SANITIZE=address,undefined -DPATHSPACE_MPI=OFF -DPATHSPACE_BENCH=OFF -DPATHSPACE_PYTHON=OFF >/dev/null
cmake --build build-asan -j"$jobs"
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# The longest statistical renders (minutes each under the sanitizers) repeat code paths that
# cheaper tests run too: they already ran in the Release suite and are left out here, unless
# PS_SANITIZE_ALL=1. Each family keeps cheap cases under the sanitizers (the shared scenes'
# renders, EstimatorAgreement.DiffuseBox, the other Metropolis cases,
# Cli.BdptStrategyImagesAndIntegratorChecks).
skip='PbrtReference|PbrtColourReference|EstimatorAgreement\.(SmoothNormals|GlassSphere)|SpectralAgreement\.DispersiveGlass|LightAgreement\.(EmitterInsideGlass|CameraInsideGlass|DiffuseUnderGlass)'
# The render tests' spectral instance (NAME/spectral, tests/CMakeLists.txt) repeats them in
# the other colour mode; the spectral code paths are covered here by the spectral tests.
skip+='|/spectral$'
skip+='|Metropolis\.(AgreesWith|ClosedFurnace|PointLight|EachDepth)|VeachMLT\.(AgreesWith|ClosedFurnace|PointLight|Regenerating|DirectLighting)|VeachMutation\.|VeachMLTInfinityMutation\.|MovingCamera\.(PrimarySample|VeachMLT)|VeachMLTBootstrap\.|BdptStrategies\.|ErrorEstimate\.'
# The agreement matrix's cells (tests/agreement/) repeat the base cell's code paths on other
# scenes, at minutes each under the sanitizers: only the base cell (all six integrators) and
# the statistics run here.
skip+='|AgreementMatrix\.EveryIntegratorAgrees/[a-z]+_'
# Statistical families whose every member drives the same code as a cheaper one kept here:
# each BSDF is sampled and evaluated under the sanitizers by All/Furnace, the integrators by
# the matrix's base cell, the checkpoint and stop tests and one case of each agreement family.
# Measured on 2 cores: 986 of the 1,704 test-seconds under the sanitizers (about 8 minutes of
# the suite's wall time), run in the Release suite all the same.
skip+='|All/(Sampling|Deterministic|Smooth)\.|SpectralDepths/|Variants/Metropolis|Heuristics/BdptMis|VeachPerturbationChiSquare|VeachMLTInfinity\.|PbrtShapesReference|PbrtMediaReference|LightAgreement|EstimatorAgreement\.(EnvironmentLit|GlossyConductor|PointAndSpot)|SpectralMode\.WhiteFurnace|VeachMLT\.(TwoStage|EmittersThatDoNot|DirectPart)|VeachTransition\.|LensHitsInMedia\.(PointLight|AreaLight)'
exclude=()
[ "${PS_SANITIZE_ALL:-0}" = 1 ] || exclude=(-E "$skip")
cd build-asan
ctest --output-on-failure -j"$jobs" --timeout 3600 "${exclude[@]}" "$@"
