#!/usr/bin/env bash
# Installs the system packages delmesh's tests, demo and benchmarks need on a Debian
# machine. Idempotent and quiet: does nothing when everything is already installed.
set -euo pipefail

packages=(
    libcgal-dev libtet1.5-dev libgmp-dev libmpfr-dev libboost-dev # reference meshers (tests only)
    pkg-config g++ make                                           # C tests and demo
    cbindgen                                                      # header generation (pinned 0.24.3)
    python3-meshio                                                # independent reader of written meshes
)

installed() {
    [ "$(dpkg-query -W -f='${Status}' "$1" 2>/dev/null)" = "install ok installed" ]
}

if ! command -v cargo >/dev/null; then
    echo "setup: cargo not found: install a Rust toolchain (rustup) first" >&2
    exit 1
fi

# Shewchuk's Triangle from PyPI (package `triangle`, test-only): the 2D reference of
# tests/python/test_vs_triangle.py.
if ! python3 -c "import triangle" 2>/dev/null; then
    echo "setup: installing the Python package triangle"
    python3 -m pip install --quiet triangle
fi

missing=()
for package in "${packages[@]}"; do
    installed "$package" || missing+=("$package")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}"
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
