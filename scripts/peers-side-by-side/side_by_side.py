"""Each peer beside `tensegrity` on the same problem, in one run (issue 48). Run by run.sh.

  side_by_side.py svd SCENE     numpy in this process: reads the scene's nodes and members,
                                builds the equilibrium matrix A (3 rows a node, one column a
                                member: the unit vector (x_i - x_j)/L at node i and its
                                negative at node j, the force form), times np.linalg.svd(A)
                                with its rank (sigma > max(m, n) eps sigma_max) and null-space
                                dimension; prints JSON
  side_by_side.py table         the whole comparison: prints a markdown table

The peers:

- compas_fd (form-finding): the functions of scripts/compas-fd-side-by-side/side_by_side.py
  (the grid rebuilt from the rule of `grid:K`, compas_fd's `fd_numpy` in a child process,
  ours `tensegrity formfind --builtin grid:K --json` and the `grid_cost` example in-process);
  agreement: the largest difference of the nodes;
- numpy SVD (statics): free towers of N Snelson prisms (the scenes of examples/tower200.toml
  continued, the generator of scripts/statics-scaling/run.sh); ours `tensegrity statics
  SCENE --json` (the full report: rank, self-stress, margin LP, prestress stability), and
  in-process the rank alone (the `statics_cost` example of tensegrity-io: the factorisation
  and rank decision the automatic method builds, least wall time of five, one thread)
  beside numpy's SVD and rank alone; agreement: rank and self-stress dimension equal;
- TsgFEM (dynamics): its T-bar dynamics example with its slack option, run under GNU Octave
  by scripts/tsgfem-export (TsgFEM's `dynamic_solver` timed by tic/toc), against
  `tensegrity simulate examples/anchors/tsgfem_tbar_elastic.toml --no-convergence-check
  --json` (the same 8013 RK4 steps); agreement: the largest distance of the final nodes;
  where Octave or a TsgFEM checkout is missing, the row says so and gives no ratio;
- MOTES: not run here (no MOTES set-up on this machine); the row gives the stored reference
  time with its date and our time, and no ratio.

Environment: TENSEGRITY_BIN, GRID_COST_BIN, STATICS_COST_BIN, REPEATS (default 3), GRIDS (default "27 85"),
TOWERS (default "50 200 800"), TSGFEM (a TsgFEM work tree, or its git directory: exported to a
temporary folder), WORK (a temporary folder for the scenes; run.sh makes one).
"""

import importlib.util
import io
import json
import os
import shutil
import subprocess
import sys
import tarfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BIN = os.environ.get("TENSEGRITY_BIN", os.path.join(ROOT, "target", "release", "tensegrity"))
REPEATS = int(os.environ.get("REPEATS", "3"))
WORK = os.environ.get("WORK", "/tmp")
# a numpy run longer than this (CPU seconds) is not repeated
SVD_REPEAT_MAX_S = 20.0
STATICS_COST = os.environ.get(
    "STATICS_COST_BIN", os.path.join(ROOT, "target", "release", "examples", "statics_cost"))
# towers up to this many members also run our dense path (--method dense) beside numpy's SVD
DENSE_MEMBERS_MAX = 2000

# the stored reference times (crates/tensegrity-bench/src/anchors.rs; docs/notes/PERFORMANCE.md)
MOTES_DBAR = (54.3, "2026-11-28, the project's 2-core machine kind, GNU Octave 7.3, "
              "whole-process CPU, best of 5")


