#!/usr/bin/env bash
# The main job: builds the library, runs the C demonstration (a tanglecube given by an implicit
# C callback, meshed and written to c_tests/build/demo.vtu), and reads the file back with an
# independent reader (meshio) to show it is what a user's tools will open.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cargo build --release
make -C c_tests demo
/usr/bin/python3 - c_tests/build/demo.vtu <<'PY'
import sys
import meshio
m = meshio.read(sys.argv[1])
cells = sum(len(b.data) for b in m.cells if b.type == "tetra")
labels = sorted({int(v) for a in m.cell_data.get("label", []) for v in a})
print(f"meshio read {sys.argv[1]}: {len(m.points)} points, {cells} tetrahedra, subdomain labels {labels}")
PY
