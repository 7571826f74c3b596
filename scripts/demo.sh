#!/usr/bin/env bash
# The main job: builds the library and runs the C demonstration.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cargo build --release
make -C c_tests demo
