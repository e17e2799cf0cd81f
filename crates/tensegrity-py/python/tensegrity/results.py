"""Typed results: every command function returns a :class:`Result` of its own class
(``StaticsResult``, ``SimulateResult``, ``RollResult``, …), a ``dict`` of the command's
``--json`` report whose keys are also attributes (``r.energy_drift`` is
``r["energy_drift"]``), with ``to_dict()`` and a docstring that lists the report's scalar
fields with their units (from the engine's registry: its result columns) and the arrays a
function adds (``simulate``'s histories, ``roll``'s, ``tipover``'s and ``tbar_roll``'s
``history``, ``tipover``'s ``grid``, ``tbar_roll``'s ``table``, ``tbar``'s studies). Being a dict, a result
compares, prints and serialises as the report does.
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
    "formfind": ("formfind",), "solve": ("solve",),
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
        cls = type(result_class_name(pyname), (Result,), {"__slots__": (), "__doc__": fields_doc(pyname),
                                                   "__module__": "tensegrity.results"})
        _CLASSES[pyname] = cls
        globals()[cls.__name__] = cls
    return cls


def wrap(pyname, report):
    """``report`` (a dict) as the result class of ``pyname``; anything else as it is."""
    if isinstance(report, dict) and not isinstance(report, Result):
        return result_class(pyname)(report)
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
    if not self.get("valid", True):
        ax.set_title("not valid: " + "; ".join(w.get("kind", "?") for w in self.get("warnings", [])))
    return ax


def _plot_roll(self, ax=None):
    """Plots the rolling history (the thesis's Figs. 3.10–3.11): the axle's position along
    the slope and its height on the left axis (m), the normal and tangential contact forces on
    a right axis (N); returns the left axes."""
    h = self["history"]
    ax = _axes(ax)
    ax.plot(h["t"], h["axle_s"], label="axle position s [m]")
    ax.plot(h["t"], h["axle_h"], label="axle height h [m]")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("m")
    right = ax.twinx()
    right.plot(h["t"], h["normal_N"], "--", label="normal force [N]")
    right.plot(h["t"], h["tangential_N"], ":", label="tangential force [N]")
    right.set_ylabel("N")
    lines = ax.get_lines() + right.get_lines()
    ax.legend(lines, [line.get_label() for line in lines], loc="best")
    if not self.get("valid", True):
        ax.set_title("not valid: " + "; ".join(w.get("kind", "?") for w in self.get("warnings", [])))
    return ax


result_class("simulate").plot = _plot_simulate
result_class("roll").plot = _plot_roll

#: The stub signatures of the result classes' methods beyond the dict's.
METHOD_STUBS = {
    "simulate": ("def plot(self, what: str = ..., ax: Any = ...) -> Any: ...",),
    "roll": ("def plot(self, ax: Any = ...) -> Any: ...",),
}
