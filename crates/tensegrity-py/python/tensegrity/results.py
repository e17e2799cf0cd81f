"""Typed results: every command function returns a :class:`Result` of its own class
(``StaticsResult``, ``SimulateResult``, ``RollResult``, …), a ``dict`` of the command's
``--json`` report whose keys are also attributes (``r.energy_drift`` is
``r["energy_drift"]``), with ``to_dict()`` and a docstring that lists the report's scalar
fields with their units (from the engine's registry: its result columns) and the arrays a
function adds (``simulate``'s histories, ``roll``'s, ``tipover``'s and ``tbar_roll``'s
``history``, ``tipover``'s ``grid``, ``tbar_roll``'s ``table``, ``tbar``'s studies). Being a dict, a result
compares, prints and serialises as the report does.

A sweep's rows are a :class:`SweepResult`: the dict of the CSV's numpy columns, with
``rows()``/``row(k)`` giving each row as a :class:`SweepRow` (its cells as Python scalars)
and ``columns`` the column names with their units.

Where a result has a common view, its ``plot(..., ax=None)`` draws it with matplotlib (an
optional dependency, imported on the first call) and returns the axes: ``simulate``'s
histories, the ``history`` of ``roll``, ``tbar_roll`` and ``tipover``, ``tipover``'s
``grid``, ``solve``'s load path, the structure of ``statics``, ``toroid``, ``formfind``,
``tbar`` and ``michell`` coloured by force (:meth:`Structure.plot`), a sweep's columns.
"""

import numpy as np

from . import _native
from ._commands import REGISTRY, result_class_name

#: The registry commands whose columns each function's result holds.
COMMANDS = {
    "statics": ("statics",), "simulate": ("simulate",), "toroid": ("toroid",),
    "roll": ("roll",), "tipover": ("tipover", "tipover_dynamic", "tipover_rolling"),
    "michell": ("michell",), "michell_optimize": ("michell_optimize",),
    "michell_table": ("michell_table",), "tbar": ("tbar",), "tbar_roll": ("tbar_roll",),
    "formfind": ("formfind",), "solve": ("solve",), "design": ("design",),
}

#: The arrays a function adds to its report: (name, shape and unit, meaning).
EXTRA_FIELDS = {
    "simulate": (
        ("t", "(samples,) s", "sample times"),
        ("trajectory", "(samples, nodes, 3) m", "node positions"),
        ("velocities", "(samples, nodes, 3) m/s", "node velocities, if recorded"),
        ("member_forces", "(samples, members) N",
         "axial forces, tension positive (bars, strings, clusters), if recorded"),
        ("kinetic_energy", "(samples,) J", "kinetic energy, if recorded"),
        ("energy", "(samples,) J", "total energy, if recorded"),
        ("contact_nodes", "(contact nodes,)", "the nodes that can touch the ground"),
        ("contact_forces", "(samples, contact nodes, 3) N", "ground forces, if recorded"),
    ),
    "roll": (
        ("history", "dict of (samples,) arrays",
         "every 1 ms sample, the columns of ``roll --out``: "
         + ", ".join(_native.ROLL_HISTORY_COLUMNS)
         + " (s, m along the slope, m, rad/s, m, N, N, J, m/s)"),
    ),
    "tipover": (
        ("history", "dict of (samples,) arrays",
         "with ``dynamic=True``: every ``output_dt`` sample, the columns of ``tipover "
         "--dynamic --out``: " + ", ".join(_native.TIPOVER_DYNAMIC_COLUMNS)
         + " (s, N lateral hub force, rad lean, N summed normal force on the near and the far "
         "tread edge); with ``rolling=True`` those of ``tipover --rolling --out``: "
         + ", ".join(_native.TIPOVER_ROLLING_COLUMNS)
         + " (s, rad lean, m hub travel downhill, m hub drift across the slope)"),
        ("grid", "dict: sigma (grid_points,), epsilon (grid_points,), "
         "normalized_friction (grid_points, grid_points)",
         "with ``grid=True``: the map of ``tipover --grid`` (Fig. 3.13), F_f/F_e "
         "(dimensionless) at [σ, ε]; its axes σ = R_i/R_o and ε = t/T (dimensionless); the "
         "CSV's rows are σ outer, ε inner"),
    ),
    "tbar": (
        ("rows", "list of dicts",
         "with ``loop_study=True`` or ``mass_sweep=True``: the study's rows as its ``--json``"),
        ("loop_study", "dict of (6,) arrays",
         "with ``loop_study=True``: the rows as columns: structure, stance (text), contacts, "
         "nodes, members, free_dofs, rank, self_stress_dim, mechanisms (counts), rigid, "
         "in_plane, out_of_plane, internal (mechanism counts by kind), prestress_margin "
         "(dimensionless)"),
        ("mass_sweep", "dict of (complexities × deltas,) arrays",
         "with ``mass_sweep=True``: the rows as columns: complexity, delta (δ, or ε in rad), "
         "min_prestress (N), mass.mass_kg, mass.michell_mass_kg, mass.yield_mass_kg (kg), "
         "mass.mass_ratio, mass.material, note (NaN or \"\" where a tread has no load "
         "envelope)"),
    ),
    "tbar_roll": (
        ("table", "dict of (tread counts,) arrays",
         "the rows of ``tbar roll --out``, one per number of treads, by the CSV's column names "
         "(treads; phi rad; tbar.mass_kg kg; tbar.I1 kg m²; speeds m/s; forces N; lengths m; "
         "flags as bool; NaN for an empty cell)"),
        ("history", "dict of (samples,) arrays",
         "every 1 ms sample of the first row's T-bar run, the columns of ``roll``'s history: "
         + ", ".join(_native.ROLL_HISTORY_COLUMNS)
         + " (s, m along the slope, m, rad/s, m, N, N, J, m/s)"),
    ),
}


