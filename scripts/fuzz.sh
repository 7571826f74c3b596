#!/usr/bin/env bash
# Fuzzes the triangulations (fuzz/fuzz_targets/triangulate.rs: random and degenerate point
# sets, weighted or not, each checked exactly by `Triangulation::validate`) or the surface
# tetrahedralization (fuzz/fuzz_targets/surface.rs: star-shaped closed surfaces, each result
# checked for its facets, labels and volume; an open one must be refused).
#   bash scripts/fuzz.sh [SECONDS] [triangulate|surface]      (default 120, triangulate)
# cargo-fuzz needs the unstable sanitizer flags; RUSTC_BOOTSTRAP lets the stable toolchain
# accept them. Crashes are written to fuzz/artifacts/TARGET/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
target=${2:-triangulate}
case "$target" in
triangulate) options=(-max_len=1600) ;;
# An input takes up to seconds: long ones (every vertex's factor its own byte) from the start.
surface) options=(-max_len=512 -len_control=0 -timeout=300) ;;
*)
    echo "unknown fuzz target: $target (triangulate or surface)" >&2
    exit 2
    ;;
esac
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
mkdir -p "fuzz/corpus/$target"
cd fuzz
RUSTC_BOOTSTRAP=1 cargo fuzz run -O "$target" "corpus/$target" -- \
  -max_total_time="$seconds" "${options[@]}"
