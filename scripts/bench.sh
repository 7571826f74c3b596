#!/usr/bin/env bash
# Builds the library and runs the C benchmarks (delmesh beside CGAL and TetGen).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cargo build --release
make -C c_tests bench
