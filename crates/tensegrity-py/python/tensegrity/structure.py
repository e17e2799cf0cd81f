"""The structure model from numpy: :class:`Structure`.

A structure is validated by the engine when it is made, exactly as a scene file is (the
core's builder and the checks of the dynamics tables: every error names the item, e.g.
``string 0: stiffness must be positive and finite, got -1``), and crosses to the engine as
data: the dict of its arrays and tables (``_arrays()``), which the engine reads as a scene
given as data. No TOML text is on the way; ``to_toml`` and ``from_toml`` are the explicit
export and import of scene files (the io crate's writer and reader).
Its arrays are read-only; :meth:`Structure.replace` makes a changed copy.
"""

import os

import numpy as np

from . import _native
from .errors import InputError

_AXES = "xyz"


def _matrix(value, cols, name, dtype):
    a = np.asarray(value, dtype=dtype)
    if a.size == 0:
        return np.zeros((0, cols), dtype=dtype)
    if a.ndim != 2 or a.shape[1] != cols:
        raise InputError("{}: expected an array of shape (k, {}), got shape {}".format(
            name, cols, a.shape))
    return a


def _integers(value, name):
    a = np.asarray(value)
    if a.size == 0:
        return np.zeros((0, 2), dtype=np.int64)
    if a.dtype.kind == "f":
        if not np.all(np.isfinite(a)) or not np.all(a == np.round(a)):
            raise InputError("{}: node indices must be whole numbers".format(name))
    elif a.dtype.kind not in "iu":
        raise InputError("{}: node indices must be integers, got {}".format(name, a.dtype))
    return _matrix(a.astype(np.int64), 2, name, np.int64)


def _per_member(value, count, name):
    """A per-member property: None (unset), one value for all, or one per member (NaN:
    unset for that member)."""
    if value is None:
        return None
    a = np.asarray(value, dtype=np.float64)
    if a.ndim == 0:
        a = np.full(count, float(a))
    if a.shape != (count,):
        raise InputError("{}: expected one value per member ({}), got shape {}".format(
            name, count, a.shape))
    return a


def _names(value, count, name):
    if value is None:
        return None
    if isinstance(value, str):
        return [value] * count
    names = [None if v is None else str(v) for v in value]
    if len(names) != count:
        raise InputError("{}: expected one name per member ({}), got {}".format(
            name, count, len(names)))
    return names


def _supports(value):
    """[(node, (fx, fy, fz))] from a dict {node: 'xyz' | (bool, bool, bool)} or a list of
    pinned nodes."""
    if value is None:
        return []
    if isinstance(value, dict):
        items = value.items()
    else:
        items = [(n, "xyz") for n in np.asarray(value, dtype=np.int64).ravel()]
    out = []
    for node, fixed in items:
        if isinstance(fixed, str):
            bad = [c for c in fixed if c not in _AXES]
            if bad:
                raise InputError("support of node {}: unknown direction {!r} (use x, y, z)"
                                 .format(node, bad[0]))
            fixed = tuple(a in fixed for a in _AXES)
        out.append((int(node), tuple(bool(f) for f in fixed)))
    return out


def _by_node(value, name, convert):
    """{node: value} of a per-node option (``None``: empty), each value converted."""
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise InputError("{}: expected a dict {{node: value}}, got {}".format(
            name, type(value).__name__))
    out = {}
    for node, v in value.items():
        try:
            out[int(node)] = convert(v)
        except (TypeError, ValueError) as e:
            raise InputError("{} of node {}: {}".format(name, node, e)) from None
    return out


def _vector(v):
    a = np.asarray(v, dtype=np.float64).ravel()
    if a.shape != (3,):
        raise ValueError("expected three components, got {}".format(a.size))
    return [float(x) for x in a]


def _vectors(v):
    a = np.asarray(v, dtype=np.float64)
    if a.ndim == 1:
        a = a.reshape(1, -1)
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError("expected directions of three components, got shape {}".format(
            a.shape))
    return a.tolist()


def _flags(value, count, name):
    """A per-bar flag: None (unset), one bool for all, or one per bar (None: unset)."""
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_)):
        return [bool(value)] * count
    flags = [None if v is None else bool(v) for v in value]
    if len(flags) != count:
        raise InputError("{}: expected one flag per bar ({}), got {}".format(
            name, count, len(flags)))
    return flags