class Result(dict):
    """A command's report: a ``dict`` whose keys are also attributes."""

    __slots__ = ()

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(
                f"{type(self).__name__} has no field {name!r} (its fields: "
                f"{', '.join(sorted(self))})") from None

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self))

    def to_dict(self):
        """The report as a plain ``dict`` (its values as they are)."""
        return dict(self)


class SweepRow(Result):
    """One row of a sweep (:meth:`SweepResult.rows`, :meth:`SweepResult.row`): a dict of
    the row's CSV cells by column name whose keys are also attributes (``row.case``,
    ``row.sides``; a dotted name such as ``mass.mass_kg`` by key), each a Python scalar:
    ``int`` in a column of whole numbers, ``float`` in a numeric one (``nan`` for an empty
    cell), ``str`` in a text one (``status``, ``message``, choices)."""

    __slots__ = ()


class SweepResult(Result):
    """The rows of a sweep (:func:`tensegrity.sweep`, :func:`tensegrity.read_rows`): a dict
    of numpy columns, one per column of the CSV in its order (``r["case"]``, ``r.sides``;
    ``to_dict()`` gives the plain dict), with the rows as objects and the columns' units.

    ``rows()``
        Every row as a :class:`SweepRow` (its cells as Python scalars).
    ``row(k)``
        Row ``k`` (0-based, negative from the end) as a :class:`SweepRow`.
    ``columns``
        The columns as ``(name, unit)`` pairs in the CSV's order; ``unit`` is the spec's
        (the sweep's ``# units:`` line: a parameter's unit from the registry for an axis,
        the report column's for a result), ``None`` where it has none (counts, flags, text,
        dimensionless numbers) or where the file read gives none.
    ``plot(x, y, group=None, ax=None)``
        Column ``y`` against column ``x`` (matplotlib), one line per value of ``group``.
    """

    __slots__ = ("_units",)

    def __init__(self, columns=(), units=None):
        super().__init__(columns)
        self._units = dict(units or {})

    @property
    def columns(self):
        """The columns as ``(name, unit)`` pairs (``unit`` ``None`` where there is none)."""
        try:
            units = self._units
        except AttributeError:
            units = {}
        return [(name, units.get(name) or None) for name in self]

    def _row_count(self):
        return len(next(iter(self.values()))) if self else 0

    def rows(self):
        """Every row as a :class:`SweepRow`: the cells of each column at that row, as Python
        scalars (``int``, ``float``, ``str``), by the column names."""
        return [self.row(k) for k in range(self._row_count())]

    def row(self, k):
        """Row ``k`` (0-based; negative counts from the end) as a :class:`SweepRow`."""
        import operator
        n = self._row_count()
        k = operator.index(k)
        if not -n <= k < n:
            raise IndexError(f"row {k} of a sweep of {n} rows")
        return SweepRow((name, _scalar(col[k])) for name, col in self.items())

    def plot(self, x, y, group=None, ax=None):
        """Draws column ``y`` against column ``x`` on ``ax`` (new axes by default) and returns
        the axes: one line through the rows in the CSV's order, or with ``group`` one line per
        value of that column (in the order they first appear, labelled ``group = value``);
        the axis labels carry the units of ``columns``. Needs matplotlib."""
        for name in (x, y) if group is None else (x, y, group):
            if name not in self:
                raise KeyError(f"{name}: not a column of the sweep (its columns: "
                               f"{', '.join(self)})")
        units = dict(self.columns)
        ax = _axes(ax)
        if group is None:
            ax.plot(self[x], self[y])
        else:
            values = self[group]
            for value in dict.fromkeys(values.tolist()):
                rows = values == value
                ax.plot(self[x][rows], self[y][rows], label=f"{group} = {value}")
            ax.legend()
        ax.set_xlabel(_label(x, units[x]))
        ax.set_ylabel(_label(y, units[y]))
        return ax


