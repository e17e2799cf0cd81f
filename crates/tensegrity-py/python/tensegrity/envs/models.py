"""The robots of :mod:`tensegrity.envs` as :class:`~tensegrity.Structure` scenes.

* :func:`superball`: the SUPERball layout (NTRT's 6-bar icosahedral robot, the model of
  ``examples/ntrt/superball.yaml``) in SI units, form-found, at rest on a string triangle on
  a penalty ground, its 24 strings the actuators. The expanded octahedron with bars of
  length L: three pairs of parallel bars, the pair along each axis at ±L/4 on the next
  axis; its 24 strings join the node pairs √6/4 L apart (self-stress: bar : string force
  densities −3/2 : 1). Every string gets the stiffness ``k`` and the rest length that gives
  it the pretension ``pretension`` in that geometry.
* :func:`toroid_wheel`: the thesis's 3-bar-prism toroid (``tensegrity toroid``, defaults,
  stiff prestressed strings) standing on a penalty ground, rolling at ``speed`` about its
  axle (x), its strings the actuators.

``python -m tensegrity.envs superball`` prints the scene TOML
(``examples/robots/superball.toml`` is that output).
"""

import itertools
import math

import numpy as np

from ..structure import Structure

#: Gravity of the robot scenes (m/s², along −z).
G = 9.81


def _ground(z, stiffness, damping, mu, v_reg):
    """A penalty ground z = ``z``. The friction's regularisation velocity ``v_reg`` is chosen
    with the model so that RK4 at 1 ms resolves the friction's viscous slope μ f_n / v_reg on
    a contact node's mass (h λ within RK4's stability interval); a smaller one would make the
    explicit step chatter at the friction cap."""
    return {"point": [0.0, 0.0, float(z)], "normal": [0.0, 0.0, 1.0], "model": "penalty",
            "stiffness": stiffness, "damping": damping, "mu_static": mu,
            "mu_kinetic": 0.8 * mu, "regularization_velocity": v_reg,
            "stribeck_velocity": 2.0 * v_reg}


def _octahedron(length):
    """The expanded octahedron's 12 nodes (bar k: nodes 2k, 2k + 1) and 24 strings."""
    a, b = length / 4.0, length / 2.0
    nodes = []
    for axis in range(3):
        for off in (-a, a):
            for end in (-b, b):
                p = [0.0, 0.0, 0.0]
                p[axis], p[(axis + 1) % 3] = end, off
                nodes.append(p)
    nodes = np.array(nodes)
    ls = length * math.sqrt(6.0) / 4.0
    strings = [(i, j) for i, j in itertools.combinations(range(12), 2)
               if abs(np.linalg.norm(nodes[i] - nodes[j]) - ls) < 1e-9 * length]
    return nodes, strings


def _face_down(nodes, strings):
    """The nodes turned so that the first closed string triangle faces −z, lifted onto
    z = 0, and that triangle."""
    adj = {i: set() for i in range(len(nodes))}
    for i, j in strings:
        adj[i].add(j)
        adj[j].add(i)
    tri = next(t for t in itertools.combinations(range(len(nodes)), 3)
               if all(q in adj[p] for p, q in itertools.combinations(t, 2)))
    n = nodes[list(tri)].mean(axis=0)
    n /= np.linalg.norm(n)
    target = np.array([0.0, 0.0, -1.0])
    v = np.cross(n, target)
    s, c = np.linalg.norm(v), float(n @ target)
    k = v / s
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    rot = np.eye(3) + s * kx + (1.0 - c) * kx @ kx
    turned = nodes @ rot.T
    turned[:, 2] -= turned[:, 2].min()
    turned[list(tri), 2] = 0.0
    return turned, tri


def superball(length=1.7, bar_mass=3.5, k=2000.0, pretension=100.0, damping=20.0,
              min_length=0.5, max_length=1.1, max_rate=0.5, dt=1e-3):
    """The SUPERball robot scene (module docs): bars ``length`` (m) of ``bar_mass`` (kg),
    strings of stiffness ``k`` (N/m), pretension (N) and damping (N·s/m); actuators between
    ``min_length`` and ``max_length`` (m) at up to ``max_rate`` (m/s); RK4 at ``dt`` (s)
    projected onto the bar lengths."""
    nodes, strings = _octahedron(length)
    nodes, _ = _face_down(nodes, strings)
    rest = length * math.sqrt(6.0) / 4.0 - pretension / k
    n_s = len(strings)
    return Structure(
        nodes, [(2 * b, 2 * b + 1) for b in range(6)], strings,
        bar_mass=[bar_mass] * 6, bar_radius=[0.03] * 6,
        stiffness=[k] * n_s, rest_length=[rest] * n_s, damping=[damping] * n_s,
        gravity=(0.0, 0.0, -G),
        ground=_ground(0.0, 1e5, 1000.0, 1.0, 0.05),
        simulation={"t_end": 5.0, "integrator": "rk4", "dt": dt, "project": True},
        actuators=[{"strings": list(range(n_s)), "min_length": min_length,
                    "max_length": max_length, "max_rate": max_rate}])


def toroid_wheel(speed=1.0, k=1e4, max_change=0.1, max_rate=0.5, dt=1e-3, **toroid):
    """The toroid wheel scene (module docs): ``tensegrity toroid``'s structure for the
    keywords ``toroid`` with strings of stiffness ``k`` (N/m), its lowest nodes on the
    ground, rolling without slip at ``speed`` (m/s, along +y) about its axle (x); every
    string an actuator within ``max_change`` (a fraction) of its rest length at up to
    ``max_rate`` (m/s)."""
    s = Structure.toroid(string_stiffness=k, **toroid)
    nodes = s.nodes
    z0 = nodes[:, 2].min()
    contact = np.array([0.0, nodes[:, 1][np.argmin(nodes[:, 2])], z0])
    omega = np.array([-speed / (nodes[:, 2].mean() - z0), 0.0, 0.0])
    velocities = np.cross(omega, nodes - contact)
    rest = np.asarray(s.rest_length, dtype=float)
    return s.replace(
        gravity=(0.0, 0.0, -G), velocities=velocities,
        ground=_ground(z0, 1e5, 500.0, 1.0, 0.2),
        simulation={"t_end": 5.0, "integrator": "rk4", "dt": dt, "project": True},
        actuators=[{"strings": [j], "min_length": float(r * (1.0 - max_change)),
                    "max_length": float(r * (1.0 + max_change)), "max_rate": max_rate}
                   for j, r in enumerate(rest)])
