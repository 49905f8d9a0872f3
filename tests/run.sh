#!/usr/bin/env bash
# The whole test suite: installs missing packages, builds, runs ctest.
# GPU tests run on whatever Vulkan device is present (Mesa lavapipe without a GPU), always with
# the validation layer on. Without arguments the input tests (fuzzing, graph and bench files,
# scene loading; no GPU) then run again in a clang build with AddressSanitizer and
# UndefinedBehaviorSanitizer, and that build's libFuzzer targets run for a bounded time each
# (docs/inputs.md); arguments go to ctest and skip that stage.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
third_party_config/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2 --timeout 600 "$@"
if [ "$#" -eq 0 ]; then
  sanitized_tests=(voxgi_input_fuzz_tests voxgi_graph_tests voxgi_bench_unit_tests voxgi_scene_tests)
  # libFuzzer needs clang; a build-sanitize configured with another compiler is configured anew.
  fresh=()
  if [ -f build-sanitize/CMakeCache.txt ] &&
    ! grep -q '^CMAKE_CXX_COMPILER:FILEPATH=.*clang++' build-sanitize/CMakeCache.txt; then
    fresh=(--fresh)
  fi
  # Line tables are all a sanitizer report needs (full debug information built 9% slower).
  CC=clang CXX=clang++ cmake "${fresh[@]}" -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" \
    -DVOXGI_SANITIZE=address,undefined -DVOXGI_FUZZ=ON
  # The pass plugins too: the graph fuzzing compiles against the real pass types.
  cmake --build build-sanitize -j2 --target "${sanitized_tests[@]}" voxgi_passes_common \
    voxgi_passes_vct voxgi_passes_dvs voxgi_passes_lpv voxgi_passes_reference voxgi_fuzz_targets
  # Leak checking needs ptrace, which some containers forbid; memory errors and undefined
  # behaviour are what this stage is for (ASAN_OPTIONS=detect_leaks=1 locally to add leaks).
  # The mutation fuzzing runs a quarter of its mutations here (the optimized run above did them
  # all); the coverage-guided fuzzing below searches further.
  for test in "${sanitized_tests[@]}"; do
    (cd build-sanitize && ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0}" \
      VOXGI_FUZZ_MUTATIONS="${VOXGI_FUZZ_MUTATIONS:-1000}" "bin/$test" --gtest_brief=1)
  done
  # Coverage-guided fuzzing of the JSON reader, graph files, expressions, bench files and glTF,
  # VOXGI_FUZZ_SECONDS each (tests/fuzz/run-libfuzzer.sh runs them longer locally).
  tests/fuzz/run-libfuzzer.sh build-sanitize "${VOXGI_FUZZ_SECONDS:-30}"
fi