def _scalar(x):
    """A numpy cell as a Python scalar (``int``, ``float``, ``str``, ``bool``)."""
    return x.item() if isinstance(x, np.generic) else x


def columns(pyname):
    """The scalar fields of ``pyname``'s report: ``(name, unit)``, each once, in the
    registry's order."""
    seen, out = set(), []
    for command in COMMANDS.get(pyname, ()):
        for c in REGISTRY.get(command, {}).get("columns", ()):
            if c["name"] not in seen:
                seen.add(c["name"])
                out.append((c["name"], c["unit"]))
    return out


def fields_doc(pyname):
    """The docstring of ``pyname``'s result class."""
    lines = [f"The result of :func:`tensegrity.{pyname}`: its ``--json`` report as a dict",
             "whose keys are also attributes (``to_dict()`` gives the plain dict).", "",
             "Fields: the report's scalars (with a unit: a float in that unit; without: a",
             "count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the",
             "report also holds its vectors and tables, every one a numpy array.", "",
             "Fields", "------"]
    for name, unit in columns(pyname):
        lines.append(f"{name} : float [{unit}]" if unit else name)
    for name, shape, meaning in EXTRA_FIELDS.get(pyname, ()):
        lines.append(f"{name} : ndarray {shape}")
        lines.append(f"    {meaning}")
    return "\n".join(lines) + "\n"


_CLASSES = {}


def result_class(pyname):
    """The result class of the function ``pyname`` (made once)."""
    cls = _CLASSES.get(pyname)
    if cls is None:
        cls = type(result_class_name(pyname), (Result,),
                   {"__slots__": ("_inputs",), "__doc__": fields_doc(pyname),
                    "__module__": "tensegrity.results"})
        _CLASSES[pyname] = cls
        globals()[cls.__name__] = cls
    return cls


def wrap(pyname, report, inputs=None):
    """``report`` (a dict) as the result class of ``pyname``; anything else as it is.
    ``inputs``, the call's arguments by name, are kept with the result (not as a key): a
    ``plot()`` draws the structure they describe when the report has no geometry of its own
    (``statics``' scene, ``toroid``'s and ``formfind``'s keywords)."""
    if isinstance(report, dict) and not isinstance(report, Result):
        report = result_class(pyname)(report)
        if inputs is not None:
            report._inputs = dict(inputs)
    return report


for _name in COMMANDS:
    result_class(_name)


def _pyplot():
    """matplotlib's pyplot, or an ImportError that says how to install it."""
    try:
        import matplotlib.pyplot as plt
    except ImportError:
        raise ImportError("plotting needs matplotlib: pip install "
                          "\"tensegrity-toolkit[plot]\" (or pip install matplotlib)") from None
    return plt


def _axes(ax):
    return ax if ax is not None else _pyplot().subplots()[1]