def load_compas_helper():
    """scripts/compas-fd-side-by-side/side_by_side.py as a module (its grid, child, ...)."""
    path = os.path.join(ROOT, "scripts", "compas-fd-side-by-side", "side_by_side.py")
    spec = importlib.util.spec_from_file_location("compas_side_by_side", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    mod.REPEATS = REPEATS
    return mod


def child(args):
    """Runs `args`: its stdout, wall seconds and CPU seconds (user + system of the child and
    the children it waited for)."""
    import resource

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    out = subprocess.run(args, check=True, stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL).stdout
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return out, wall, cpu


def tower_toml(n):
    """The free tower of N Snelson prisms: scripts/statics-scaling/tower.py's scene."""
    path = os.path.join(ROOT, "scripts", "statics-scaling", "tower.py")
    spec = importlib.util.spec_from_file_location("tower", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.tower_toml(n)


def svd(scene):
    """numpy's statics of a free scene (no supports): JSON on stdout."""
    t0 = time.perf_counter()
    import numpy as np
    import tomllib

    imported = time.perf_counter() - t0
    with open(scene, "rb") as f:
        s = tomllib.load(f)
    assert not s.get("supports"), "svd: free scenes only (every node's 3 rows kept)"
    x = np.array(s["nodes"], dtype=float)
    members = [m["nodes"] for m in s.get("bars", []) + s.get("strings", [])]
    t1 = time.perf_counter()
    m, n = 3 * len(x), len(members)
    a = np.zeros((m, n))
    for c, (i, j) in enumerate(members):
        d = x[i] - x[j]
        u = d / np.linalg.norm(d)
        a[3 * i:3 * i + 3, c] = u
        a[3 * j:3 * j + 3, c] = -u
    built = time.perf_counter() - t1
    wall, cpu = time.perf_counter(), time.process_time()
    sigma = np.linalg.svd(a, compute_uv=False)
    rank = int(np.sum(sigma > max(m, n) * np.finfo(float).eps * sigma[0]))
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    json.dump({"rows": m, "members": n, "rank": rank, "self_stress_dim": n - rank,
               "mechanisms": m - rank, "svd_wall_s": wall, "svd_cpu_s": cpu,
               "build_s": built, "import_s": imported}, sys.stdout)


def fmt(s):
    """Seconds, 3 significant digits in a fitting unit (a text as it is)."""
    if s is None:
        return "—"
    if isinstance(s, str):
        return s
    if s >= 1:
        return f"{s:.3g} s"
    if s >= 1e-3:
        return f"{s * 1e3:.3g} ms"
    return f"{s * 1e6:.3g} µs"


def ratio(peer, ours):
    """peer / ours where both were measured in this run."""
    if isinstance(peer, float) and isinstance(ours, float) and ours > 0:
        r = peer / ours
        return f"{r:,.0f}×" if r >= 100 else f"{r:.3g}×"
    return "—"


def compas_rows(rows, versions):
    fd = load_compas_helper()
    grid_cost = fd.GRID_COST
    have_cost = os.path.exists(grid_cost)
    for k in [int(k) for k in os.environ.get("GRIDS", "27 85").split()]:
        nodes, members, q, fixed = fd.grid(k)
        best = {}
        ours = peer = None
        for _ in range(REPEATS):
            out, _, cpu = child([BIN, "formfind", "--builtin", f"grid:{k}", "--json"])
            ours = json.loads(out)
            best["ours_cpu"] = min(best.get("ours_cpu", 1e300), cpu)
            out, _, cpu = child([sys.executable, fd.__file__, "compas", str(k)])
            peer = json.loads(out)
            best["fd_cpu"] = min(best.get("fd_cpu", 1e300), cpu)
            best["fd_solve"] = min(best.get("fd_solve", 1e300), peer["solve_wall_s"])
            if have_cost:
                form, _ = fd.ours_solve(k)
                best["ours_solve"] = min(best.get("ours_solve", 1e300), form)
        # the same grid (the checks of the compas helper's table)
        assert ours["n_bars"] + ours["n_strings"] == len(members), "not the same grid"
        assert ours["force_density"] == q, "not the same force densities"
        assert all(ours["nodes"][i] == nodes[i] for i in fixed), "not the same held nodes"
        dmax = max(abs(a - b) for p, s in zip(ours["nodes"], peer["nodes"]) for a, b in zip(p, s))
        problem = f"form-finding grid:{k} ({len(members):,} members)"
        agree = f"nodes within {dmax:.1e} m"
        rows.append((problem, versions["compas_fd"], "process CPU",
                     best["fd_cpu"], best["ours_cpu"], agree))
        rows.append((problem, versions["compas_fd"], "solve alone (wall): fd_numpy / form_find",
                     best["fd_solve"], best.get("ours_solve"), agree))


def agreement(ours, peer):
    """Rank and self-stress dimension of our report against numpy's."""
    same = (ours["rank"], ours["self_stress_dim"]) == (peer["rank"], peer["self_stress_dim"])
    return (f"rank {ours['rank']}, self-stress {ours['self_stress_dim']}: "
            + ("equal" if same else f"DIFFER (numpy {peer['rank']}, {peer['self_stress_dim']})"))


def numpy_rows(rows, versions):
    for n in [int(n) for n in os.environ.get("TOWERS", "50 200 800").split()]:
        scene = os.path.join(WORK, f"tower{n}.toml")
        with open(scene, "w") as f:
            f.write(tower_toml(n))
        best = {}
        ours = peer = None
        runs = 0
        for _ in range(REPEATS):
            out, _, cpu = child([BIN, "statics", scene, "--json", "--max-work", "100000"])
            ours = json.loads(out)
            best["ours_cpu"] = min(best.get("ours_cpu", 1e300), cpu)
            out, _, cpu = child([sys.executable, __file__, "svd", scene])
            peer = json.loads(out)
            best["np_cpu"] = min(best.get("np_cpu", 1e300), cpu)
            best["np_svd"] = min(best.get("np_svd", 1e300), peer["svd_cpu_s"])
            runs += 1
            if cpu > SVD_REPEAT_MAX_S:
                break  # a dense SVD of minutes: one run of each
        once = "" if runs == REPEATS else f" ({runs} run)"
        agree = agreement(ours, peer)
        method = ours.get("statics_method", "svd")
        problem = (f"statics, free tower of {n} prisms ({peer['members']:,} members, "
                   f"A {peer['rows']:,} × {peer['members']:,}; ours: {method})")
        rows.append((problem, versions["numpy"], "process CPU" + once,
                     best["np_cpu"], best["ours_cpu"], agree))
        rows.append((problem, versions["numpy"],
                     "numpy SVD + rank alone (CPU) / our whole process" + once,
                     best["np_svd"], best["ours_cpu"], agree))
        if os.path.exists(STATICS_COST):
            # the rank alone on both sides: numpy's SVD and rank, our factorisation and rank
            out, _, _ = child([STATICS_COST, scene])
            cost = json.loads(out)
            same = (cost["rank"], cost["self_stress_dim"]) == (peer["rank"],
                                                             peer["self_stress_dim"])
            rows.append((problem, versions["numpy"],
                         "numpy SVD + rank alone (CPU) / our factorisation + rank alone "
                         "(wall, in-process)" + once,
                         best["np_svd"], cost["rank_s"],
                         agree if same else "rank or self-stress dimension differ"))
        if peer["members"] <= DENSE_MEMBERS_MAX:
            # SVD against SVD: our dense path (the SVD with its vectors, then the same report)
            for _ in range(runs):
                out, _, cpu = child([BIN, "statics", scene, "--json", "--method", "dense"])
                dense = json.loads(out)
                best["dense_cpu"] = min(best.get("dense_cpu", 1e300), cpu)
            rows.append((problem, versions["numpy"],
                         "numpy SVD + rank alone (CPU) / our whole process, --method dense",
                         best["np_svd"], best["dense_cpu"], agreement(dense, peer)))


def tsgfem_checkout():
    """A TsgFEM work tree from $TSGFEM (a work tree, or a git directory exported here), and
    its commit; or None and why not."""
    src = os.environ.get("TSGFEM", "")
    if not src or not os.path.isdir(src):
        return None, None, "no TsgFEM checkout (set TSGFEM to a work tree or its git directory)"
    if os.path.isdir(os.path.join(src, "Function_library")):
        rev = subprocess.run(["git", "-C", src, "rev-parse", "--short", "HEAD"],
                             capture_output=True, text=True).stdout.strip() or "?"
        return src, rev, None
    rev = subprocess.run(["git", "--git-dir", src, "rev-parse", "--short", "HEAD"],
                         capture_output=True, text=True).stdout.strip()
    if not rev:
        return None, None, f"{src} is neither a TsgFEM work tree nor a git directory"
    tree = os.path.join(WORK, "tsgfem")
    # its MATLAB sources only (a mirror may lack the large .mat and .gif files)
    names = subprocess.run(["git", "--git-dir", src, "ls-tree", "-r", "--name-only", "HEAD"],
                           check=True, capture_output=True, text=True).stdout.splitlines()
    sources = [p for p in names if p.endswith(".m")]
    data = subprocess.run(["git", "--git-dir", src, "archive", "HEAD", "--"] + sources,
                          check=True, capture_output=True).stdout
    with tarfile.open(fileobj=io.BytesIO(data)) as t:
        t.extractall(tree, filter="data")
    return tree, rev, None


def tsgfem_rows(rows, versions):
    problem = "dynamics, TsgFEM T-bar with slack strings (8013 RK4 steps)"
    scene = os.path.join(ROOT, "examples", "anchors", "tsgfem_tbar_elastic.toml")
    ours_args = [BIN, "simulate", scene, "--no-convergence-check", "--json"]
    best = {}
    ours = None
    for _ in range(REPEATS):
        out, _, cpu = child(ours_args)
        ours = json.loads(out)
        best["ours_cpu"] = min(best.get("ours_cpu", 1e300), cpu)
        best["ours_int"] = min(best.get("ours_int", 1e300), ours["wall_time_s"])
    octave = shutil.which("octave")
    tree, rev, why = tsgfem_checkout()
    if octave is None:
        why = "GNU Octave is not installed"
    if why:
        rows.append((problem, "TsgFEM: no reference run at hand", why,
                     None, best["ours_int"], "—"))
        return
    version = subprocess.run([octave, "--version"], capture_output=True,
                             text=True).stdout.splitlines()[0].replace("GNU Octave, version ", "")
    peer_name = f"TsgFEM {rev} (GNU Octave {version})"
    out_dir = os.path.join(WORK, "tsgfem_out")
    os.makedirs(out_dir, exist_ok=True)
    result = os.path.join(out_dir, "tsgfem_tbar_dynamics_slack.json")
    export = [sys.executable, os.path.join(ROOT, "scripts", "tsgfem-export"), tree, out_dir,
              "tbar_dynamics_slack"]
    for _ in range(REPEATS):
        _, _, cpu = child(export)
        if not os.path.exists(result):
            rows.append((problem, peer_name, "the export failed: no reference run at hand",
                         None, best["ours_int"], "—"))
            return
        peer = json.load(open(result))
        best["peer_cpu"] = min(best.get("peer_cpu", 1e300), cpu)
        best["peer_int"] = min(best.get("peer_int", 1e300), peer["solver_seconds"])
    state = peer["state_end"]
    nn = len(state) // 6
    final = [state[3 * i:3 * i + 3] for i in range(nn)]
    d = max(abs(a - b) for p, s in zip(ours["final_nodes"], final) for a, b in zip(p, s))
    agree = f"final nodes within {d:.1e} m ({peer['steps']} / {ours['steps']} steps)"
    rows.append((problem, peer_name, "process CPU (Octave: start, set-up, modes, export)",
                 best["peer_cpu"], best["ours_cpu"], agree))
    rows.append((problem, peer_name, "integration alone (wall): dynamic_solver tic/toc / wall_time_s",
                 best["peer_int"], best["ours_int"], agree))


def motes_rows(rows):
    scene = os.path.join(ROOT, "examples", "anchors", "motes_dbar.toml")
    best = None
    for _ in range(REPEATS):
        _, _, cpu = child([BIN, "simulate", scene, "--json"])
        best = cpu if best is None else min(best, cpu)
    seconds, when = MOTES_DBAR
    rows.append(("dynamics, MOTES D-bar (5000 RK4 steps)",
                 "MOTES: no reference run at hand (not set up on this machine)",
                 "process CPU",
                 f"stored: {seconds} s ({when})", best, "—"))


def table():
    rows = []
    import numpy
    import scipy

    versions = {"numpy": f"numpy {numpy.__version__} (LAPACK gesdd, values only)"}
    try:
        import compas_fd

        versions["compas_fd"] = (f"compas_fd {compas_fd.__version__} (scipy {scipy.__version__}, "
                                 f"numpy {numpy.__version__})")
    except ImportError:
        versions["compas_fd"] = None
    if versions["compas_fd"]:
        compas_rows(rows, versions)
    numpy_rows(rows, versions)
    tsgfem_rows(rows, versions)
    motes_rows(rows)
    print("| problem | peer, version | what is timed | peer | ours | peer / ours | agreement |")
    print("|---|---|---|---:|---:|---:|---|")
    for problem, peer, what, tp, to, agree in rows:
        print(f"| {problem} | {peer} | {what} | {fmt(tp)} | {fmt(to)} | {ratio(tp, to)} | {agree} |")
    print()
    print(f"best of {REPEATS} for every time; process CPU = user + system of the whole child "
          "process (its start and imports included); load average at the end: "
          + " ".join(f"{x:.2f}" for x in os.getloadavg()))


if __name__ == "__main__":
    if sys.argv[1] == "svd":
        svd(sys.argv[2])
    else:
        table()