def _clusters(value):
    """[[node, ...]] of the clustered strings: each a sequence of at least three node
    indices (whole numbers)."""
    out = []
    for k, path in enumerate(value or ()):
        a = np.asarray(path)
        if a.ndim != 1 or (a.size and a.dtype.kind not in "iu" and not (
                a.dtype.kind == "f" and np.all(np.isfinite(a)) and np.all(a == np.round(a)))):
            raise InputError("clusters[{}]: expected a sequence of node indices".format(k))
        out.append([int(i) for i in a])
    return out


def _per_cluster(value, count, name, convert):
    """A per-cluster option: None (unset), or one entry per cluster (None: unset)."""
    if value is None:
        return None
    values = list(value)
    if len(values) != count:
        raise InputError("{}: expected one entry per cluster ({}), got {}".format(
            name, count, len(values)))
    try:
        return [None if v is None else convert(v) for v in values]
    except (TypeError, ValueError) as e:
        raise InputError("{}: {}".format(name, e)) from None


def _loads(value, n_nodes):
    """[(node, force)] from a dict {node: force} or an (n, 3) array of nodal loads (rows of
    zeros left out)."""
    if value is None:
        return []
    if isinstance(value, dict):
        return [(int(k), [float(x) for x in np.asarray(f, dtype=float).ravel()])
                for k, f in value.items()]
    a = _matrix(value, 3, "loads", np.float64)
    if a.shape[0] != n_nodes:
        raise InputError("loads: expected one row per node ({}), got {}".format(
            n_nodes, a.shape[0]))
    return [(i, a[i].tolist()) for i in range(n_nodes) if np.any(a[i] != 0.0)]


def _materials(value):
    """{name: (density, Young's modulus, yield strength)}: three numbers each."""
    out = {}
    for k, v in (value or {}).items():
        if isinstance(v, dict):
            v = (v.get("density"), v.get("youngs_modulus"), v.get("yield_strength"))
        v = tuple(v)
        if len(v) != 3:
            raise InputError("materials: {}: expected (density, youngs_modulus, "
                             "yield_strength), got {} values".format(k, len(v)))
        out[str(k)] = tuple(float(x) for x in v)
    return out


def _column(a):
    """A per-member column as data: NaN (unset) as None."""
    return None if a is None else [None if np.isnan(x) else float(x) for x in a]