def _label(name, unit):
    """An axis label: ``name [unit]``, or the name alone where there is no unit."""
    return f"{name} [{unit}]" if unit else name


def _title(ax, result, notes=()):
    """Says in ``ax``'s title what is wrong with the result: not valid (the kinds of its
    warnings), then ``notes`` (e.g. "not prestressable"); no title when all is well."""
    parts = []
    if not result.get("valid", True):
        parts.append("not valid: " + "; ".join(w.get("kind", "?")
                                               for w in result.get("warnings") or []))
    parts += [n for n in notes if n]
    if parts:
        ax.set_title(" — ".join(parts))


def _plot_simulate(self, what="heights", ax=None):
    """Plots the run against time on ``ax`` (new axes by default) and returns the axes:
    ``what="heights"`` every node's height (the last coordinate of ``trajectory``, m),
    ``"energy"`` the kinetic and total energy (J, when the scene records ``energy``),
    ``"forces"`` every member's axial force (N, when it records ``member_forces``)."""
    t = self["t"]
    if what == "heights":
        series, label = self["trajectory"][:, :, 2], "node height [m]"
    elif what == "energy":
        if "energy" not in self:
            raise KeyError("energy: the scene does not record it ([simulation] record)")
        series, label = np.c_[self["kinetic_energy"], self["energy"]], "energy [J]"
    elif what == "forces":
        if "member_forces" not in self:
            raise KeyError("member_forces: the scene does not record it ([simulation] record)")
        series, label = self["member_forces"], "axial force [N] (tension +)"
    else:
        raise ValueError(f"what = {what!r}: one of 'heights', 'energy', 'forces'")
    ax = _axes(ax)
    ax.plot(t, series)
    if what == "energy":
        ax.legend(["kinetic", "total"])
    ax.set_xlabel("t [s]")
    ax.set_ylabel(label)
    _title(ax, self)
    return ax


def _plot_history(self, left, left_unit, right, right_unit, ax=None):
    """Plots columns of ``self["history"]`` against its ``t``: ``left`` and ``right`` are
    ``(column, label, line style)`` triples drawn on ``ax`` and on a twin right axis (units
    ``left_unit``, ``right_unit``), with one legend for both; returns the left axes."""
    h = self["history"]
    ax = _axes(ax)
    for column, label, style in left:
        ax.plot(h["t"], h[column], style, label=label)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(left_unit)
    twin = ax.twinx()
    for column, label, style in right:
        twin.plot(h["t"], h[column], style, label=label)
    twin.set_ylabel(right_unit)
    lines = ax.get_lines() + twin.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="best")
    _title(ax, self)
    return ax


def _plot_roll(self, ax=None):
    """Plots the rolling history (the thesis's Figs. 3.10–3.11): the axle's position along
    the slope and its height on the left axis (m), the normal and tangential contact forces on
    a right axis (N); returns the left axes."""
    return _plot_history(
        self, [("axle_s", "axle position s [m]", "-"), ("axle_h", "axle height h [m]", "-")],
        "m", [("normal_N", "normal force [N]", "--"),
              ("tangential_N", "tangential force [N]", ":")], "N", ax)


def _plot_tipover(self, ax=None):
    """Plots what the tip-over run computed on ``ax`` (new axes by default) and returns the
    axes: with ``grid=True`` the map of F_f/F_e over σ (x) and ε (y), with a colour bar;
    with ``dynamic=True`` the lean (rad, left axis) and the lateral hub force and the normal
    forces on the near and the far tread edge (N, right axis) against time; with
    ``rolling=True`` the lean (rad, left) and the hub's travel downhill and across the slope
    (m, right) against time. The static check (neither) has nothing to plot."""
    if "grid" in self:
        g = self["grid"]
        ax = _axes(ax)
        mesh = ax.pcolormesh(g["sigma"], g["epsilon"], g["normalized_friction"].T,
                             shading="nearest", cmap="viridis")
        ax.figure.colorbar(mesh, ax=ax, label="F_f / F_e")
        ax.set_xlabel("σ = R_i / R_o")
        ax.set_ylabel("ε = t / T")
        return ax
    if "history" not in self:
        raise ValueError("plot(): the static tip-over check has nothing to plot (run it with "
                         "grid=True, dynamic=True or rolling=True)")
    if "force" in self["history"]:
        return _plot_history(
            self, [("lean", "lean [rad]", "-")], "rad",
            [("force", "lateral hub force [N]", "--"),
             ("near_normal", "near edge normal force [N]", ":"),
             ("far_normal", "far edge normal force [N]", "-.")], "N", ax)
    return _plot_history(
        self, [("lean", "lean [rad]", "-")], "rad",
        [("downhill", "hub travel downhill [m]", "--"),
         ("across", "hub drift across the slope [m]", ":")], "m", ax)


