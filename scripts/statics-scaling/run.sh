#!/usr/bin/env bash
# The cost of `tensegrity statics` against size (issue 48, item 2): the forms of the gallery
# (examples/formfind), the double-layer grids of `formfind --builtin grid:K` (K = 5…86) and
# the free towers of N Snelson prisms (N = 2…12,800, the scenes of examples/tower200.toml
# continued), each run `statics SCENE --json` (the full report: rank, self-stress basis where
# listed, margin LP, prestress stability) as a whole process; the least CPU (user + sys, from
# getrusage) of three runs. Prints one CSV row per scene, family,size,members,seconds,basis
# (the self-stress basis listed or omitted), then the fitted exponent of seconds against
# members over the larger half of each family.
#
#   scripts/statics-scaling/run.sh [BINARY] [--quick]
#
# BINARY defaults to target/release/tensegrity; --quick runs K ≤ 20 and N ≤ 1,600.
set -euo pipefail
BIN=${1:-target/release/tensegrity}
QUICK=${2:-}
[ -x "$BIN" ] || { echo "no binary at $BIN (cargo build --release)" >&2; exit 2; }
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
GRIDS="5 6 7 8 9 10 11 12 13 14 15 16 18 20 25 30 40 50 60 70 86"
TOWERS="2 3 5 10 25 50 100 200 400 800 1600 3200 6400 12800"
if [ "$QUICK" = --quick ]; then
    GRIDS="5 6 7 8 9 10 11 12 13 14 15 16 18 20"
    TOWERS="2 3 5 10 25 50 100 200 400 800 1600"
fi

tower() { # N: the free tower of N prisms (tower.py beside this script)
    python3 "$(dirname "$0")/tower.py" "$1"
}

best() { # SCENE: the least CPU (user + sys, from getrusage) of three runs of statics --json
    python3 - "$BIN" "$1" "$DIR/out.json" <<'PY'
import resource, subprocess, sys
bin_, scene, out = sys.argv[1:]
best = None
for _ in range(3):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(out, "w") as f:
        subprocess.run([bin_, "statics", scene, "--json", "--max-work", "100000"], stdout=f,
                       stderr=subprocess.DEVNULL, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    best = t if best is None else min(best, t)
print(f"{best:.4f}")
PY
}

row() { # FAMILY SIZE SCENE
    local t members path
    t=$(best "$3")
    read -r members path < <(python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
basis = "omitted" if d.get("self_stress_omitted") else "listed"
print(d["bar_count"] + d["string_count"], basis)' "$DIR/out.json")
    echo "$1,$2,$members,$t,$path" | tee -a "$DIR/rows.csv"
}

echo "family,size,members,seconds,basis"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
for f in "$ROOT"/examples/formfind/*.toml; do
    # the gallery's forms (a topology that does not form-find is skipped)
    "$BIN" formfind "$f" --out "$DIR/f.toml" > /dev/null 2>&1 || continue
    row gallery "$(basename "$f" .toml)" "$DIR/f.toml"
done
for k in $GRIDS; do
    "$BIN" formfind --builtin "grid:$k" --out "$DIR/g.toml" > /dev/null
    row grid "$k" "$DIR/g.toml"
done
for n in $TOWERS; do
    tower "$n" > "$DIR/t.toml"
    row tower "$n" "$DIR/t.toml"
done
python3 - "$DIR/rows.csv" <<'PY'
import csv, math, sys
rows = list(csv.reader(open(sys.argv[1])))
for fam in ("gallery", "grid", "tower"):
    pts = [(float(r[2]), float(r[3])) for r in rows if r[0] == fam and r[2] and float(r[3]) > 0]
    pts = pts[len(pts) // 2:]
    if len(pts) < 2:
        continue
    xs = [math.log(m) for m, _ in pts]; ys = [math.log(t) for _, t in pts]
    mx = sum(xs) / len(xs); my = sum(ys) / len(ys)
    p = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    print(f"# {fam}: seconds ~ members^{p:.2f} over members {pts[0][0]:.0f}…{pts[-1][0]:.0f}")
PY
