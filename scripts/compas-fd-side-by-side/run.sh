#!/usr/bin/env bash
# compas_fd against `tensegrity formfind` on the same double-layer grids, side by side
# (issue 48): a venv under target/ with compas_fd from PyPI, the release binary and the
# `grid_cost` example, then the table of side_by_side.py (best of 5) for the grids given
# (default: grid:27, 10 260 members, and grid:85, 101 320 members: 14 K² + 2 K).
#
#   scripts/compas-fd-side-by-side/run.sh [K ...]
#
# Environment: PYTHON (default python3), REPEATS (default 5).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
cd "$root"
venv="$root/target/compas-fd-venv"
if [ ! -x "$venv/bin/python" ]; then
    "${PYTHON:-python3}" -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import compas_fd" 2>/dev/null; then
    "$venv/bin/pip" install --quiet compas_fd
fi
cargo build --release --quiet --bin tensegrity
cargo build --release --quiet -p formfind --example grid_cost
"$venv/bin/python" -c "import compas_fd, scipy, numpy; print('compas_fd', compas_fd.__version__, 'scipy', scipy.__version__, 'numpy', numpy.__version__)"
if [ "$#" -eq 0 ]; then
    set -- 27 85
fi
"$venv/bin/python" "$here/side_by_side.py" table "$@"
