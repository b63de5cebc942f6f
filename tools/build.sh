#!/usr/bin/env bash
# Configures (once) and builds Kappa in build/ (Release, Ninja, 2 jobs by default).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${KAPPA_JOBS:-2}"  # 2 cores on the project machines
if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build -j "$jobs"
