"""jax-fdm against `tensegrity design` on four of jax-fdm's published inverse form-finding
examples (issue 47): the cable-net prestress of its docs (docs/examples/cablenet.md: a 10 x 10
quad net hung from four corners, a diagonal pair lifted 5 m, 220 force densities >= 0.1, the
boundary cables' forces aimed at 20 and the interior cables' lengths at 1, mean squared error
each, L-BFGS-B, maxiter 1000, tol 1e-8), the dome of its examples (examples/dome/dome.py:
8 sides, 30 rings, compression-only force densities <= -1e-6, the cross edges' lengths aimed
at 0.03 and their directions at an angle rising from 15 to 45 degrees, squared error,
L-BFGS-B, maxiter 10000, tol 1e-8) and the pringle of its examples
(examples/pringle/pringle.py: a 10 x 9 vault anchored at its arches' ends, 161 force
densities in [-5, -0.1], the anchors' reaction magnitudes aimed at 0.45 to 2 (weight 100),
every free node kept in its transversal plane (weight 10) and the cross edges at their
lengths, squared errors, SLSQP, maxiter 1000, tol 1e-9) and the monkey saddle of its
examples (examples/monkey_saddle/monkey_saddle.py: its coarse mesh, data/json/
monkey_saddle.json, read from $JAXFDM_DATA or downloaded from GitHub at a pinned commit,
subdivided twice; 216 force densities in [-20, -0.01], every edge's length (weight 1), the
supports' reaction magnitudes rising towards the corners (weight 10), the load path as a
prediction error (alpha 0.01) and the L2 regulariser (alpha 0.1), L-BFGS-B, maxiter 500,
tol 1e-3).

Run by run.sh beside it (which makes the venv with jax-fdm from PyPI and builds the release
binary). Three modes:

  side_by_side.py export DIR        build the problems with jax-fdm's own datastructures and
                                    write them as design files (DIR/cablenet.toml,
                                    DIR/dome.toml, DIR/pringle.toml,
                                    DIR/monkey_saddle.toml): the same nodes, edges,
                                    supports, loads, start force densities, bounds, goals and
                                    stopping rules
  side_by_side.py table [TOL]       for each problem: jax-fdm's constrained_fdm (jax on CPU,
                                    the example's optimiser, the first call with its
                                    compilation and the best of REPEATS warm calls) and
                                    `tensegrity design FILE --json` with each of our
                                    optimisers, lbfgsb and levenberg_marquardt (best of
                                    REPEATS, whole process, wall), each with the stopping
                                    rules of the example (or TOL for ftol and gtol of all, an
                                    iteration cap of 100 000 and scipy's evaluation cap raised
                                    to ours, 1.5 million), and the objective of each result
                                    recomputed here by one formula from its forces, geometry
                                    and reactions
  side_by_side.py optimum           for each sum-of-squares problem: scipy's least_squares (trust-region
                                    reflective, bounds, tolerances 1e-15) on residuals written
                                    here in jax from the problem's arrays (the force density
                                    method by a dense solve, the Jacobian by jax.jacfwd): an
                                    optimum found independently of both codes, against
                                    `tensegrity design --method levenberg_marquardt` at
                                    ftol 1e-15

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
# PROBLEMS=dome runs one of them (default: all)
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


def pringle():
    from compas.geometry import Translation, add_vectors
    from jax_fdm.datastructures import FDNetwork
    from jax_fdm.goals import EdgeLengthGoal, NodePlaneGoal, NodeResidualForceGoal
    from jax_fdm.losses import Loss, SquaredError
    from jax_fdm.parameters import EdgeForceDensityParameter

    length_vault, width_vault, num_u, num_v = 6.0, 3.0, 10, 9
    q_init, pz, rz_min, rz_max = -0.25, -0.1, 0.45, 2.0
    network = FDNetwork()
    length_u = length_vault / (num_u - 1)
    length_v = width_vault / (num_v - 1)
    arches = []
    for i in range(num_v):
        start = add_vectors([0.0, 0.0, 0.0], [0.0, i * length_v, 0.0, 0.0])
        arch = []
        for j in range(num_u):
            x, y, z = add_vectors(start, [j * length_u, 0.0, 0.0])
            arch.append(network.add_node(x=x, y=y, z=z))
        arches.append(arch)
        a = i * num_u
        b = a + num_u - 1
        for u, v in zip(range(a, b), range(a + 1, b + 1)):
            network.add_edge(u, v)
    cross_edges = []
    for i in range(num_u):
        seq = [arch[i] for arch in arches]
        for u, v in zip(seq[:-1], seq[1:]):
            cross_edges.append(network.add_edge(u, v))
    anchors = []
    for arch in arches:
        network.node_anchor(arch[0])
        network.node_anchor(arch[-1])
        anchors += [arch[0], arch[-1]]
    for node in network.nodes_free():
        network.node_load(node, load=[0.0, 0.0, pz])
    for edge in network.edges():
        network.edge_forcedensity(edge, q_init)
    network.transform(Translation.from_vector([-length_vault / 2.0, -width_vault / 2.0, 0.0]))
    num_steps = (num_v - 1) / 2.0
    step = (rz_max - rz_min) / num_steps
    rzs = [rz_min + i * step for i in range(int(num_steps) + 1)]
    rzs = rzs + rzs[0:-1][::-1]
    parameters = [EdgeForceDensityParameter(e, -5.0, -0.1) for e in network.edges()]
    vertex = {n: i for i, n in enumerate(network.nodes())}
    goals_a, reactions = [], []
    for rz, arch in zip(rzs, arches):
        for node in (arch[0], arch[-1]):
            goals_a.append(NodeResidualForceGoal(node, target=rz, weight=100.0))
            reactions.append({"kind": "reaction_force", "nodes": [vertex[node]], "target": rz,
                              "weight": 100.0})
    goals_b, planes = [], []
    for node in network.nodes_free():
        origin = network.node_coordinates(node)
        goals_b.append(NodePlaneGoal(node, target=(origin, [1.0, 0.0, 0.0]), weight=10.0))
        planes.append({"kind": "plane", "nodes": [vertex[node]], "point": origin,
                       "normal": [1.0, 0.0, 0.0], "weight": 10.0})
    edges = list(network.edges())
    index = {e: k for k, e in enumerate(edges)}
    goals_c, lengths = [], []
    for edge in cross_edges:
        target = network.edge_length(edge)
        goals_c.append(EdgeLengthGoal(edge, target=target, weight=1.0))
        lengths.append({"kind": "length", "members": [index[edge]], "target": target,
                        "weight": 1.0})
    loss = Loss(
        SquaredError(goals_a, alpha=1.0, name="ResidualForceGoal"),
        SquaredError(goals_b, alpha=1.0, name="NodePlaneGoal"),
        SquaredError(goals_c, alpha=1.0, name="EdgeLengthGoal"),
    )
    problem = {
        "name": "pringle",
        "kind": "bars",
        "nodes": [network.node_coordinates(n) for n in network.nodes()],
        "vertex": vertex,
        "edges": edges,
        "q": [network.edge_forcedensity(e) for e in edges],
        "supports": anchors,
        "loads": {n: [0.0, 0.0, pz] for n in network.nodes_free()},
        "bounds": (-5.0, -0.1),
        "terms": [
            ("ResidualForceGoal", "squared", reactions),
            ("NodePlaneGoal", "squared", planes),
            ("EdgeLengthGoal", "squared", lengths),
        ],
        "optimizer": "SLSQP",
        "maxiter": 1000,
        "tol": 1e-9,
    }
    return network, parameters, loss, problem


# jax-fdm's coarse monkey-saddle mesh (data/json/monkey_saddle.json, 1.4 kB) at the commit
# read: from $JAXFDM_DATA when set, else downloaded once into target/
JAXFDM_COMMIT = "71d449076d7384104108cfd133108be01278c18d"


def jaxfdm_data(name):
    folder = os.environ.get("JAXFDM_DATA")
    if folder:
        return os.path.join(folder, name)
    path = os.path.join(ROOT, "target", "jaxfdm-data", name)
    if not os.path.exists(path):
        import urllib.request

        os.makedirs(os.path.dirname(path), exist_ok=True)
        url = ("https://raw.githubusercontent.com/arpastrana/jax_fdm/"
               f"{JAXFDM_COMMIT}/data/json/{name}")
        urllib.request.urlretrieve(url, path)
    return path


def monkey_saddle():
    from compas.itertools import pairwise
    from compas.topology import dijkstra_path
    from jax_fdm.datastructures import FDMesh
    from jax_fdm.goals import EdgeLengthGoal, MeshLoadPathGoal, VertexResidualForceGoal
    from jax_fdm.losses import L2Regularizer, Loss, PredictionError, SquaredError
    from jax_fdm.parameters import EdgeForceDensityParameter

    q0, load = -2.0, [0.0, 0.0, -1.0]
    qmin, qmax, rmin, rmax, r_exp = -20.0, -0.01, 4.0, 8.0, 0.5
    mesh = FDMesh.from_json(jaxfdm_data("monkey_saddle.json")).subdivided(scheme="quad", k=2)
    # the supports: the boundary's polyedges (split at the degree-2 corners) shorter than
    # their mean
    corners = {v for v in mesh.vertices() if mesh.vertex_degree(v) == 2}
    boundary = mesh.vertices_on_boundaries()[0]
    if boundary[0] == boundary[-1]:
        boundary = boundary[:-1]
    first = next(i for i, v in enumerate(boundary) if v in corners)
    boundary = boundary[first:] + boundary[:first]
    polyedges, polyedge = [], [boundary[0]]
    for v in boundary[1:] + [boundary[0]]:
        polyedge.append(v)
        if v in corners:
            polyedges.append(polyedge)
            polyedge = [v]
    lengths = {tuple(pe): sum(mesh.edge_length(e) for e in pairwise(pe)) for pe in polyedges}
    mean = sum(lengths.values()) / len(lengths)
    supports = set(v for pe, length in lengths.items() if length < mean for v in pe)
    # each support's target reaction falls with its steps (along the mesh) from a corner
    adjacency = mesh.adjacency
    weight = {(u, v): 1.0 for u in adjacency for v in adjacency[u]}
    steps = {}
    for v in supports:
        steps[v] = 0 if v in corners else min(
            len(dijkstra_path(adjacency, weight, v, c)) - 1 for c in corners)
    top = max(steps.values())
    steps = {v: top - step for v, step in steps.items()}
    for v in supports:
        mesh.vertex_support(v)
    mesh.vertices_loads(load, keys=list(mesh.vertices_free()))
    mesh.edges_forcedensities(q0)
    parameters = [EdgeForceDensityParameter(e, qmin, qmax) for e in mesh.edges()]
    edges = list(mesh.edges())
    index = {e: k for k, e in enumerate(edges)}
    vertex = {v: i for i, v in enumerate(mesh.vertices())}
    goals_a = [EdgeLengthGoal(e, mesh.edge_length(e), weight=1.0) for e in edges]
    length_goals = [{"kind": "length", "members": [index[e]], "target": mesh.edge_length(e),
                     "weight": 1.0} for e in edges]
    goals_b, reaction_goals = [], []
    for v in mesh.vertices_supports():
        reaction = (1 - steps[v] / top) ** r_exp * (rmax - rmin) + rmin
        goals_b.append(VertexResidualForceGoal(v, reaction, weight=10.0))
        reaction_goals.append({"kind": "reaction_force", "nodes": [vertex[v]],
                               "target": reaction, "weight": 10.0})
    loss = Loss(
        SquaredError(goals_a, alpha=1.0, name="EdgeLengthGoal"),
        SquaredError(goals_b, alpha=1.0, name="ReactionForceGoal"),
        PredictionError([MeshLoadPathGoal()], alpha=0.01, name="LoadPathGoal"),
        L2Regularizer(alpha=0.1),
    )
    problem = {
        "name": "monkey_saddle",
        "kind": "bars",
        "nodes": [mesh.vertex_coordinates(v) for v in mesh.vertices()],
        "vertex": vertex,
        "edges": edges,
        "q": [mesh.edge_forcedensity(e) for e in edges],
        "supports": list(mesh.vertices_supports()),
        "loads": {v: load for v in mesh.vertices_free()},
        "bounds": (qmin, qmax),
        "terms": [
            ("EdgeLengthGoal", "squared", length_goals),
            ("ReactionForceGoal", "squared", reaction_goals),
            ("LoadPathGoal", "prediction", [{"kind": "load_path"}], 0.01),
            ("L2Regularizer", "squared", [{"kind": "force_density"}], 0.1),
        ],
        "maxiter": 500,
        "tol": 1e-3,
    }
    return mesh, parameters, loss, problem


PROBLEMS = {"cablenet": cablenet, "dome": dome, "pringle": pringle,
            "monkey_saddle": monkey_saddle}


# ------------------------------------------------------------------------------------------
# the design file
# ------------------------------------------------------------------------------------------


def num(x):
    return repr(float(x))


def vec(v):
    return "[" + ", ".join(num(x) for x in v) + "]"


def term_weight(term):
    return term[3] if isinstance(term[2], list) and len(term) == 4 else 1.0


def least_squares_only(p):
    """Whether every term is a sum of squares (levenberg_marquardt's problems)."""
    return all(term[1] in ("squared", "mean_squared") for term in p["terms"])


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
    for term in p["terms"]:
        name, error = term[0], term[1]
        out += ["", "[[design.terms]]", f"name = \"{name}\"", f"error = \"{error}\""]
        if term_weight(term) != 1.0:
            out.append(f"weight = {num(term_weight(term))}")
        for goal in goals_of(term):
            out.append("[[design.terms.goals]]")
            for key, value in goal.items():
                if key == "targets" and isinstance(value[0], list):
                    out.append("targets = [" + ", ".join(vec(t) for t in value) + "]")
                elif isinstance(value, str):
                    out.append(f"{key} = \"{value}\"")
                elif isinstance(value, list) and key in ("nodes", "members"):
                    out.append(f"{key} = {value}")
                elif isinstance(value, list):
                    out.append(f"{key} = {vec(value)}")
                else:
                    out.append(f"{key} = {num(value)}")
    return "\n".join(out) + "\n"


def goals_of(term):
    """A term's goals as dicts: (name, error, [goal, ...]) or (name, error, [goal, ...],
    term weight), or the one-goal short form (name, error, kind, members, target or
    targets)."""
    if isinstance(term[2], list):
        return term[2]
    _, _, kind, members, target = term
    goal = {"kind": kind, "members": members}
    goal["targets" if isinstance(target, list) else "target"] = target
    return [goal]


# ------------------------------------------------------------------------------------------
# one objective formula for both results
# ------------------------------------------------------------------------------------------


def objective(p, forces, lengths, vectors, nodes, reactions):
    """The example's loss from the result's member forces, lengths and vectors, node positions
    (by file index) and reactions (by file index of the held node)."""
    total = 0.0
    q = [f / length for f, length in zip(forces, lengths)]
    every = list(range(len(forces)))
    for term in p["terms"]:
        error = term[1]
        errs = []
        for goal in goals_of(term):
            kind, w = goal["kind"], goal.get("weight", 1.0)
            if kind == "load_path":
                errs.append(w * sum(abs(q[k]) * lengths[k] ** 2 for k in every))
                continue
            items = goal.get("members", goal.get("nodes", every))
            targets = goal.get("targets") or [goal.get("target", 0.0)] * len(items)
            for k, t in zip(items, targets):
                if kind == "force_density":
                    errs.append(w * (q[k] - t) ** 2)
                elif kind == "force":
                    errs.append(w * (forces[k] - t) ** 2)
                elif kind == "length":
                    errs.append(w * (lengths[k] - t) ** 2)
                elif kind == "reaction_force":
                    errs.append(w * (math.sqrt(sum(x * x for x in reactions[k])) - t) ** 2)
                elif kind == "plane":
                    n = goal["normal"]
                    nn = math.sqrt(sum(x * x for x in n))
                    d = sum((nodes[k][c] - goal["point"][c]) * n[c] / nn for c in range(3))
                    errs.append(w * d * d)
                else:
                    tn = math.sqrt(sum(x * x for x in t))
                    v = vectors[k]
                    vn = math.sqrt(sum(x * x for x in v))
                    errs.append(w * sum((v[c] / vn - t[c] / tn) ** 2 for c in range(3)))
        s = sum(errs)
        total += term_weight(term) * (s / len(errs) if error == "mean_squared" else s)
    return total


def jax_run(name, tol):
    from jax_fdm.equilibrium import constrained_fdm
    from jax_fdm.optimization import LBFGSB, SLSQP

    times = []
    result = None
    for _ in range(REPEATS + 1):
        ds, parameters, loss, p = PROBLEMS[name]()
        if p.get("optimizer") == "SLSQP":
            optimizer = SLSQP()
        else:
            # with a tolerance, scipy's cap of 15 000 evaluations lifted as ours is
            optimizer = LBFGSB() if tol is None else LBFGSB(maxfun=15 * TIGHT_MAXITER)
        t0 = time.perf_counter()
        result = constrained_fdm(
            ds,
            optimizer=optimizer,
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
    vid = p["vertex"]
    nodes = [None] * len(vid)
    reactions = [None] * len(vid)
    # a network's nodes, a mesh's vertices
    coordinates = getattr(result, "node_coordinates", None) or result.vertex_coordinates
    residual = getattr(result, "node_residual", None) or result.vertex_residual
    for n, i in vid.items():
        nodes[i] = coordinates(n)
        reactions[i] = residual(n)
    f = objective(p, forces, lengths, vectors, nodes, reactions)
    return p, times[0], min(times[1:]), f, q


def ours_run(p, tol, method="lbfgsb"):
    path = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"jaxfdm-{p['name']}.toml")
    with open(path, "w") as f:
        f.write(design_toml(p, tol))
    best, report = math.inf, None
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        out = subprocess.run([BIN, "design", path, "--method", method, "--json"], check=True,
                             capture_output=True)
        best = min(best, time.perf_counter() - t0)
        report = json.loads(out.stdout)
    nodes = report["nodes"]
    vid = p["vertex"]
    vectors = [
        [nodes[vid[v]][c] - nodes[vid[u]][c] for c in range(3)] for (u, v) in p["edges"]
    ]
    reactions = [None] * len(nodes)
    for s, r in zip(p["supports"], report["reactions"]):
        reactions[vid[s]] = r
    mine = objective(p, report["force"], report["length"], vectors, nodes, reactions)
    return best, mine, report


def table(tol):
    print("| problem | tol | jax-fdm (optimiser) | ours, lbfgsb | ours, levenberg_marquardt "
          "| lbfgsb vs jax-fdm | jax-fdm first call (s) | jax-fdm warm (s) | ours lbfgsb (s) "
          "| ours levenberg_marquardt (s) | iterations (lbfgsb, levenberg_marquardt) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for name in os.environ.get("PROBLEMS", ",".join(PROBLEMS)).split(","):
        p, cold, warm, fj, _ = jax_run(name, tol)
        wall, fo, report = ours_run(p, tol)
        if least_squares_only(p):
            wall_lm, fl, report_lm = ours_run(p, tol, "levenberg_marquardt")
            lm = f"{fl:.10e}", f"{wall_lm:.3f}", f"{report_lm['iterations']} ({report_lm['stop']})"
        else:
            lm = "— (not a sum of squares)", "—", "—"
        rel = abs(fj - fo) / max(abs(fj), abs(fo))
        t = p["tol"] if tol is None else tol
        print(f"| {name} | {t:g} | {fj:.10e} ({p.get('optimizer', 'L-BFGS-B')}) | {fo:.10e} "
              f"| {lm[0]} | {rel:.1e} | {cold:.2f} | {warm:.3f} | {wall:.3f} | {lm[1]} "
              f"| {report['iterations']} ({report['stop']}), {lm[2]} |")
        sys.stdout.flush()


def residuals_in_jax(p):
    """The problem's residuals (f = |r|^2, as our design file defines them) as a jax function
    of the force densities: the force density method by a dense solve."""
    import jax
    import jax.numpy as jnp
    import numpy as np

    jax.config.update("jax_enable_x64", True)
    vid = p["vertex"]
    x0 = np.array(p["nodes"], dtype=float)
    n, m = len(x0), len(p["edges"])
    c = np.zeros((m, n))
    for k, (u, v) in enumerate(p["edges"]):
        c[k, vid[u]], c[k, vid[v]] = -1.0, 1.0
    fixed = [vid[s] for s in p["supports"]]
    free = [i for i in range(n) if i not in set(fixed)]
    loads = np.zeros((n, 3))
    for node, load in p["loads"].items():
        loads[vid[node]] += load
    cf, cx, xfix = c[:, free], c[:, fixed], x0[fixed]

    def residuals(q):
        a = cf.T @ (q[:, None] * cf)
        b = loads[free] - cf.T @ (q[:, None] * (cx @ xfix))
        x = jnp.zeros((n, 3)).at[jnp.array(free)].set(jnp.linalg.solve(a, b))
        x = x.at[jnp.array(fixed)].set(xfix)
        vectors = c @ x
        lengths = jnp.linalg.norm(vectors, axis=1)
        # the force on each node from its members, less its load: a held node's reaction
        # (up to its sign, which a magnitude ignores)
        nodal = c.T @ (q[:, None] * vectors) - loads
        out = []
        for term in p["terms"]:
            parts = []
            for goal in goals_of(term):
                w = math.sqrt(goal.get("weight", 1.0))
                items = goal.get("members", goal.get("nodes"))
                targets = goal.get("targets") or [goal.get("target")] * len(items)
                for k, t in zip(items, targets):
                    kind = goal["kind"]
                    if kind == "force":
                        parts.append(w * (q[k] * lengths[k] - t))
                    elif kind == "length":
                        parts.append(w * (lengths[k] - t))
                    elif kind == "reaction_force":
                        parts.append(w * (jnp.linalg.norm(nodal[k]) - t))
                    elif kind == "plane":
                        normal = np.array(goal["normal"]) / np.linalg.norm(goal["normal"])
                        parts.append(w * jnp.dot(x[k] - np.array(goal["point"]), normal))
                    else:
                        unit = np.array(t) / np.linalg.norm(t)
                        parts.extend(w * (vectors[k] / lengths[k] - unit))
            parts = jnp.stack(parts)
            if term[1] == "mean_squared":
                parts = parts / math.sqrt(len(parts))
            out.append(parts)
        return jnp.concatenate(out)

    return residuals


def optimum():
    import jax
    import numpy as np
    from scipy.optimize import least_squares

    print("| problem | scipy least_squares (trf, jax Jacobian) | its optimality | "
          "ours, levenberg_marquardt at ftol 1e-15 | relative difference | scipy (s) "
          "| ours (s) |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name in os.environ.get("PROBLEMS", ",".join(PROBLEMS)).split(","):
        _, _, _, p = PROBLEMS[name]()
        if not least_squares_only(p):
            continue
        r = jax.jit(residuals_in_jax(p))
        jac = jax.jit(jax.jacfwd(residuals_in_jax(p)))
        lower, upper = p["bounds"]
        lower = -np.inf if lower is None else lower
        upper = np.inf if upper is None else upper
        q0 = np.clip(np.array(p["q"], dtype=float), lower, upper)
        np.asarray(jac(q0))  # compiled before the clock starts
        t0 = time.perf_counter()
        sol = least_squares(lambda q: np.asarray(r(q)), q0, jac=lambda q: np.asarray(jac(q)),
                            bounds=(lower, upper), method="trf", ftol=1e-15, xtol=1e-15,
                            gtol=1e-15, max_nfev=20000)
        scipy_time = time.perf_counter() - t0
        fs = float(np.sum(sol.fun ** 2))
        wall, fo, _ = ours_run(p, 1e-15, "levenberg_marquardt")
        rel = abs(fs - fo) / max(abs(fs), abs(fo))
        print(f"| {name} | {fs:.12e} | {sol.optimality:.1e} | {fo:.12e} | {rel:.1e} "
              f"| {scipy_time:.2f} | {wall:.3f} |")
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
    if len(sys.argv) >= 2 and sys.argv[1] == "optimum":
        optimum()
        return
    sys.exit(__doc__)


if __name__ == "__main__":
    main()
