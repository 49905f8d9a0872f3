#!/usr/bin/env bash
# The whole test suite: installs missing packages, builds, runs ctest.
# GPU tests run on whatever Vulkan device is present (Mesa lavapipe without a GPU), always with
# the validation layer on. Without arguments the input tests (fuzzing, graph and bench files,
# scene loading; no GPU) then run again in a build with AddressSanitizer and
# UndefinedBehaviorSanitizer (docs/inputs.md); arguments go to ctest and skip that stage.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
third_party_config/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2 --timeout 600 "$@"
if [ "$#" -eq 0 ]; then
  sanitized_tests=(voxgi_input_fuzz_tests voxgi_graph_tests voxgi_bench_unit_tests voxgi_scene_tests)
  cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOXGI_SANITIZE=address,undefined
  # The pass plugins too: the graph fuzzing compiles against the real pass types.
  cmake --build build-sanitize -j2 --target "${sanitized_tests[@]}" voxgi_passes_common \
    voxgi_passes_vct voxgi_passes_dvs voxgi_passes_reference
  # Leak checking needs ptrace, which some containers forbid; memory errors and undefined
  # behaviour are what this stage is for (ASAN_OPTIONS=detect_leaks=1 locally to add leaks).
  for test in "${sanitized_tests[@]}"; do
    (cd build-sanitize && ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0}" "bin/$test" --gtest_brief=1)
  done
fi
