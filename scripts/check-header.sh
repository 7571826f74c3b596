#!/usr/bin/env bash
# Regenerates the C header from src/ffi/ with the pinned cbindgen and fails, showing the
# difference, when it is not the committed include/delmesh.h.
set -euo pipefail
cd "$(dirname "$0")/.."

pinned="cbindgen 0.24.3"
found="$(cbindgen --version 2>/dev/null || echo "no cbindgen")"
if [ "$found" != "$pinned" ]; then
    echo "check-header: need $pinned (Debian's package), found: $found" >&2
    exit 1
fi

generated="$(mktemp)"
trap 'rm -f "$generated"' EXIT
cbindgen --quiet --config cbindgen.toml --output "$generated" src/ffi/mod.rs

if ! diff -u include/delmesh.h "$generated"; then
    echo "check-header: include/delmesh.h is out of date; regenerate it with" >&2
    echo "  cbindgen --config cbindgen.toml --output include/delmesh.h src/ffi/mod.rs" >&2
    exit 1
fi
echo "check-header: include/delmesh.h matches src/ffi/"
