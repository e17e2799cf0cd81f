#!/usr/bin/env bash
# jax-fdm against `tensegrity design` on four of jax-fdm's published inverse form-finding
# examples, side by side (issue 47): a venv under target/ with jax-fdm from PyPI (jax on CPU),
# the release binary, then the table of side_by_side.py: at the examples' own stopping rules
# (no argument) or at a tolerance given to all (e.g. 1e-16: the optimum itself compared).
#
#   scripts/jaxfdm-side-by-side/run.sh [TOL]
#   scripts/jaxfdm-side-by-side/run.sh optimum        # scipy's least_squares, independently
#   scripts/jaxfdm-side-by-side/run.sh export DIR     # rewrite the design files
#
# Environment: PYTHON (default python3), REPEATS (default 3), PROBLEMS (default
# cablenet,dome,pringle,monkey_saddle), JAXFDM_DATA (a folder with jax-fdm's
# data/json/monkey_saddle.json; default: downloaded into target/jaxfdm-data).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
cd "$root"
venv="$root/target/jaxfdm-venv"
if [ ! -x "$venv/bin/python" ]; then
    "${PYTHON:-python3}" -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import jax_fdm" 2>/dev/null; then
    "$venv/bin/pip" install --quiet jax-fdm
fi
cargo build --release --quiet --bin tensegrity
"$venv/bin/python" -c "import jax_fdm, jax, scipy; print('jax-fdm', jax_fdm.__version__, 'jax', jax.__version__, 'scipy', scipy.__version__)"
if [ "${1:-}" = "export" ]; then
    exec "$venv/bin/python" "$here/side_by_side.py" export "${2:-examples/design}"
fi
if [ "${1:-}" = "optimum" ]; then
    exec "$venv/bin/python" "$here/side_by_side.py" optimum
fi
"$venv/bin/python" "$here/side_by_side.py" table "$@"
