#!/usr/bin/env bash
# The whole test suite: installs missing packages, builds, runs ctest.
# GPU tests run on whatever Vulkan device is present (Mesa lavapipe without a GPU), always with
# the validation layer on.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
third_party_config/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2 --timeout 600 "$@"