def _structure(self, structure, build):
    """The structure a ``plot()`` draws: ``structure`` (a :class:`Structure`, or a scene's
    path or TOML text), else the one the call's arguments describe (``build(inputs)``)."""
    from .structure import Structure
    if isinstance(structure, Structure):
        return structure
    if structure is not None:
        return Structure.from_toml(structure)
    try:
        inputs = self._inputs
    except AttributeError:
        inputs = None
    if inputs is None:
        raise TypeError(f"{type(self).__name__}.plot(): the report holds no geometry: pass "
                        "the structure, plot(structure, ...) (a Structure, or for statics the "
                        "scene's path or TOML text)")
    return build(inputs)


def _keywords(inputs, command):
    """The arguments of ``inputs`` that are parameters of the registry's ``command``."""
    names = {p["name"] for p in REGISTRY[command]["params"]}
    return {k: v for k, v in inputs.items() if k in names and v is not None}


def _draw(structure, result, forces, nodes=None, ax=None, notes=()):
    """``structure.plot(forces, nodes, ax)`` with ``result``'s validity in the title."""
    ax = structure.plot(forces=forces, nodes=nodes, ax=ax)
    _title(ax, result, notes)
    return ax


def _not_prestressable(result):
    return "not prestressable" if result.get("prestressable") is False else None


def _plot_statics(self, structure=None, ax=None):
    """Draws the scene in 3-D (:meth:`Structure.plot`: bars thick, strings thin) coloured by
    the report's member forces: the load solve's ``member_force`` (N) where the scene has
    loads, else the self-stress ``prestress``; uncoloured where it has neither. A scene that
    is not prestressable says so in the title. ``structure``: the scene analysed (a
    :class:`Structure`, or its path or TOML text; default: the call's ``scene``). Returns the
    axes."""
    from .structure import Structure
    s = _structure(self, structure, lambda i: i["scene"] if isinstance(i["scene"], Structure)
                   else Structure.from_toml(i["scene"]))
    forces = self.get("member_force")
    if forces is None:
        forces = self.get("prestress")
    return _draw(s, self, forces, ax=ax, notes=[_not_prestressable(self)])


def _plot_toroid(self, structure=None, ax=None):
    """Draws the toroid wheel in 3-D (:meth:`Structure.plot`) coloured by its prestress
    forces ``prestress_member_force`` (N); one that is not prestressable says so in the
    title. ``structure``: the wheel (default: ``Structure.toroid`` of the call's keywords).
    Returns the axes."""
    from .structure import Structure
    s = _structure(self, structure, lambda i: Structure.toroid(**_keywords(i, "toroid")))
    return _draw(s, self, self.get("prestress_member_force"), ax=ax,
                 notes=[_not_prestressable(self)])


def _plot_formfind(self, structure=None, ax=None):
    """Draws the form found in 3-D (:meth:`Structure.plot`) at the report's ``nodes``,
    coloured by the members' axial forces ``member_force`` (N; the force densities
    ``force_density`` times the lengths, the same signs). ``structure``: its connectivity
    (default: ``Structure.from_formfind`` of the call's keywords). Returns the axes."""
    from .structure import Structure
    s = _structure(self, structure,
                   lambda i: Structure.from_formfind(**_keywords(i, "formfind")))
    return _draw(s, self, self["member_force"], nodes=self["nodes"], ax=ax,
                 notes=[_not_prestressable(self)])


