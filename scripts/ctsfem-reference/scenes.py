#!/usr/bin/env python3
"""Writes this toolkit's scene files (examples/ctsfem/*.toml) from the design numbers that the
Octave drivers dumped from CTSFEM (tests/data/ctsfem/*.json): node coordinates, member
areas, Young's moduli, rest lengths and masses, mapped member by member (a bar: its
material's Young's modulus and radius sqrt(A/pi), so E pi r^2 = E A; a string or a cluster:
stiffness E A / l0 of the whole member, rest length l0 of the whole member).

Usage: scenes.py DATA_DIR EXAMPLES_DIR
"""
import json
import math
import sys
from pathlib import Path


def f(x):
    return repr(float(x))


def nodes_block(nodes):
    return "nodes = [\n" + "".join(f"  [{f(p[0])}, {f(p[1])}, {f(p[2])}],\n" for p in nodes) + "]\n"


def tbar(data, out):
    r = json.loads((data / "tbar.json").read_text())
    Eb, Es = r["youngs_modulus_bar"], r["youngs_modulus_string"]
    A, l0, m = r["area"], r["rest_length"], r["mass"]
    rad = [math.sqrt(a / math.pi) for a in A]

    def members(rest, masses, change=None):
        s = "[materials.ctsfem_q345]\ndensity = 7870.0\n"
        s += f"youngs_modulus = {f(Eb)}\nyield_strength = 300e6\n\n"
        for k, nodes in enumerate([(0, 2), (1, 3)]):
            s += f"[[bars]]\nnodes = [{nodes[0]}, {nodes[1]}]\nmaterial = \"ctsfem_q345\"\n"
            s += f"radius = {f(rad[k])}\nrest_length = {f(l0[k])}\n"
            if masses:
                s += f"mass = {f(m[k])}\n"
            s += "\n"
        s += "[[clusters]]\nnodes = [0, 1, 2]\n"
        s += f"stiffness = {f(Es * A[2] / rest[2])}\nrest_length = {f(rest[2])}\n"
        if change and change[2]:
            s += f"rest_length_change = {f(change[2])}\n"
        s += "\n"
        for k, nodes in [(3, (2, 3)), (4, (3, 0))]:
            s += f"[[strings]]\nnodes = [{nodes[0]}, {nodes[1]}]\n"
            s += f"stiffness = {f(Es * A[k] / rest[k])}\nrest_length = {f(rest[k])}\n"
            if change:
                s += f"rest_length_change = {f(change[k])}\n"
            if masses:
                s += f"mass = {f(m[k + 1])}\n"
            s += "\n"
        return s

    head = """# CTSFEM's clustered T-bar (its example 3Clustered_tensegrity/dynamic/4CTS_Tbar_dynamic,
# CTSFEM commit 13ac83f): a planar rhombus, bars 0-2 and 1-3, one clustered string
# 0 -> 1 -> 2 over a frictionless pulley at node 1, strings 2-3 and 3-0, every node held in z.
# Sizes, Young's moduli (Q345 bars, steel strings) and the prestress (bar 0-2 at -100 N)
# are CTSFEM's design (scripts/ctsfem-reference, tests/data/ctsfem/tbar.json); a bar's
# E pi r^2 is CTSFEM's E A, a string's or the cluster's stiffness its E A / l0.
# Written by scripts/ctsfem-reference/scenes.py; see docs/notes/CTSFEM.md.
"""
    static = head + """#
# Statics (`tensegrity solve`): the example's rest-length changes driven along the load
# path (rest_length_change, EA kept as CTSFEM keeps it): the cluster shortened by 2 m and
# strings 2-3, 3-0 lengthened by 0.5 m each. The
# structure floats in its plane: node 0 is held in x and y and node 2 in y only to remove
# the rigid motions (they carry no force). tests/ctsfem_reference.rs compares the nodes and
# forces with CTSFEM's static_solver_CTS.
"""
    static += nodes_block(r["nodes_initial"]) + "\n"
    rest = list(r["rest_length"])
    change = [r["rest_length_static"][k] - r["rest_length"][k] for k in range(5)]
    static += members(rest, False, change)
    static += '[[supports]]\nnode = 0\ndirections = ["x", "y", "z"]\n\n'
    static += '[[supports]]\nnode = 1\ndirections = ["z"]\n\n'
    static += '[[supports]]\nnode = 2\ndirections = ["y", "z"]\n\n'
    static += '[[supports]]\nnode = 3\ndirections = ["z"]\n'
    (out / "tbar_static.toml").write_text(static)

    dyn = head + f"""#
# Dynamics (`tensegrity simulate`): from the prestressed shape at rest, the cluster's rest
# length is shortened by 0.1 m at t = 0 (a step), and the T-bar vibrates undamped for
# {r["t_end"]} s: elastic bars, CTSFEM's consistent mass matrix (bars and strings rho A l0 with
# rho = 7870 kg/m^3; the cluster massless, as this toolkit's clusters are), RK4 at CTSFEM's
# step. tests/ctsfem_reference.rs compares the nodes and forces with CTSFEM's
# dynamic_solver_CTS (ode4) run on the same problem.
"""
    dyn += nodes_block(r["nodes_initial"]) + "\n"
    dyn += f"""[simulation]
t_end = {f(r["t_end"])}
bars = "elastic"
mass_matrix = "consistent"
integrator = "rk4"
dt = {f(r["dt"])}
output_interval = 0.05

"""
    dyn += members(r["rest_length_dynamic"], True)
    for n in range(4):
        dyn += f'[[supports]]\nnode = {n}\ndirections = ["z"]\n\n'
    (out / "tbar_dynamic.toml").write_text(dyn.rstrip() + "\n")