class Structure:
    """Bars and strings between nodes, with masses, stiffnesses, rest lengths, damping,
    supports, loads and gravity.

    Parameters
    ----------
    nodes : array_like, shape (n, 3)
        Node positions (m).
    bars, strings : array_like of int, shape (m, 2)
        Node pairs, 0-based (a member runs from its first node to its second).
    bar_mass : float or array_like, optional
        Bar masses (kg): one for all or one per bar (NaN: unset).
    bar_radius : float or array_like, optional
        Bar radii (m), for sizing and modes.
    bar_material, string_material : str or sequence of str, optional
        Material names: built-in ones or keys of ``materials``.
    stiffness : float or array_like, optional
        String axial stiffness (N/m).
    rest_length : float or array_like, optional
        String rest lengths (m).
    damping : float or array_like, optional
        String damping (N s/m); default 0.
    materials : dict, optional
        ``{name: (density kg/m³, Young's modulus Pa, yield strength Pa)}``.
    supports : dict or sequence of int, optional
        ``{node: "xyz"}`` (the fixed directions, or three booleans), or nodes fixed in all
        three directions.
    support_along : dict, optional
        ``{node: [[dx, dy, dz], ...]}``: held directions of any orientation (unit vectors,
        one to three, independent; beside the node's ``supports`` flags, or alone).
    support_stiffness : dict, optional
        ``{node: k}`` (N/m): the node's support is a spring of stiffness k along each held
        direction (``statics``, ``solve`` and elastic ``simulate``).
    support_displacement : dict, optional
        ``{node: (dx, dy, dz)}`` (m): the supported node's prescribed displacement
        (``statics``' linear response; ``solve``: at load factor 1).
    bar_rest_length : float or array_like, optional
        Rest lengths of elastic bars (m; default: their length).
    bar_rest_length_change, rest_length_change : float or array_like, optional
        Rest-length change of bars and strings at load factor 1 (m; ``solve``).
    bar_elastic : bool or sequence of bool, optional
        Per bar: elastic (True) or rigid (False) in ``simulate``, over the scene's
        ``[simulation] bars``.
    string_mass : float or array_like, optional
        String masses (kg; elastic ``simulate``, and as dead load in ``solve``).
    masses : dict, optional
        ``{node: kg}``: point masses (elastic ``simulate``, and as dead load in ``solve``).
    clusters : sequence of sequences of int, optional
        Clustered strings: each the nodes one continuous string passes through, in order
        (at least three; the inner ones are frictionless pulleys unless ``cluster_friction``).
    cluster_stiffness, cluster_rest_length, cluster_damping : sequence of float, optional
        Per cluster (None: unset): the whole cluster's stiffness k (N/m), rest length (m)
        and damping (N s/m).
    cluster_friction : sequence of sequences of float, optional
        Per cluster (None: frictionless): the pulleys' friction coefficients, one per inner
        node.
    cluster_material : sequence of str, optional
        Per cluster: material names.
    cluster_rest_length_change : sequence of float, optional
        Per cluster (None: unset): the change of its whole rest length at load factor 1
        (m; ``solve`` only: one actuator reeling every segment along the load path).
    loads : dict or array_like, optional
        ``{node: (Fx, Fy, Fz)}`` (N), or an (n, 3) array of nodal loads.
    gravity : array_like, shape (3,), optional
        Gravitational acceleration (m/s²), e.g. ``(0, 0, -9.81)``.
    velocities : array_like, shape (n, 3), optional
        Initial node velocities (m/s) for ``simulate``.
    simulation, ground : dict, optional
        The scene's ``[simulation]`` and ``[ground]`` tables (keys as in a scene file, e.g.
        ``ground={"point": [0, 0, 0], "normal": [0, 0, 1], "model": "penalty",
        "stiffness": 1e4, "damping": 100.0}``).
    actuation : list of dict, optional
        The scene's ``[[actuation]]`` tables.
    actuators : list of dict, optional
        The scene's ``[[actuators]]`` tables: the rest lengths a :class:`Simulator`'s actions
        set and their limits, e.g. ``[{"strings": [0, 1], "min_length": 0.2, "max_rate":
        0.1}]`` (default: every string, then every cluster, without limits).

    Raises
    ------
    InputError
        (a ``ValueError``) naming the item: an index out of range, a non-finite coordinate,
        a negative stiffness, …
    """

    def __init__(self, nodes, bars=(), strings=(), *, bar_mass=None, bar_radius=None,
                 bar_material=None, stiffness=None, rest_length=None, damping=None,
                 string_material=None, materials=None, supports=None, loads=None,
                 gravity=None, velocities=None, simulation=None, ground=None, actuation=None,
                 actuators=None, support_along=None, support_stiffness=None, support_displacement=None,
                 bar_rest_length=None, bar_rest_length_change=None, rest_length_change=None,
                 bar_elastic=None, string_mass=None, masses=None, clusters=None,
                 cluster_stiffness=None, cluster_rest_length=None, cluster_damping=None,
                 cluster_friction=None, cluster_material=None,
                 cluster_rest_length_change=None):
        self.nodes = _matrix(nodes, 3, "nodes", np.float64)
        self.bars = _integers(bars, "bars")
        self.strings = _integers(strings, "strings")
        nb, ns, n = len(self.bars), len(self.strings), len(self.nodes)
        self.bar_mass = _per_member(bar_mass, nb, "bar_mass")
        self.bar_radius = _per_member(bar_radius, nb, "bar_radius")
        self.bar_material = _names(bar_material, nb, "bar_material")
        self.stiffness = _per_member(stiffness, ns, "stiffness")
        self.rest_length = _per_member(rest_length, ns, "rest_length")
        self.damping = _per_member(damping, ns, "damping")
        self.string_material = _names(string_material, ns, "string_material")
        self.materials = _materials(materials)
        self.supports = _supports(supports)
        self.support_along = _by_node(support_along, "support_along", _vectors)
        self.support_stiffness = _by_node(support_stiffness, "support_stiffness", float)
        self.support_displacement = _by_node(support_displacement, "support_displacement",
                                             _vector)
        self.bar_rest_length = _per_member(bar_rest_length, nb, "bar_rest_length")
        self.bar_rest_length_change = _per_member(bar_rest_length_change, nb,
                                                  "bar_rest_length_change")
        self.rest_length_change = _per_member(rest_length_change, ns, "rest_length_change")
        self.bar_elastic = _flags(bar_elastic, nb, "bar_elastic")
        self.string_mass = _per_member(string_mass, ns, "string_mass")
        self.masses = _by_node(masses, "masses", float)
        self.clusters = _clusters(clusters)
        nc = len(self.clusters)
        self.cluster_stiffness = _per_cluster(cluster_stiffness, nc, "cluster_stiffness", float)
        self.cluster_rest_length = _per_cluster(cluster_rest_length, nc, "cluster_rest_length",
                                                float)
        self.cluster_damping = _per_cluster(cluster_damping, nc, "cluster_damping", float)
        self.cluster_friction = _per_cluster(cluster_friction, nc, "cluster_friction",
                                             lambda mu: [float(m) for m in mu])
        self.cluster_material = _per_cluster(cluster_material, nc, "cluster_material", str)
        self.cluster_rest_length_change = _per_cluster(
            cluster_rest_length_change, nc, "cluster_rest_length_change", float)
        self.loads = _loads(loads, n)
        self.gravity = None if gravity is None else np.asarray(gravity, dtype=np.float64)
        self.velocities = (None if velocities is None
                           else _matrix(velocities, 3, "velocities", np.float64))
        self.tables = {}
        for name, table in (("simulation", simulation), ("ground", ground),
                            ("actuation", actuation), ("actuators", actuators)):
            if table is not None:
                self.tables[name] = table
        for a in (self.nodes, self.bars, self.strings, self.bar_mass, self.bar_radius,
                  self.stiffness, self.rest_length, self.damping, self.gravity,
                  self.velocities, self.bar_rest_length, self.bar_rest_length_change,
                  self.rest_length_change, self.string_mass):
            if a is not None:
                a.setflags(write=False)
        self._data = self._columns()
        _native.structure_check(self._data)

    def _columns(self):
        """The structure's arrays and tables as the engine reads a scene given as data."""
        data = {
            "nodes": self.nodes.tolist(),
            "bars": self.bars.tolist(),
            "strings": self.strings.tolist(),
            "materials": {k: {"density": v[0], "youngs_modulus": v[1], "yield_strength": v[2]}
                          for k, v in self.materials.items()},
            "supports": [[n, list(f)] for n, f in self._support_rows()],
            "loads": [[n, list(f)] for n, f in self.loads],
            "masses": [[n, m] for n, m in self.masses.items()],
        }
        optional = {
            "velocities": None if self.velocities is None else self.velocities.tolist(),
            "gravity": None if self.gravity is None else self.gravity.tolist(),
            "bar_mass": _column(self.bar_mass),
            "bar_radius": _column(self.bar_radius),
            "bar_material": self.bar_material,
            "stiffness": _column(self.stiffness),
            "rest_length": _column(self.rest_length),
            "damping": _column(self.damping),
            "string_material": self.string_material,
            "bar_rest_length": _column(self.bar_rest_length),
            "bar_rest_length_change": _column(self.bar_rest_length_change),
            "rest_length_change": _column(self.rest_length_change),
            "bar_elastic": self.bar_elastic,
            "string_mass": _column(self.string_mass),
            "cluster_stiffness": self.cluster_stiffness,
            "cluster_rest_length": self.cluster_rest_length,
            "cluster_damping": self.cluster_damping,
            "cluster_friction": self.cluster_friction,
            "cluster_material": self.cluster_material,
            "cluster_rest_length_change": self.cluster_rest_length_change,
        }
        if self.clusters:
            optional["clusters"] = self.clusters
        rows = self._support_rows()
        for key, by_node in (("support_along", self.support_along),
                             ("support_stiffness", self.support_stiffness),
                             ("support_displacement", self.support_displacement)):
            if by_node:
                optional[key] = [by_node.get(n) for n, _ in rows]
        data.update((k, v) for k, v in optional.items() if v is not None)
        data.update(self.tables)
        return data

    def _support_rows(self):
        """[(node, flags)]: the ``supports``, then a row (no axis flagged) for each node
        that only ``support_along`` holds. A stiffness or displacement on a node no support
        holds is an error naming the node."""
        rows = list(self.supports)
        held = {n for n, _ in rows}
        rows += [(n, (False, False, False)) for n in self.support_along if n not in held]
        held |= set(self.support_along)
        for name, by_node in (("support_stiffness", self.support_stiffness),
                              ("support_displacement", self.support_displacement)):
            for n in by_node:
                if n not in held:
                    raise InputError("{} of node {}: the node has no support (give it in "
                                     "supports or support_along)".format(name, n))
        return rows

    def _arrays(self):
        """The dict of the structure's arrays and tables: how it crosses to the engine (a
        scene given as data, validated as a scene file is)."""
        return self._data

    # --- scene TOML --------------------------------------------------------------------

    def to_toml(self):
        """The structure as scene TOML (the io crate's writer; read back exactly): the
        explicit export of a scene file."""
        return _native.structure_toml(self._data)

    @classmethod
    def from_toml(cls, scene):
        """A structure from scene TOML text or a scene file's path (the io crate's reader:
        errors name the file, the item and its line); JSON of the same shape is read too
        (a file whose name ends in ``.json``, or text starting with ``{``)."""
        is_text = not isinstance(scene, os.PathLike) and (
            "\n" in scene or "=" in scene or scene.lstrip().startswith("{"))
        if not is_text:
            path = os.fspath(scene)
            try:
                with open(path, encoding="utf-8") as f:
                    text = f.read()
            except OSError as e:
                raise InputError("reading {}: {}".format(path, e.strerror or e)) from None
            name = path
        else:
            text, name = scene, "scene text"
        return cls._from_arrays(_native.structure_read(text, name))

    @classmethod
    def _from_arrays(cls, data):
        """A structure from the engine's data of a scene (plain lists; ``None``: unset)."""

        def column(key):
            values = data.get(key)
            return None if values is None else [np.nan if v is None else v for v in values]

        rows = data.get("supports", ())

        def per_support(key):
            values = data.get(key) or [None] * len(rows)
            return {n: v for (n, _), v in zip(rows, values) if v is not None} or None

        return cls(
            data["nodes"] if data["nodes"] else np.zeros((0, 3)),
            data.get("bars", ()),
            data.get("strings", ()),
            bar_mass=column("bar_mass"),
            bar_material=data.get("bar_material"),
            bar_radius=column("bar_radius"),
            stiffness=column("stiffness"),
            rest_length=column("rest_length"),
            damping=column("damping"),
            string_material=data.get("string_material"),
            materials=data.get("materials"),
            supports={n: tuple(f) for n, f in rows if any(f)},
            support_along=per_support("support_along"),
            support_stiffness=per_support("support_stiffness"),
            support_displacement=per_support("support_displacement"),
            loads={n: f for n, f in data.get("loads", ())} or None,
            gravity=data.get("gravity"),
            velocities=data.get("velocities"),
            bar_rest_length=column("bar_rest_length"),
            bar_rest_length_change=column("bar_rest_length_change"),
            rest_length_change=column("rest_length_change"),
            bar_elastic=data.get("bar_elastic"),
            string_mass=column("string_mass"),
            masses={n: m for n, m in data.get("masses", ())} or None,
            clusters=data.get("clusters"),
            cluster_stiffness=data.get("cluster_stiffness"),
            cluster_rest_length=data.get("cluster_rest_length"),
            cluster_damping=data.get("cluster_damping"),
            cluster_friction=data.get("cluster_friction"),
            cluster_material=data.get("cluster_material"),
            cluster_rest_length_change=data.get("cluster_rest_length_change"),
            **{t: data[t] for t in ("simulation", "ground", "actuation", "actuators")
               if t in data},
        )

    def plot(self, forces=None, nodes=None, ax=None):
        """Draws the structure in 3-D on ``ax`` (new 3-D axes by default) and returns the
        axes: bars thick, strings thin, at ``nodes`` (default the structure's; e.g. a
        ``simulate`` trajectory's sample). With ``forces`` (one per member, bars then strings,
        N, tension positive: a ``statics`` report's ``prestress`` or a run's
        ``member_forces`` sample) members are coloured by sign and size (tension red,
        compression blue; the project's diverging map) and a colour bar is added. Needs
        matplotlib (``pip install "tensegrity-toolkit[plot]"``)."""
        from .results import _pyplot
        plt = _pyplot()
        x = self.nodes if nodes is None else np.asarray(nodes, dtype=np.float64)
        if ax is None:
            ax = plt.figure().add_subplot(projection="3d")
        members = [(b, 2.5) for b in self.bars] + [(st, 1.0) for st in self.strings]
        if forces is not None:
            forces = np.asarray(forces, dtype=np.float64).ravel()
            if len(forces) < len(members):
                raise ValueError(f"forces: expected {len(members)} (bars then strings), got "
                                 f"{len(forces)}")
            scale = max(float(np.abs(forces[:len(members)]).max()), 1e-300)
            cmap = plt.get_cmap("RdBu_r")
        for k, ((i, j), width) in enumerate(members):
            color = "0.2" if width > 1.0 else "0.5"
            if forces is not None:
                color = cmap(0.5 + 0.5 * forces[k] / scale)
            ax.plot(*x[[i, j]].T, color=color, linewidth=width)
        if forces is not None:
            mappable = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(-scale, scale))
            ax.figure.colorbar(mappable, ax=ax, label="axial force [N] (tension +)")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
        return ax

    def replace(self, **changes):
        """A copy with some arguments of the constructor changed."""
        args = dict(
            nodes=self.nodes, bars=self.bars, strings=self.strings, bar_mass=self.bar_mass,
            bar_radius=self.bar_radius, bar_material=self.bar_material,
            stiffness=self.stiffness, rest_length=self.rest_length, damping=self.damping,
            string_material=self.string_material, materials=self.materials,
            supports={n: f for n, f in self.supports},
            loads={n: f for n, f in self.loads} or None, gravity=self.gravity,
            velocities=self.velocities, support_along=self.support_along or None,
            support_stiffness=self.support_stiffness or None,
            support_displacement=self.support_displacement or None,
            bar_rest_length=self.bar_rest_length,
            bar_rest_length_change=self.bar_rest_length_change,
            rest_length_change=self.rest_length_change, bar_elastic=self.bar_elastic,
            string_mass=self.string_mass, masses=self.masses or None,
            clusters=self.clusters or None, cluster_stiffness=self.cluster_stiffness,
            cluster_rest_length=self.cluster_rest_length,
            cluster_damping=self.cluster_damping, cluster_friction=self.cluster_friction,
            cluster_material=self.cluster_material,
            cluster_rest_length_change=self.cluster_rest_length_change, **self.tables)
        args.update(changes)
        return Structure(**args)

    # --- topologies --------------------------------------------------------------------

    @classmethod
    def toroid(cls, **kwargs):
        """The toroid wheel of the ``toroid`` command's keywords (as ``toroid
        --export-scene`` writes it; with ``string_stiffness`` its strings are stiff and
        prestressed)."""
        return cls._from_arrays(_native.topology("toroid", kwargs))

    @classmethod
    def michell(cls, **kwargs):
        """The Michell truss of the ``michell`` command's keywords: members as bars, extra
        strings (``extra_strings``) as strings, the last level pinned."""
        return cls._from_arrays(_native.topology("michell", kwargs))

    @classmethod
    def tbar(cls, **kwargs):
        """The T-bar tread or wheel of the ``tbar`` command's keywords (as ``tbar
        --export-scene`` writes it)."""
        return cls._from_arrays(_native.topology("tbar", kwargs))

    @classmethod
    def from_formfind(cls, **kwargs):
        """The form-found, prestressed structure of the ``formfind`` command's keywords (as
        ``formfind --out`` writes it: string rest lengths and stiffnesses realising the
        prestress), e.g. ``Structure.from_formfind(builtin="prism:3")``."""
        return cls._from_arrays(_native.topology("formfind", kwargs))

    @classmethod
    def from_matrices(cls, N, C_b, C_s=None, bar_mass=None, stiffness=None, rest_length=None,
                      pinned=()):
        """The structure of MOTES's or TsgFEM's matrices (as ``tensegrity import motes``
        reads them from text): the node matrix ``N`` (3 × n, a node per column, or n × 3),
        the connectivities ``C_b`` and ``C_s`` (a member per row: −1 at its first node, +1
        at its second), one bar mass (kg), string stiffness (N/m) and rest length (m) per
        member where given, and the ``pinned`` nodes. Bad matrices raise ``InputError``
        naming the row."""
        def rows(a):
            return None if a is None else np.asarray(a, dtype=np.float64).tolist()

        def values(a):
            return None if a is None else np.asarray(a, dtype=np.float64).ravel().tolist()

        return cls._from_arrays(_native.topology("matrices", {
            "N": rows(N), "C_b": rows(C_b), "C_s": rows(C_s), "bar_mass": values(bar_mass),
            "stiffness": values(stiffness), "rest_length": values(rest_length),
            "pinned": [int(i) for i in pinned]}))

    # --- matrices ------------------------------------------------------------------------

    def _matrices(self):
        if not hasattr(self, "_m"):
            m = _native.matrices(self._data)
            out = {}
            for key in ("C_b", "C_s", "C_c", "S", "A"):
                shape = tuple(m[key]["shape"])
                a = np.array(m[key]["data"], dtype=np.float64).reshape(shape)
                a.setflags(write=False)
                out[key] = a
            out["free_dofs"] = np.array(m["free_dofs"], dtype=np.int64).reshape(-1, 2)
            self._m = out
        return self._m

    @property
    def C_b(self):
        """Bar connectivity (bars × nodes): −1 at a bar's first node, +1 at its second."""
        return self._matrices()["C_b"]

    @property
    def C_s(self):
        """String connectivity (strings × nodes)."""
        return self._matrices()["C_s"]

    @property
    def C_c(self):
        """Cluster segment connectivity (segments × nodes): every cluster's segments in
        order, cluster after cluster; −1 at a segment's first node, +1 at its second."""
        return self._matrices()["C_c"]

    @property
    def clustering_matrix(self):
        """The clustering matrix S (clusters × segments of ``C_c``): 1 where a segment
        belongs to a cluster (CTSFEM's S: one tension per row)."""
        return self._matrices()["S"]

    @property
    def equilibrium_matrix(self):
        """The equilibrium matrix A (free degrees of freedom × columns: bars, strings, then
        one per cluster): A q = w for force densities q (tension positive; a cluster's the
        force density on its whole length, q_c = t_c / L_c, its column Σ_i (L_c / l_i) times
        its segment i's) and the free components w of the nodal loads; rows node-major,
        supported directions removed (see ``free_dofs``)."""
        return self._matrices()["A"]

    @property
    def free_dofs(self):
        """(node, direction) of each row of the equilibrium matrix (direction 0, 1, 2 = x,
        y, z)."""
        return self._matrices()["free_dofs"]

    def sparse(self, name):
        """``C_b``, ``C_s``, ``C_c``, ``clustering_matrix`` or ``equilibrium_matrix`` as
        scipy-compatible triplets ``(row,
        col, val, shape)``: ``scipy.sparse.coo_matrix((val, (row, col)), shape=shape)``."""
        a = {"C_b": self.C_b, "C_s": self.C_s, "C_c": self.C_c,
             "clustering_matrix": self.clustering_matrix, "S": self.clustering_matrix,
             "equilibrium_matrix": self.equilibrium_matrix, "A": self.equilibrium_matrix}
        if name not in a:
            raise InputError("no matrix {!r} (C_b, C_s, C_c, clustering_matrix, "
                             "equilibrium_matrix)".format(name))
        m = a[name]
        row, col = np.nonzero(m)
        return row.astype(np.int64), col.astype(np.int64), m[row, col], m.shape

    # --- sizes -----------------------------------------------------------------------------

    @property
    def n_nodes(self):
        """Number of nodes."""
        return len(self.nodes)

    @property
    def n_bars(self):
        """Number of bars."""
        return len(self.bars)

    @property
    def n_strings(self):
        """Number of strings."""
        return len(self.strings)

    @property
    def n_clusters(self):
        """Number of clustered strings."""
        return len(self.clusters)

    def __repr__(self):
        return "Structure({} nodes, {} bars, {} strings)".format(
            self.n_nodes, self.n_bars, self.n_strings)

    def _canonical(self):
        """The data as the engine gives it back (the materials the members name, the tables
        in full): equal for equal structures, however they were given."""
        if not hasattr(self, "_c"):
            self._c = _native.structure_arrays(self._data)
        return self._c

    def __eq__(self, other):
        return isinstance(other, Structure) and self._canonical() == other._canonical()

    __hash__ = None
