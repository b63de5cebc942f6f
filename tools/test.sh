#!/usr/bin/env bash
# Sets up a fresh Debian machine, builds Kappa and runs every test; then
# builds the statistics-free baseline and checks it (tools/check_baseline.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
tools/build.sh
(cd build && ctest --output-on-failure -j 2 "$@")
tools/check_baseline.sh