def members_block(r, rest_key, driven_key=None):
    """Bars, strings and clusters of a CTSFEM model dumped member by member (C's rows) and
    element by element (the clustering matrix S's rows), with the rest lengths r[rest_key]
    per element; bars in member order, then strings, then clusters in S's order. With
    `driven_key`, a cluster whose r[driven_key] differs gets the difference as its
    rest_length_change (driven along `solve`'s load path, its EA kept)."""
    Eb, Es = r["youngs_modulus_bar"], r["youngs_modulus_string"]
    ne = len(r["member_start"])
    ends = [(int(r["member_start"][k]) - 1, int(r["member_end"][k]) - 1) for k in range(ne)]
    first = [int(x) - 1 for x in r["element_members_first"]]
    elem_of = {k: e for e, k in enumerate(first)}
    bars, strings, clusters = "", "", {}
    for k in range(ne):
        c = int(r["member_cluster"][k])
        if c:
            clusters.setdefault(c, []).append(k)
            continue
        e = elem_of[k]
        area, rest = r["element_area"][e], r[rest_key][e]
        if r["member_is_bar"][k]:
            bars += f"[[bars]]\nnodes = [{ends[k][0]}, {ends[k][1]}]\nmaterial = \"ctsfem_q345\"\n"
            bars += f"radius = {f(math.sqrt(area / math.pi))}\nrest_length = {f(rest)}\n\n"
        else:
            strings += f"[[strings]]\nnodes = [{ends[k][0]}, {ends[k][1]}]\n"
            strings += f"stiffness = {f(Es * area / rest)}\nrest_length = {f(rest)}\n\n"
    s = "[materials.ctsfem_q345]\ndensity = 7870.0\n"
    s += f"youngs_modulus = {f(Eb)}\nyield_strength = 300e6\n\n" + bars + strings
    for c in sorted(clusters):
        segs = clusters[c]
        e = elem_of[segs[0]]
        # chain the segments into the path of nodes the string runs through
        path = list(ends[segs[0]])
        left = [ends[k] for k in segs[1:]]
        while left:
            for i, (a, b) in enumerate(left):
                if a == path[-1]:
                    path.append(b)
                elif b == path[-1]:
                    path.append(a)
                elif a == path[0]:
                    path.insert(0, b)
                elif b == path[0]:
                    path.insert(0, a)
                else:
                    continue
                left.pop(i)
                break
            else:
                raise SystemExit(f"cluster {c}: segments do not form a path")
        area, rest = r["element_area"][e], r[rest_key][e]
        s += f"# CTSFEM clustered element {e + 1} (members {[k + 1 for k in segs]})\n"
        s += f"[[clusters]]\nnodes = {path}\n"
        s += f"stiffness = {f(Es * area / rest)}\nrest_length = {f(rest)}\n"
        if driven_key and r[driven_key][e] != rest:
            s += f"rest_length_change = {f(r[driven_key][e] - rest)}\n"
        s += "\n"
    for n in r["pinned_nodes"]:
        s += f"[[supports]]\nnode = {int(n) - 1}\n\n"
    return s


