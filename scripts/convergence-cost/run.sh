#!/usr/bin/env bash
# The convergence check's cost against the bare run (issue 48, item 3): builds the release
# binary and prints the table of docs/notes/PERFORMANCE.md, "The convergence check's cost".
# Usage: bash scripts/convergence-cost/run.sh [--repeat N]
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --quiet
python3 scripts/convergence-cost/measure.py target/release/tensegrity "$@"
