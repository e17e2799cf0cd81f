"""jax-fdm against `tensegrity design` on two of jax-fdm's published inverse form-finding
examples (issue 47): the cable-net prestress of its docs (docs/examples/cablenet.md: a 10 x 10
quad net hung from four corners, a diagonal pair lifted 5 m, 220 force densities >= 0.1, the
boundary cables' forces aimed at 20 and the interior cables' lengths at 1, mean squared error
each, L-BFGS-B, maxiter 1000, tol 1e-8) and the dome of its examples (examples/dome/dome.py:
8 sides, 30 rings, compression-only force densities <= -1e-6, the cross edges' lengths aimed
at 0.03 and their directions at an angle rising from 15 to 45 degrees, squared error,
L-BFGS-B, maxiter 10000, tol 1e-8).

Run by run.sh beside it (which makes the venv with jax-fdm from PyPI and builds the release
binary). Two modes:

  side_by_side.py export DIR        build both problems with jax-fdm's own datastructures and
                                    write them as design files (DIR/cablenet.toml,
                                    DIR/dome.toml): the same nodes, edges, supports, loads,
                                    start force densities, bounds, goals and stopping rules
  side_by_side.py table [TOL]       for each problem: jax-fdm's constrained_fdm (jax on CPU,
                                    the first call with its compilation and the best of
                                    REPEATS warm calls) and `tensegrity design FILE --json`
                                    (best of REPEATS, whole process, wall), each with the
                                    stopping rules of the example (or TOL for ftol and gtol of
                                    both, an iteration cap of 100 000 and scipy's evaluation cap
                                    raised to ours, 1.5 million), and the objective of
                                    each result recomputed here by one formula from its forces
                                    and geometry

scipy's L-BFGS-B takes `tol` as both its ftol and gtol; the design files say the same.
"""

import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.environ.get("TENSEGRITY_BIN", os.path.join(ROOT, "target", "release", "tensegrity"))
REPEATS = int(os.environ.get("REPEATS", "3"))
# PROBLEMS=dome runs one of them
# the iteration cap of both codes when a tolerance is given (the optimum itself compared)
TIGHT_MAXITER = 100000


# ------------------------------------------------------------------------------------------
# the two problems, built as jax-fdm's examples build them
# ------------------------------------------------------------------------------------------


def cablenet():
    from jax_fdm.datastructures import FDMesh
    from jax_fdm.goals import EdgeForceGoal, EdgeLengthGoal
    from jax_fdm.losses import Loss, MeanSquaredError
    from jax_fdm.parameters import EdgeForceDensityParameter

    mesh = FDMesh.from_meshgrid(10.0, nx=10)
    boundary = [e for e in mesh.edges() if mesh.is_edge_on_boundary(e)]
    interior = [e for e in mesh.edges() if not mesh.is_edge_on_boundary(e)]
    corners = list(mesh.vertices_where(vertex_degree=2))
    mesh.vertices_supports(corners)
    mesh.vertex_attribute(corners[0], "z", 5.0)
    mesh.vertex_attribute(corners[-1], "z", 5.0)
    for e in mesh.edges():
        force = 20.0 if mesh.is_edge_on_boundary(e) else 1.0
        mesh.edge_forcedensity(e, force / mesh.edge_length(e))
    parameters = [EdgeForceDensityParameter(e, 0.1, None) for e in mesh.edges()]
    loss = Loss(
        MeanSquaredError([EdgeForceGoal(e, target=20.0) for e in boundary], name="BoundaryForce"),
        MeanSquaredError([EdgeLengthGoal(e, target=1.0) for e in interior], name="InteriorLength"),
    )
    edges = list(mesh.edges())
    index = {e: k for k, e in enumerate(edges)}
    problem = {
        "name": "cablenet",
        "kind": "strings",
        "nodes": [mesh.vertex_coordinates(v) for v in mesh.vertices()],
        "vertex": {v: i for i, v in enumerate(mesh.vertices())},
        "edges": edges,
        "q": [mesh.edge_forcedensity(e) for e in edges],
        "supports": corners,
        "loads": {},
        "bounds": (0.1, None),
        "terms": [
            ("BoundaryForce", "mean_squared", "force", [index[e] for e in boundary], 20.0),
            ("InteriorLength", "mean_squared", "length", [index[e] for e in interior], 1.0),
        ],
        "maxiter": 1000,
        "tol": 1e-8,
    }
    return mesh, parameters, loss, problem


