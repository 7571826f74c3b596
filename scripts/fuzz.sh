#!/usr/bin/env bash
# Fuzzes the triangulations (fuzz/fuzz_targets/triangulate.rs): random and degenerate point
# sets, weighted or not, each checked exactly by `Triangulation::validate`.
#   bash scripts/fuzz.sh [SECONDS]      (default 120)
# cargo-fuzz needs the unstable sanitizer flags; RUSTC_BOOTSTRAP lets the stable toolchain
# accept them. Crashes are written to fuzz/artifacts/triangulate/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
mkdir -p fuzz/corpus/triangulate
cd fuzz
RUSTC_BOOTSTRAP=1 cargo fuzz run -O triangulate corpus/triangulate -- \
  -max_total_time="$seconds" -max_len=1600
