#!/usr/bin/env bash
# Sets up a fresh Debian machine, builds Kappa and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
tools/build.sh
cd build
ctest --output-on-failure -j 2 "$@"
