#!/usr/bin/env bash
# Installs missing packages, then configures and builds FlowScape (Release) into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
