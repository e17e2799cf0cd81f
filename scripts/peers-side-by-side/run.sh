#!/usr/bin/env bash
# Each peer beside `tensegrity` on the same problem, in one run on this machine (issue 48):
# compas_fd (form-finding grid:27 and grid:85), numpy's SVD (the statics of free towers of 50,
# 200 and 800 Snelson prisms), TsgFEM under GNU Octave (its T-bar dynamics example, where
# Octave and a TsgFEM checkout are at hand) and MOTES (not run: its stored time, no ratio).
# Prints one markdown table; see side_by_side.py beside this script for what each row times.
#
#   scripts/peers-side-by-side/run.sh
#   TSGFEM=/path/to/TsgFEM REPEATS=3 scripts/peers-side-by-side/run.sh
#
# Needs the release binary (target/release/tensegrity), the `grid_cost` example of formfind
# and the `statics_cost` example of tensegrity-io (built here if missing), python3, and for the peers the venv target/compas-fd-venv
# (made here with compas_fd, which brings numpy and scipy). TSGFEM: a TsgFEM work tree or its
# git directory; without it (or without `octave`) the TsgFEM row says so. Writes nothing in the
# repository but under target/; its scenes go to a temporary folder, removed at the end.
# OPENBLAS_NUM_THREADS=1 for the peers. Environment: TENSEGRITY_BIN, REPEATS (default 3), GRIDS (default "27 85"), TOWERS
# (default "50 200 800"), TSGFEM.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
cd "$root"
export TENSEGRITY_BIN="${TENSEGRITY_BIN:-$root/target/release/tensegrity}"
[ -x "$TENSEGRITY_BIN" ] || { echo "no binary at $TENSEGRITY_BIN (cargo build --release)" >&2; exit 2; }
if [ ! -x target/release/examples/grid_cost ]; then
    cargo build --release --quiet -p formfind --example grid_cost
fi
if [ ! -x target/release/examples/statics_cost ]; then
    cargo build --release --quiet -p tensegrity-io --example statics_cost
fi
venv="$root/target/compas-fd-venv"
if [ ! -x "$venv/bin/python" ]; then
    "${PYTHON:-python3}" -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import compas_fd" 2>/dev/null; then
    "$venv/bin/pip" install --quiet compas_fd
fi
# the peers' BLAS in one thread: a second OpenBLAS thread spinning on a shared 2-core
# machine adds CPU time, not speed (tower of 200 prisms: 3.3 s against 1.5 s of SVD)
export OPENBLAS_NUM_THREADS=1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export WORK
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, $("$TENSEGRITY_BIN" --version)"
"$venv/bin/python" "$here/side_by_side.py" table