def _plot_tbar(self, ax=None):
    """Draws the T-bar tread or wheel in 3-D (:meth:`Structure.plot`: its
    ``node_coordinates``, ``bar_nodes`` and ``string_nodes``) coloured by its prestress
    ``prestress_force`` (N, bars then strings); one that is not prestressable says so in the
    title. Returns the axes."""
    from .structure import Structure
    if "node_coordinates" not in self:
        raise ValueError("plot(): a loop_study or mass_sweep table has no structure to draw")
    s = Structure(self["node_coordinates"], self["bar_nodes"], self["string_nodes"])
    return _draw(s, self, self.get("prestress_force"), ax=ax,
                 notes=[_not_prestressable(self)])


def _plot_michell(self, ax=None):
    """Draws the Michell truss in 3-D (:meth:`Structure.plot`, from the report's ``nodes``
    and ``members``): the members of kind ``bar`` thick, the others thin, coloured by their
    ``force`` (N, tension red, compression blue). Returns the axes."""
    from .structure import Structure
    index = {tuple(n["index"]): k for k, n in enumerate(self["nodes"])}
    bars, strings, bar_forces, string_forces = [], [], [], []
    for m in self["members"]:
        pair = [index[tuple(m["parent"])], index[tuple(m["child"])]]
        if m["kind"] == "bar":
            bars.append(pair)
            bar_forces.append(m["force"])
        else:
            strings.append(pair)
            string_forces.append(m["force"])
    s = Structure([n["position"] for n in self["nodes"]], bars, strings)
    return _draw(s, self, bar_forces + string_forces, ax=ax)


def _plot_solve(self, ax=None):
    """Plots the load path on ``ax`` (new axes by default) and returns the axes: the load
    factor λ of every point of ``path.points`` against its largest node displacement (m),
    with the path's events (limit points, bifurcations, …) marked, one marker style per
    kind; a path that stopped short of its target says why in the title."""
    path = self["path"]
    points = path["points"]
    ax = _axes(ax)
    ax.plot([p["max_displacement"] for p in points], [p["lambda"] for p in points], ".-",
            label="path")
    events = {}
    for e in path.get("events") or []:
        events.setdefault(e["kind"], []).append(e)
    for (kind, es), marker in zip(events.items(), "o^sDv*"):
        ax.plot([e["max_displacement"] for e in es], [e["lambda"] for e in es], marker,
                linestyle="none", label=kind.replace("_", " "))
    if events:
        ax.legend()
    ax.set_xlabel("largest displacement [m]")
    ax.set_ylabel("load factor λ")
    stop = (path.get("stop") or {}).get("kind")
    _title(ax, self, [f"stopped: {stop}" if stop not in (None, "reached_target") else None])
    return ax


result_class("simulate").plot = _plot_simulate
result_class("roll").plot = _plot_roll
result_class("tbar_roll").plot = _plot_roll
result_class("tipover").plot = _plot_tipover
result_class("statics").plot = _plot_statics
result_class("toroid").plot = _plot_toroid
result_class("formfind").plot = _plot_formfind
result_class("tbar").plot = _plot_tbar
result_class("michell").plot = _plot_michell
result_class("solve").plot = _plot_solve

#: The stub signatures of the result classes' methods beyond the dict's (``sweep``: those of
#: :class:`SweepResult`).
METHOD_STUBS = {
    "simulate": ("def plot(self, what: str = ..., ax: Any = ...) -> Any: ...",),
    "roll": ("def plot(self, ax: Any = ...) -> Any: ...",),
    "tbar_roll": ("def plot(self, ax: Any = ...) -> Any: ...",),
    "tipover": ("def plot(self, ax: Any = ...) -> Any: ...",),
    "statics": ("def plot(self, structure: Any = ..., ax: Any = ...) -> Any: ...",),
    "toroid": ("def plot(self, structure: Any = ..., ax: Any = ...) -> Any: ...",),
    "formfind": ("def plot(self, structure: Any = ..., ax: Any = ...) -> Any: ...",),
    "tbar": ("def plot(self, ax: Any = ...) -> Any: ...",),
    "michell": ("def plot(self, ax: Any = ...) -> Any: ...",),
    "solve": ("def plot(self, ax: Any = ...) -> Any: ...",),
    "sweep": ("def plot(self, x: str, y: str, group: Optional[str] = ..., ax: Any = ...) "
              "-> Any: ...",),
}
