"""compas_fd against `tensegrity formfind` on the built-in double-layer grids (issue 48).

Run by run.sh beside it (which makes the venv and builds the release binaries). Three modes:

  side_by_side.py compas K          one compas_fd solve of grid:K in this process: prints JSON
                                    with the nodes and the solve's wall and CPU seconds
  side_by_side.py table K [K ...]   the table: for each K, best of REPEATS runs of (a) this
                                    script in `compas` mode and (b) `tensegrity formfind
                                    --builtin grid:K --json` as whole processes (CPU time of the
                                    child, user + system, and wall), plus the solves alone
                                    (compas_fd's `fd_numpy` call; ours: `form_find` timed
                                    in-process by the `grid_cost` example), and the largest
                                    difference of the nodes (m)

The grid is rebuilt here from the rule of `grid:K` (crates/formfind/src/builtin.rs): the same
node numbering, members (bars, bottom edges, top strings, vertical strings), force densities
and held outline; the script checks it against our JSON (member count, force densities equal,
held nodes at their positions) before comparing anything.
"""

import json
import os
import resource
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.environ.get("TENSEGRITY_BIN", os.path.join(ROOT, "target", "release", "tensegrity"))
GRID_COST = os.environ.get(
    "GRID_COST_BIN", os.path.join(ROOT, "target", "release", "examples", "grid_cost")
)
REPEATS = int(os.environ.get("REPEATS", "5"))


def grid(k):
    """Nodes, members [(i, j)], force densities and held nodes of `grid:K` (K >= 2)."""
    nc = (k + 1) * (k + 1)
    ny = nc + (k + 1) * k

    def corner(u, v):
        return v * (k + 1) + u

    def xmid(u, v):
        return nc + v * k + u

    def ymid(u, v):
        return ny + v * (k + 1) + u

    n = ny + k * (k + 1)
    nodes = [[0.0, 0.0, 0.0] for _ in range(n)]
    for v in range(k + 1):
        for u in range(k + 1):
            nodes[corner(u, v)] = [float(u), float(v), 0.0]
    for v in range(k + 1):
        for u in range(k):
            nodes[xmid(u, v)] = [u + 0.5, float(v), 0.5]
    for v in range(k):
        for u in range(k + 1):
            nodes[ymid(u, v)] = [float(u), v + 0.5, 0.5]
    bars, top, vertical = [], [], []
    for v in range(k):
        for u in range(k):
            b = [corner(u + 1, v + 1), corner(u, v + 1), corner(u, v), corner(u + 1, v)]
            t = [ymid(u, v), xmid(u, v), ymid(u + 1, v), xmid(u, v + 1)]
            for i in range(4):
                bars.append((b[i], t[i]))
                top.append((t[i], t[(i + 1) % 4]))
                vertical.append((b[i], t[(i + 3) % 4]))
    edges = []
    for v in range(k + 1):
        for u in range(k):
            q = 0.5 if v in (0, k) else 1.0
            edges.append(((corner(u, v), corner(u + 1, v)), q))
    for v in range(k):
        for u in range(k + 1):
            q = 0.5 if u in (0, k) else 1.0
            edges.append(((corner(u, v), corner(u, v + 1)), q))
    members = bars + [e for e, _ in edges] + top + vertical
    q = [-1.0] * len(bars) + [q for _, q in edges] + [1.0] * (len(top) + len(vertical))

    def outline(p):
        return p[0] == 0.0 or p[1] == 0.0 or p[0] == k or p[1] == k

    fix = [False] * n
    pinned = [0] * n
    for i in range(nc):
        fix[i] = outline(nodes[i])
    for c, t in bars:
        if outline(nodes[t]) and not fix[c] and pinned[c] < 2:
            fix[t] = True
            pinned[c] += 1
    fixed = [i for i in range(n) if fix[i]]
    return nodes, members, q, fixed