def dome(data, out):
    r = json.loads((data / "dome.json").read_text())
    s = """# CTSFEM's clustered Levy cable dome (its example 3Clustered_tensegrity/static/2cable_dome,
# main_CTS_cable_dome_trajectory.m at deployment rate 0.8; CTSFEM commit 13ac83f): radius
# 50 m, 12 sectors, 2 rings of bars, 30 m high, the 12 outer nodes pinned; 24 bars and 132
# string segments, each of the 7 string groups split into 3 clustered strings (21 clusters
# through 4 or 8 nodes each, frictionless). Sizes, Young's moduli, rest lengths and the
# prestress (one clustered self-stress, scaled by CTSFEM's design to 133.3 kN in one group)
# are CTSFEM's (scripts/ctsfem-reference, tests/data/ctsfem/dome.json): a bar's E pi r^2 is
# CTSFEM's E A, a cluster's stiffness its E A / l0 over the whole cluster.
# `tensegrity solve`: at lambda = 0 the prestressed dome stands as drawn, with CTSFEM's
# prestress in every member (tests/ctsfem_reference.rs). The load, 10 kN down on each of the
# 24 upper nodes, is there for the path to run; it is not compared: the clustered dome is not
# prestress-stable (negative tangent eigenvalues from lambda = 0, `statics` says
# prestress_stable = false), and CTSFEM's solver leaves the symmetric path for a collapse.
# `tensegrity statics` takes the scene without the bars' rest_length lines (the test writes
# that copy): rank 44, one self-stress, CTSFEM's.
# Written by scripts/ctsfem-reference/scenes.py; see docs/notes/CTSFEM.md.
"""
    s += nodes_block(r["nodes_initial"]) + "\n" + members_block(r, "element_rest_length")
    for n in sorted([5 * k for k in range(12)] + [5 * k + 1 for k in range(12)]):
        s += f"[[loads]]\nnode = {n}\nforce = [0.0, 0.0, -1e4]\n\n"
    (out / "cable_dome.toml").write_text(s.rstrip() + "\n")


def prism(data, out):
    r = json.loads((data / "prism.json").read_text())
    s = """# CTSFEM's clustered two-stage prism (its example 3Clustered_tensegrity/dynamic/
# 5CTS_prism_dynamic, main_CTS_prism_dynamics.m, step 1: statics; CTSFEM commit 13ac83f):
# 12 nodes on three levels 1 m apart, the bottom four pinned, 8 bars, 12 ring strings and 4
# clusters, each a vertical string of the lower stage joined over a middle node to one of the
# upper stage. Sizes, Young's moduli and the prestress are CTSFEM's design
# (scripts/ctsfem-reference, tests/data/ctsfem/prism.json; the middle ring's area 1e-8 m^2
# as in the example); a bar's E pi r^2 is CTSFEM's E A, a string's or a cluster's stiffness
# its E A / l0. The example's actuation, the four clusters shortened by 0.7 m each, is
# driven along `tensegrity solve`'s load path (rest_length_change, EA kept as CTSFEM keeps
# it); tests/ctsfem_reference.rs compares its last point (lambda = 1) with CTSFEM's
# static_solver_CTS.
# Written by scripts/ctsfem-reference/scenes.py; see docs/notes/CTSFEM.md.
"""
    s += nodes_block(r["nodes_initial"]) + "\n"
    s += members_block(r, "element_rest_length", "element_rest_length_static")
    (out / "prism_static.toml").write_text(s.rstrip() + "\n")


if __name__ == "__main__":
    data, out = Path(sys.argv[1]), Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    tbar(data, out)
    dome(data, out)
    prism(data, out)
