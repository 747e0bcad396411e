#!/usr/bin/env bash
# Installs, builds and runs the whole test suite (Catch2 and pytest, both through CTest).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