def dome():
    from compas.geometry import (
        Polygon,
        add_vectors,
        cross_vectors,
        offset_polygon,
        rotate_points,
        subtract_vectors,
    )
    from compas.itertools import pairwise
    from jax_fdm.datastructures import FDNetwork
    from jax_fdm.goals import EdgeDirectionGoal, EdgeLengthGoal
    from jax_fdm.losses import Loss, SquaredError
    from jax_fdm.parameters import EdgeForceDensityParameter

    num_sides, num_rings = 8, 30
    network = FDNetwork()
    polygon = Polygon.from_sides_and_radius_xy(num_sides, 0.5).points
    rings = []
    for _ in range(num_rings + 1):
        polygon = offset_polygon(polygon, 0.01)
        rings.append([network.add_node(x=x, y=y, z=z) for x, y, z in polygon])
    for ring in rings[1:]:
        for u, v in pairwise(ring + ring[:1]):
            network.add_edge(u, v)
    for i in range(num_sides):
        for u, v in pairwise([ring[i] for ring in rings]):
            network.add_edge(u, v)
    cross_rings = [list(zip(*pair)) for pair in pairwise(rings)]
    for node in rings[0]:
        network.node_anchor(node)
    for node in network.nodes_free():
        network.node_load(node, load=[0.0, 0.0, -0.1])
    scale = math.sqrt(network.number_of_edges()) / 2.0
    for ring in rings[1:]:
        for u, v in pairwise(ring + ring[:1]):
            network.edge_forcedensity((u, v), -2.0)
    for i, cross_ring in enumerate(cross_rings):
        for e in cross_ring:
            network.edge_forcedensity(e, -0.5 * scale * (num_rings - i))
    parameters = [EdgeForceDensityParameter(e, None, -1e-6) for e in network.edges()]
    goals = []
    for cross_ring in cross_rings:
        for e in cross_ring:
            goals.append(EdgeLengthGoal(e, target=0.03, weight=1.0))
    directions = []
    for i, cross_ring in enumerate(cross_rings):
        angle = 15.0 + 30.0 * (i / (num_rings - 1))
        for u, v in cross_ring:
            xyz = network.node_coordinates(u)
            normal = cross_vectors(network.edge_vector((u, v)), [0.0, 0.0, 1.0])
            point = add_vectors(xyz, [0.0, 0.0, 1.0])
            end = rotate_points([point], -math.radians(angle), axis=normal, origin=xyz).pop()
            vector = subtract_vectors(end, xyz)
            goals.append(EdgeDirectionGoal((u, v), target=vector, weight=1.0))
            directions.append(((u, v), vector))
    loss = Loss(SquaredError(goals=goals))
    edges = list(network.edges())
    index = {e: k for k, e in enumerate(edges)}
    lengths = [index[e] for cross_ring in cross_rings for e in cross_ring]
    problem = {
        "name": "dome",
        "kind": "bars",
        "nodes": [network.node_coordinates(n) for n in network.nodes()],
        "vertex": {n: i for i, n in enumerate(network.nodes())},
        "edges": edges,
        "q": [network.edge_forcedensity(e) for e in edges],
        "supports": list(rings[0]),
        "loads": {n: [0.0, 0.0, -0.1] for n in network.nodes_free()},
        "bounds": (None, -1e-6),
        "terms": [
            ("SquaredError", "squared", "length", lengths, 0.03),
            ("SquaredError", "squared", "direction", [index[e] for e, _ in directions],
             [v for _, v in directions]),
        ],
        "maxiter": 10000,
        "tol": 1e-8,
    }
    return network, parameters, loss, problem


PROBLEMS = {"cablenet": cablenet, "dome": dome}


# ------------------------------------------------------------------------------------------
# the design file
# ------------------------------------------------------------------------------------------


def num(x):
    return repr(float(x))


def vec(v):
    return "[" + ", ".join(num(x) for x in v) + "]"


def design_toml(p, tol=None):
    maxiter = p["maxiter"] if tol is None else TIGHT_MAXITER
    tol = p["tol"] if tol is None else tol
    vid = p["vertex"]
    out = [
        f"# jax-fdm's {p['name']} example as a design file, written by",
        "# scripts/jaxfdm-side-by-side/side_by_side.py export (the problem built with jax-fdm's",
        "# own datastructures: the same nodes, edges, supports, loads, start force densities,",
        "# bounds, goals and stopping rules).",
        f"#   tensegrity design examples/design/{p['name']}.toml",
        "",
        "nodes = [",
    ]
    out += [f"  {vec(x)}," for x in p["nodes"]]
    out.append("]")
    table = "bars" if p["kind"] == "bars" else "strings"
    for (u, v), q in zip(p["edges"], p["q"]):
        out += ["", f"[[{table}]]", f"nodes = [{vid[u]}, {vid[v]}]", f"force_density = {num(q)}"]
    for s in p["supports"]:
        out += ["", "[[fixed]]", f"node = {vid[s]}", f"position = {vec(p['nodes'][vid[s]])}"]
    for n, load in p["loads"].items():
        out += ["", "[[loads]]", f"node = {vid[n]}", f"force = {vec(load)}"]
    out += [
        "",
        "[design.optimizer]",
        f"max_iterations = {maxiter}",
        f"ftol = {num(tol)}",
        f"gtol = {num(tol)}",
        "",
        "[[design.parameters]]",
        "select = \"all\"",
    ]
    lower, upper = p["bounds"]
    if (lower is None or lower < 0) and (upper is None or upper > 0):
        # bounds across zero: jax-fdm's edges have no kind, ours keep their sign unless told
        out.append("sign = \"free\"")
    if lower is not None:
        out.append(f"lower = {num(lower)}")
    if upper is not None:
        out.append(f"upper = {num(upper)}")
    for name, error, kind, members, target in p["terms"]:
        out += ["", "[[design.terms]]", f"name = \"{name}\"", f"error = \"{error}\""]
        out += ["[[design.terms.goals]]", f"kind = \"{kind}\"", f"members = {members}"]
        if isinstance(target, list):
            out.append("targets = [" + ", ".join(vec(t) for t in target) + "]")
        else:
            out.append(f"target = {num(target)}")
    return "\n".join(out) + "\n"


