#!/usr/bin/env bash
# Configures (Release, Ninja) and builds isoquad and its tests in build/ (arguments go to
# cmake --build: `--target isoquad` builds the CLI alone).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build -j "$(nproc)" "$@"