def compas(k):
    """One compas_fd solve of grid:K: JSON on stdout."""
    t0 = time.perf_counter()
    from compas_fd.solvers import fd_numpy

    imported = time.perf_counter() - t0
    nodes, members, q, fixed = grid(k)
    wall, cpu = time.perf_counter(), time.process_time()
    result = fd_numpy(vertices=nodes, fixed=fixed, edges=members, forcedensities=q)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    xyz = [list(map(float, p)) for p in result.vertices]
    json.dump({"solve_wall_s": wall, "solve_cpu_s": cpu, "import_s": imported, "nodes": xyz},
              sys.stdout)


def child(args):
    """Runs `args`; its stdout, wall seconds and CPU seconds (user + system of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    out = subprocess.run(args, check=True, stdout=subprocess.PIPE).stdout
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return out, wall, cpu


def ours_solve(k):
    """Best in-process time of form_find (no statics) and with them, from grid_cost."""
    out = subprocess.run([GRID_COST, str(k)], check=True, stdout=subprocess.PIPE, text=True)
    row = out.stdout.strip().splitlines()[-1].split(",")
    return float(row[3]), float(row[4])


def table(ks):
    rows = []
    for k in ks:
        nodes, members, q, fixed = grid(k)
        best = {}
        ours = compas_out = None
        for _ in range(REPEATS):
            out, wall, cpu = child([BIN, "formfind", "--builtin", f"grid:{k}", "--json"])
            ours = out
            best["ours_wall"] = min(best.get("ours_wall", 1e300), wall)
            best["ours_cpu"] = min(best.get("ours_cpu", 1e300), cpu)
            out, wall, cpu = child([sys.executable, __file__, "compas", str(k)])
            compas_out = json.loads(out)
            best["fd_wall"] = min(best.get("fd_wall", 1e300), wall)
            best["fd_cpu"] = min(best.get("fd_cpu", 1e300), cpu)
            best["fd_solve"] = min(best.get("fd_solve", 1e300), compas_out["solve_wall_s"])
            best["fd_solve_cpu"] = min(best.get("fd_solve_cpu", 1e300), compas_out["solve_cpu_s"])
            form, analysed = ours_solve(k)
            best["ours_solve"] = min(best.get("ours_solve", 1e300), form)
            best["ours_analysed"] = min(best.get("ours_analysed", 1e300), analysed)
        # one analysed process too (the cost of `--analyse`), best of REPEATS
        for _ in range(REPEATS):
            _, wall, cpu = child([BIN, "formfind", "--builtin", f"grid:{k}", "--analyse",
                                  "--json"])
            best["ours_analyse_cpu"] = min(best.get("ours_analyse_cpu", 1e300), cpu)
        r = json.loads(ours)
        assert r["n_bars"] + r["n_strings"] == len(members), "not the same grid"
        assert r["force_density"] == q, "not the same force densities"
        xs = r["nodes"]
        assert all(xs[i] == nodes[i] for i in fixed), "not the same held nodes"
        fd = compas_out["nodes"]
        dmax = max(abs(a - b) for p, s in zip(xs, fd) for a, b in zip(p, s))
        rows.append((k, len(nodes), len(members), best, dmax))
    head = ("| K | nodes | members | compas_fd process CPU | ours process CPU | "
            "ours --analyse process CPU | compas_fd fd_numpy | ours form_find | "
            "ours form_find + analyse | max abs node diff (m) |")
    print(head)
    print("|" + "---:|" * 10)
    for k, n, m, b, d in rows:
        print(f"| {k} | {n} | {m} | {b['fd_cpu']:.3f} s | {b['ours_cpu']:.3f} s | "
              f"{b['ours_analyse_cpu']:.3f} s | {b['fd_solve']:.4f} s | {b['ours_solve']:.4f} s | "
              f"{b['ours_analysed']:.4f} s | {d:.1e} |")
    print()
    print(f"best of {REPEATS}; process CPU = user + system of the whole child process "
          "(Python start and imports included for compas_fd); fd_numpy and form_find wall "
          "time in-process (single-threaded). Load average: "
          + " ".join(f"{x:.2f}" for x in os.getloadavg()))


if __name__ == "__main__":
    if sys.argv[1] == "compas":
        compas(int(sys.argv[2]))
    else:
        table([int(k) for k in sys.argv[2:]])