# ------------------------------------------------------------------------------------------
# one objective formula for both results
# ------------------------------------------------------------------------------------------


def objective(p, forces, lengths, vectors):
    """The example's loss from the result's member forces, lengths and vectors."""
    total = 0.0
    for _, error, kind, members, target in p["terms"]:
        errs = []
        for j, k in enumerate(members):
            if kind == "force":
                errs.append((forces[k] - target) ** 2)
            elif kind == "length":
                errs.append((lengths[k] - target) ** 2)
            else:
                t = target[j]
                tn = math.sqrt(sum(x * x for x in t))
                v = vectors[k]
                vn = math.sqrt(sum(x * x for x in v))
                errs.append(sum((v[c] / vn - t[c] / tn) ** 2 for c in range(3)))
        s = sum(errs)
        total += s / len(errs) if error == "mean_squared" else s
    return total


def jax_run(name, tol):
    from jax_fdm.equilibrium import constrained_fdm
    from jax_fdm.optimization import LBFGSB

    times = []
    result = None
    for _ in range(REPEATS + 1):
        ds, parameters, loss, p = PROBLEMS[name]()
        t0 = time.perf_counter()
        result = constrained_fdm(
            ds,
            # with a tolerance, scipy's cap of 15 000 evaluations lifted as ours is
            optimizer=LBFGSB() if tol is None else LBFGSB(maxfun=15 * TIGHT_MAXITER),
            loss=loss,
            parameters=parameters,
            maxiter=p["maxiter"] if tol is None else TIGHT_MAXITER,
            tol=p["tol"] if tol is None else tol,
        )
        times.append(time.perf_counter() - t0)
    edges = p["edges"]
    forces = [result.edge_force(e) for e in edges]
    lengths = [result.edge_length(e) for e in edges]
    vectors = [result.edge_vector(e) for e in edges]
    q = [result.edge_forcedensity(e) for e in edges]
    return p, times[0], min(times[1:]), objective(p, forces, lengths, vectors), q


def ours_run(p, tol):
    path = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"jaxfdm-{p['name']}.toml")
    with open(path, "w") as f:
        f.write(design_toml(p, tol))
    best, report = math.inf, None
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        out = subprocess.run([BIN, "design", path, "--json"], check=True, capture_output=True)
        best = min(best, time.perf_counter() - t0)
        report = json.loads(out.stdout)
    nodes = report["nodes"]
    vid = p["vertex"]
    vectors = [
        [nodes[vid[v]][c] - nodes[vid[u]][c] for c in range(3)] for (u, v) in p["edges"]
    ]
    mine = objective(p, report["force"], report["length"], vectors)
    return best, mine, report


def table(tol):
    print(f"| problem | tol | jax-fdm objective | ours | relative difference | max |Δq| / max |q| "
          f"| jax-fdm first call (s) | jax-fdm warm (s) | ours, whole process (s) | our iterations |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name in os.environ.get("PROBLEMS", ",".join(PROBLEMS)).split(","):
        p, cold, warm, fj, qj = jax_run(name, tol)
        wall, fo, report = ours_run(p, tol)
        rel = abs(fj - fo) / max(abs(fj), abs(fo))
        qo = report["force_density"]
        dq = max(abs(a - b) for a, b in zip(qj, qo)) / max(abs(a) for a in qj)
        t = p["tol"] if tol is None else tol
        print(f"| {name} | {t:g} | {fj:.10e} | {fo:.10e} | {rel:.1e} | {dq:.1e} | {cold:.2f} "
              f"| {warm:.3f} | {wall:.3f} | {report['iterations']} ({report['stop']}) |")
        sys.stdout.flush()


def main():
    if len(sys.argv) >= 3 and sys.argv[1] == "export":
        os.makedirs(sys.argv[2], exist_ok=True)
        for name, build in PROBLEMS.items():
            _, _, _, p = build()
            with open(os.path.join(sys.argv[2], f"{name}.toml"), "w") as f:
                f.write(design_toml(p))
        return
    if len(sys.argv) >= 2 and sys.argv[1] == "table":
        table(float(sys.argv[2]) if len(sys.argv) > 2 else None)
        return
    sys.exit(__doc__)


if __name__ == "__main__":
    main()
