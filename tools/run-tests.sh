#!/usr/bin/env bash
# Builds isoquad if needed and runs every test; a failing test prints its output.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
bash tools/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" "$@"
