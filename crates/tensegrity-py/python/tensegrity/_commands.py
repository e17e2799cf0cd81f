"""One function per command, built from the engine's registry: the keyword arguments, their
defaults, the signature and the docstring come from each command's parameters (name, kind,
unit, default, help), so a parameter added to a request in Rust is a keyword here at once.
Nothing about a parameter is written twice: this module only knows which registry command
a function runs and how its result is handed back. Values cross as Python objects: the native
module converts them to the engine's values and its reports back (``src/convert.rs``), so no
text is written on the way."""

import csv
import inspect
import os
import tempfile
import textwrap

import numpy as np

from . import _native
from .errors import Interrupted, TensegrityError

#: The registry: every command, by name.
REGISTRY = {c["name"]: c for c in _native.commands()}

#: Keywords of every function: the resource limits checked before any work (the command
#: line's global flags ``--max-memory``, ``--max-work``, ``--max-output``).
LIMITS = ("max_memory", "max_work", "max_output")

_LIMITS_DOC = """\
max_memory : float or str, optional
    Refuse the call when its estimated peak memory is above this (bytes, or a size such as
    ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
max_work : float, optional
    Refuse the call when its estimated work is above this many seconds (default 60).
max_output : float or str, optional
    Refuse the call when its estimated output is above this (default 1 GiB).
"""

_KIND_TYPE = {
    "count": "int",
    "number": "float",
    "angle": "float or str",
    "flag": "bool",
    "choice": "str",
    "text": "str",
    "counts": "sequence of int or str",
    "numbers": "sequence of float or str",
}


def params_of(*names):
    """The parameters of the commands ``names`` (the first description of a name wins)."""
    seen, out = set(), []
    for n in names:
        for p in REGISTRY[n]["params"]:
            if p["name"] not in seen:
                seen.add(p["name"])
                out.append(p)
    return out


def describe(p):
    """The numpydoc entry of one parameter."""
    kind = _KIND_TYPE[p["kind"]]
    if p["name"] == "scene":
        kind = "str, os.PathLike or Structure"
    if p["kind"] == "choice":
        kind = "{" + ", ".join(repr(c) for c in p["choices"]) + "}"
    head = "{} : {}".format(p["name"], kind)
    if p["optional"] and not p["required"]:
        head += ", optional"
    text = p["help"]
    if p["unit"]:
        text += " ({})".format(p["unit"])
    if p["kind"] == "angle":
        text += "; radians, or a string such as '30deg', 'pi/8', '3pi/4'"
    numeric = p["kind"] in ("count", "number", "angle", "counts", "numbers")
    if numeric and p["rule"]:
        text += "; " + p["rule"]
    if p["required"]:
        text += ". Required"
    elif p["default"] is not None and p["kind"] != "flag":
        text += ". Default: {!r}".format(p["default"])
    body = textwrap.fill(text, 88, initial_indent="    ", subsequent_indent="    ")
    return head + "\n" + body + "\n"


def _signature(params, positional=(), extra=()):
    items = []
    for p in params:
        kind = (
            inspect.Parameter.POSITIONAL_OR_KEYWORD
            if p["name"] in positional
            else inspect.Parameter.KEYWORD_ONLY
        )
        default = inspect.Parameter.empty if p["required"] else p["default"]
        items.append(inspect.Parameter(p["name"], kind, default=default))
    items.sort(key=lambda q: q.kind)
    for name, default in extra:
        items.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=default))
    for name in LIMITS:
        items.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=None))
    return inspect.Signature(items)


def _limits(bound):
    return {k: bound.pop(k, None) for k in LIMITS}


def _given(bound, skip=()):
    """The values given (a ``None`` keeps the default, as an absent flag does)."""
    return {k: v for k, v in bound.items() if v is not None and k not in skip}


def _partial(e, convert):
    """Re-raises an error of the engine with its partial results converted."""
    raw = getattr(e, "partial_raw", None)
    if raw is not None:
        e.partial = convert(raw)
        del e.partial_raw
    return e


def _call(name, sig, args, kwargs):
    """The arguments given (a default is not passed on: the engine applies its own, as the
    command line passes only the flags given)."""
    return dict(sig.bind(*args, **kwargs).arguments)


def make(pyname, command, summary, positional=(), doc_extra=""):
    """The function ``pyname`` running the registry's ``command``."""
    params = REGISTRY[command]["params"]
    sig = _signature(params, positional)

    def f(*args, **kwargs):
        bound = _call(pyname, sig, args, kwargs)
        limits = _limits(bound)
        values = _given(bound)
        return _native.run(command, values, limits)

    return finish(f, pyname, sig, summary, params, doc_extra)


def finish(f, pyname, sig, summary, params, doc_extra="", extra_doc=""):
    """The function ``pyname`` running ``f``: its result typed (:mod:`tensegrity.results`),
    its signature and its docstring."""

    def typed(*args, **kwargs):
        from .results import wrap
        report = f(*args, **kwargs)
        # the call's arguments kept with the result: its plot() draws what they describe
        # (bound after the call, which has checked them and named any error its own way)
        return wrap(pyname, report, inputs=sig.bind(*args, **kwargs).arguments)

    typed.__name__ = typed.__qualname__ = pyname
    typed.__signature__ = sig
    typed.__module__ = "tensegrity"
    typed.__doc__ = docstring(summary, params, doc_extra, extra_doc, returns=pyname)
    return typed


def result_class_name(pyname):
    """``statics`` → ``StaticsResult`` (:mod:`tensegrity.results`)."""
    return "".join(w.capitalize() for w in pyname.split("_")) + "Result"


def docstring(summary, params, doc_extra="", extra_doc="", returns=None):
    """The docstring of a command function (also written into the stubs)."""
    parts = [summary.strip(), ""]
    if doc_extra:
        parts += [textwrap.dedent(doc_extra).strip(), ""]
    parts += ["Parameters", "----------"]
    parts += [describe(p).rstrip() for p in params]
    if extra_doc:
        parts.append(textwrap.dedent(extra_doc).rstrip())
    parts.append(_LIMITS_DOC.rstrip())
    kind = "dict" if returns is None else f"tensegrity.results.{result_class_name(returns)}"
    parts += [
        "",
        "Returns",
        "-------",
        kind,
        "    The command's ``--json`` report, every vector or matrix a numpy array (a dict",
        "    whose keys are also attributes; its fields and units: the class's docstring).",
    ]
    return "\n".join(parts) + "\n"


# --- the commands whose runs stream ------------------------------------------------------


def make_simulate(summary, doc_extra):
    params = REGISTRY["simulate"]["params"]
    extra = (("trajectory", True), ("progress", None))
    sig = _signature(params, ("scene",), extra)

    def simulate(*args, **kwargs):
        bound = _call("simulate", sig, args, kwargs)
        limits = _limits(bound)
        keep = bool(bound.pop("trajectory", True))
        report = _reporter(bound.pop("progress", None), "simulate", "s simulated")
        values = _given(bound)
        try:
            out, raw = _native.simulate(values, limits, keep, report)
        except Interrupted as e:
            raise _partial(e, _samples) from None
        finally:
            _close(report)
        if keep:
            out.update(_samples(raw))
        return out

    extra_doc = """\
    trajectory : bool, optional
        Keep the samples at the output times (the scene's, else ``output_interval``, else
        t_end/200), as the command line's ``--out`` writes them: the result then also holds
        ``t``, ``trajectory`` and the histories the scene's ``[simulation] record`` lists
        (their shapes and units: :class:`tensegrity.results.SimulateResult`). Default: True.
    progress : callable or bool, optional
        """ + PROGRESS_DOC
    return finish(simulate, "simulate", sig, summary, params, doc_extra, extra_doc)


def _samples(raw):
    """The samples' arrays (read-only views of the bytes from Rust): ``t`` (S,),
    ``trajectory`` (S, n, 3), and where the scene records them ``velocities`` (S, n, 3),
    ``member_forces`` (S, m), ``kinetic_energy`` and ``energy`` (S,), ``contact_nodes`` (c,)
    with ``contact_forces`` (S, c, 3)."""

    def arr(key):
        return np.frombuffer(raw[key], dtype=np.float64)

    t, n = arr("t"), raw["n_nodes"]
    s = len(t)
    out = {"t": t, "trajectory": arr("nodes").reshape(s, n, 3)}
    if "velocities" in raw:
        out["velocities"] = arr("velocities").reshape(s, n, 3)
    if "member_forces" in raw:
        out["member_forces"] = arr("member_forces").reshape(s, raw["n_members"])
    if "energy" in raw:
        e = arr("energy").reshape(s, 2)
        out["kinetic_energy"], out["energy"] = e[:, 0], e[:, 1]
    if "contact_forces" in raw:
        nodes = np.asarray(raw["contact_nodes"], dtype=np.int64)
        out["contact_nodes"] = nodes
        out["contact_forces"] = arr("contact_forces").reshape(s, len(nodes), 3)
    return out


def progress_doc(measure, note="", lead=""):
    """The documentation of a ``progress`` keyword whose ``(done, total)`` are ``measure``
    (``note``: what else to know about this call's count; ``lead``: a sentence before)."""
    text = (lead + "Reports the progress of the run: ``callback(done, total)`` ({}) at most "
            "every 50 ms while it runs and once at its end, from the calling thread, ``done`` "
            "never decreasing (an exception it raises stops the run as Ctrl-C does, with the "
            "results so far); ``True``: a ``tqdm`` bar (``tqdm.auto``, in notebooks too) when "
            "tqdm is installed, else a line on stderr every few seconds; any other value but "
            "``None`` or ``False`` is a TypeError. {}Default: none.").format(
        measure, (note.strip() + " ") if note else "")
    indent = " " * 8
    return textwrap.fill(text, 88, initial_indent=indent, subsequent_indent=indent).lstrip()


#: The documentation of the ``progress`` keyword of ``simulate`` and ``roll``.
PROGRESS_DOC = progress_doc("simulated seconds and the end time")


def _reporter(progress, what, unit):
    """The callback of a ``progress`` keyword (``None`` for none); a value that is neither
    a callable nor a flag is a TypeError naming the keyword."""
    if progress is None or (isinstance(progress, (bool, np.bool_)) and not progress):
        return None
    if callable(progress):
        return progress
    if not isinstance(progress, (bool, np.bool_)):
        raise TypeError(f"{what}(): progress = {progress!r}: expected a callable "
                        "progress(done, total), True (a bar or lines on stderr), or "
                        "None/False (none)")
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return _LineReporter(what, unit)
    return _TqdmReporter(tqdm, what, unit)


def _close(report):
    close = getattr(report, "close", None)
    if close is not None:
        close()


class _TqdmReporter:
    """A tqdm bar fed by ``(done, total)`` calls."""

    def __init__(self, tqdm, what, unit):
        self.tqdm, self.what, self.unit, self.bar = tqdm, what, unit, None

    def __call__(self, done, total):
        if self.bar is None:
            self.bar = self.tqdm(total=total, desc=self.what, unit=self.unit.split()[0])
        self.bar.update(done - self.bar.n)

    def close(self):
        if self.bar is not None:
            self.bar.close()


class _LineReporter:
    """A line on stderr every few seconds: ``simulate: 42 % (0.42 of 1 s simulated)``."""

    def __init__(self, what, unit, every=5.0):
        self.what, self.unit, self.every, self.last = what, unit, every, None

    def __call__(self, done, total):
        import sys
        import time
        now = time.monotonic()
        if self.last is None or now - self.last >= self.every or done >= total:
            self.last = now
            percent = 100.0 * done / total if total > 0 else 100.0
            print(f"{self.what}: {percent:.0f} % ({done:g} of {total:g} {self.unit})",
                  file=sys.stderr)


def make_roll(summary, doc_extra):
    params = REGISTRY["roll"]["params"]
    sig = _signature(params, (), (("progress", None),))

    def roll(*args, **kwargs):
        bound = _call("roll", sig, args, kwargs)
        limits = _limits(bound)
        report = _reporter(bound.pop("progress", None), "roll", "s simulated")
        values = _given(bound)
        try:
            out, raw = _native.roll(values, limits, report)
        except (Interrupted, TensegrityError) as e:
            raise _partial(e, _with_history) from None
        finally:
            _close(report)
        out["history"] = _history(raw)
        return out

    extra_doc = """\
    The result's ``history`` holds every sample (1 ms) as numpy arrays, the columns of the
    command line's ``roll --out`` CSV (their units: :class:`tensegrity.results.RollResult`).

    progress : callable or bool, optional
        """ + PROGRESS_DOC
    return finish(roll, "roll", sig, summary, params, doc_extra, extra_doc)


def _history(raw):
    """A rolling history's columns (read-only views of the bytes from Rust)."""
    cols = _native.ROLL_HISTORY_COLUMNS
    rows = np.frombuffer(raw, dtype=np.float64).reshape(-1, len(cols))
    return {name: rows[:, k] for k, name in enumerate(cols)}


def _with_history(raw):
    """The partial result of a stopped roll: its report (if any) with its history."""
    report, history = raw
    if report is None:
        return None
    report["history"] = _history(history)
    return report


def _count(value, name, least):
    """``value`` as an int of at least ``least``, else an InputError naming ``name``."""
    import operator
    try:
        n = operator.index(value)
    except TypeError:
        raise _input(name, f"{name} = {value!r}: expected a whole number") from None
    if n < least:
        raise _input(name, f"{name} = {n}: must be at least {least}")
    return n


def _real(value, name):
    """``value`` as a finite float, else an InputError naming ``name``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise _input(name, f"{name} = {value!r}: expected a number") from None
    if not np.isfinite(x):
        raise _input(name, f"{name} = {x}: must be finite")
    return x


def _input(name, message):
    from .errors import InputError
    e = InputError(message)
    e.parameter = name
    return e


def _columns(raw, names):
    """Rows of f64 (raw bytes from Rust) as a dict of read-only column views."""
    rows = np.frombuffer(raw, dtype=np.float64).reshape(-1, len(names))
    return {name: rows[:, k] for k, name in enumerate(names)}


def _friction_grid(raw, grid_points):
    """The rows of ``tipover --grid`` (σ outer) as its axes and its map."""
    cols = _columns(raw, _native.FRICTION_GRID_COLUMNS)
    n = grid_points
    return {
        "sigma": cols["sigma"][::n].copy(),
        "epsilon": cols["epsilon"][:n].copy(),
        "normalized_friction": cols["normalized_friction"].reshape(n, n),
    }


def make_tipover(summary, doc_extra):
    modes = ("tipover", "tipover_dynamic", "tipover_rolling")
    params = params_of(*modes)
    sig = _signature(params, (), (("dynamic", False), ("rolling", False), ("grid", False),
                                  ("grid_points", None), ("eps_max", None),
                                  ("progress", None)))

    def tipover(*args, **kwargs):
        bound = _call("tipover", sig, args, kwargs)
        limits = _limits(bound)
        dynamic, rolling = bool(bound.pop("dynamic", False)), bool(bound.pop("rolling", False))
        grid = bool(bound.pop("grid", False))
        grid_points, eps_max = bound.pop("grid_points", None), bound.pop("eps_max", None)
        report = _reporter(bound.pop("progress", None), "tipover", "s simulated")
        if report is not None and not (dynamic or rolling):
            raise TypeError("tipover(): progress applies to the timed runs only (dynamic=True "
                            "or rolling=True)")
        if dynamic and rolling:
            raise TypeError("tipover(): dynamic and rolling cannot be used together")
        if grid and (dynamic or rolling):
            raise TypeError("tipover(): grid cannot be used with dynamic or rolling")
        values = _given(bound)
        if grid:
            if values:
                name = next(iter(values))
                raise _input(name, f"{name} does not apply to the grid (it depends on σ and ε "
                                   "only: grid_points, eps_max)")
            n = _count(GRID_POINTS if grid_points is None else grid_points, "grid_points", 2)
            e = _real(EPS_MAX if eps_max is None else eps_max, "eps_max")
            raw = _native.friction_grid(n, e, limits)
            return {"grid_points": n, "eps_max": e, "grid": _friction_grid(raw, n)}
        for name, v in (("grid_points", grid_points), ("eps_max", eps_max)):
            if v is not None:
                raise _input(name, f"{name} applies to the grid only (grid=True)")
        if dynamic or rolling:
            try:
                out, raw = _native.tipover_history(rolling, values, limits, list(modes), report)
            finally:
                _close(report)
            cols = (_native.TIPOVER_ROLLING_COLUMNS if rolling
                    else _native.TIPOVER_DYNAMIC_COLUMNS)
            out["history"] = _columns(raw, cols)
            return out
        return _native.run(modes[0], values, limits, list(modes))

    extra_doc = """\
    dynamic : bool, optional
        Check the threshold with the full 3-D dynamics (the command line's ``--dynamic``):
        the wheel at rest on a side on level ground, a lateral force ramped at the hub. The
        result's ``history`` holds the samples of ``--out``: t (s), force (N), lean (rad),
        near_normal and far_normal (N).
    rolling : bool, optional
        Roll the wheel down a plane with a side slope and report its lean (``--rolling``).
        The result's ``history`` holds the samples of ``--out``: t (s), lean (rad),
        downhill and across (m).
    grid : bool, optional
        Instead of one wheel, F_f/F_e over a σ × ε grid (Fig. 3.13, the command line's
        ``--grid FILE``): the result's ``grid`` holds the axes ``sigma`` (grid_points,) and
        ``epsilon`` (grid_points,) and the map ``normalized_friction`` (grid_points,
        grid_points), indexed [σ, ε] (dimensionless); no other wheel keyword applies.
    grid_points : int, optional
        Grid points per axis, at least 2 (``--grid-points``). Default: 50.
    eps_max : float, optional
        Largest ε of the grid, positive (``--eps-max``). Default: 1.0.
    progress : callable or bool, optional
        """ + progress_doc(
        "simulated seconds and the run's end time: ``settle + ramp_time + hold`` with "
        "``dynamic``, ``t_end`` with ``rolling``",
        "The library runs the wheel in one call and cannot count as it goes: until the run "
        "ends, ``done`` is the elapsed time against the engine's work estimate scaled to the "
        "end time (at most 99 % of it); at its end, the time of its last sample.",
        lead="With ``dynamic`` or ``rolling`` only (else a TypeError). ")
    return finish(tipover, "tipover", sig, summary, params, doc_extra, extra_doc)


#: The command line's defaults of ``tipover --grid``: points per axis and the largest ε.
GRID_POINTS, EPS_MAX = _native.FRICTION_GRID_POINTS, _native.FRICTION_GRID_EPS_MAX
#: The command line's defaults of ``tbar --mass-sweep``: complexities and offsets δ (or ε).
SWEEP_COMPLEXITIES = tuple(_native.MASS_SWEEP_COMPLEXITIES)
SWEEP_DELTAS = tuple(_native.MASS_SWEEP_OFFSETS)


def table(rows):
    """A list of report rows (dicts) as a dict of numpy columns: nested fields by dotted
    name (``mass.mass_kg``); numbers as float64 (int64 when every one is whole; a null
    NaN), flags as bool, text as str (a null ``""``), a column null in every row NaN; a
    row's vector as an object array."""
    names = []
    flat_rows = []
    for row in rows:
        flat = {}
        _flatten(row, "", flat)
        flat_rows.append(flat)
        for k in flat:
            if k not in names:
                names.append(k)
    # a field null in some rows and an object in others: its dotted fields only
    names = [n for n in names if not any(m.startswith(n + ".") for m in names)]
    out = {}
    for name in names:
        cells = [r.get(name) for r in flat_rows]
        out[name] = _cells(cells)
    return out


def _flatten(value, prefix, out):
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(v, f"{prefix}{k}" if not prefix else f"{prefix}.{k}", out)
    else:
        out[prefix] = value


def _cells(cells):
    known = [c for c in cells if c is not None]
    if not known:
        return np.full(len(cells), np.nan)
    if known and all(isinstance(c, (bool, np.bool_)) for c in known) and len(known) == len(cells):
        return np.array(cells, dtype=bool)
    numeric = all(isinstance(c, (int, float, np.integer, np.floating))
                  and not isinstance(c, (bool, np.bool_)) for c in known)
    if numeric and known:
        if len(known) == len(cells) and all(isinstance(c, (int, np.integer)) for c in cells):
            return np.array(cells, dtype=np.int64)
        return np.array([np.nan if c is None else float(c) for c in cells], dtype=np.float64)
    if all(isinstance(c, str) for c in known):
        return np.array(["" if c is None else c for c in cells], dtype=str)
    arr = np.empty(len(cells), dtype=object)
    arr[:] = cells
    return arr


def make_tbar(summary, doc_extra):
    params = REGISTRY["tbar"]["params"]
    sig = _signature(params, (), (("loop_study", False), ("mass_sweep", False),
                                  ("sweep_complexities", None), ("sweep_deltas", None)))

    def tbar(*args, **kwargs):
        bound = _call("tbar", sig, args, kwargs)
        limits = _limits(bound)
        loop, mass = bool(bound.pop("loop_study", False)), bool(bound.pop("mass_sweep", False))
        qs, ds = bound.pop("sweep_complexities", None), bound.pop("sweep_deltas", None)
        if loop and mass:
            raise TypeError("tbar(): loop_study and mass_sweep cannot be used together")
        if not mass:
            for name, v in (("sweep_complexities", qs), ("sweep_deltas", ds)):
                if v is not None:
                    raise _input(name, f"{name} applies to the mass sweep only (mass_sweep=True)")
        values = _given(bound)
        if loop:
            rows = _native.tbar_study("loop_study", values)
            return {"loop_study": table(rows), "rows": rows}
        if mass:
            qs = [_count(q, "sweep_complexities", 1)
                  for q in _sequence(SWEEP_COMPLEXITIES if qs is None else qs,
                                     "sweep_complexities")]
            ds = [_real(d, "sweep_deltas")
                  for d in _sequence(SWEEP_DELTAS if ds is None else ds, "sweep_deltas")]
            rows = _native.tbar_study("mass_sweep", values, qs, ds)
            return {"mass_sweep": table(rows), "rows": rows}
        return _native.run("tbar", values, limits)

    extra_doc = """\
    loop_study : bool, optional
        Instead of one analysis, the single loop against the extended wheel (copy at
        ``extended``, default 0.5 r₀) with a free rim body, free and standing on the ground
        (the command line's ``--loop-study``): the result's ``rows`` are its ``--json`` rows
        and ``loop_study`` the same as numpy columns (counts; in_plane, out_of_plane,
        internal, rigid: mechanism counts as numbers; prestress_margin dimensionless).
    mass_sweep : bool, optional
        Instead of one analysis, the mass price against the Michell truss of single treads
        over ``sweep_complexities`` × ``sweep_deltas`` (``--mass-sweep``): ``rows`` as its
        ``--json`` and ``mass_sweep`` as columns (min_prestress N, mass.mass_kg kg,
        mass.michell_mass_kg kg, mass.yield_mass_kg kg, mass.mass_ratio; NaN and "" where a
        tread has no load envelope, ``note`` says why).
    sweep_complexities : sequence of int, optional
        Complexities q of the mass sweep, each at least 1. Default: (1, 2, 3).
    sweep_deltas : sequence of float, optional
        Offsets δ (or angles ε, radians, with ``spherical``) of the mass sweep. Default:
        (0.05, 0.1, 0.25, 0.5, 1.0)."""
    return finish(tbar, "tbar", sig, summary, params, doc_extra, extra_doc)


def _sequence(value, name):
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise _input(name, f"{name} = {value!r}: expected a sequence")
    return list(value)


def make_tbar_roll(summary, doc_extra):
    params = REGISTRY["tbar_roll"]["params"]
    sig = _signature(params, (), (("progress", None),))
    row_columns = [c["name"][len("rows.0."):] for c in REGISTRY["tbar_roll"]["columns"]
                   if c["name"].startswith("rows.0.")]

    def tbar_roll(*args, **kwargs):
        bound = _call("tbar_roll", sig, args, kwargs)
        limits = _limits(bound)
        report = _reporter(bound.pop("progress", None), "tbar_roll", "s simulated")
        values = _given(bound)
        try:
            out, raw = _native.tbar_roll(values, limits, report)
        finally:
            _close(report)
        out["table"] = {c: _cells([_lookup(row, c) for row in out["rows"]])
                        for c in row_columns}
        out["history"] = _columns(raw, _native.ROLL_HISTORY_COLUMNS)
        return out

    extra_doc = """\
    The result's ``table`` holds the command line's ``tbar roll --out`` CSV as numpy columns
    (one entry per number of treads; its columns and units: ``TbarRollResult``), its
    ``history`` every 1 ms sample of the first row's T-bar run (the columns of ``roll``'s
    history); each row's ``tbar.convergence`` is the run's convergence object.

    progress : callable or bool, optional
        """ + progress_doc(
        "simulated seconds of every row's T-bar run and their total, the number of tread "
        "counts times t_end",
        "Row k counts from k·t_end; its toroid column and tip-over run after its T-bar run, "
        "so the count holds at (k+1)·t_end meanwhile. With a callback each tread count runs "
        "as a call of its own (the rows are the same to the bit).")
    return finish(tbar_roll, "tbar_roll", sig, summary, params, doc_extra, extra_doc)


def _lookup(row, dotted):
    v = row
    for part in dotted.split("."):
        if not isinstance(v, dict) or part not in v:
            return None
        v = v[part]
    return v


# --- sweeps -------------------------------------------------------------------------------

_SWEEP_DOC = """\
Run a parameter study (the command line's ``tensegrity sweep SPEC --out FILE``).

Parameters
----------
spec : dict or str or os.PathLike
    The sweep spec: a dict with the keys of a spec file (``study``, ``fixed``, ``axes``,
    ``derived``, ``output``), TOML text, or the path of a spec file.
threads : int, optional
    Worker threads (default: one per core). Rows are the same for any thread count.
out : str or os.PathLike, optional
    Also keep the rows in this CSV file (the command line's ``--out``; with ``resume`` an
    interrupted file is continued). Default: a temporary file, removed afterwards.
shard : (int, int), optional
    Run only shard ``k`` of ``n`` (cases with id = k-1 mod n), as ``--shard K/N``.
resume : bool, optional
    Continue the rows already in ``out``.
units : bool, optional
    Write the ``# units:`` line into ``out``.
progress : callable or bool, optional
    """ + progress_doc(
    "the cases in the file and the cases of the sweep (of its shard)",
    "Counted by the sweeps crate's own hook, the one the command line's bar is fed by: a "
    "case counts once its row is written, in case order; with ``resume`` the rows already "
    "in the file count from the start.").replace("\n        ", "\n    ") + """
""" + _LIMITS_DOC + """
Returns
-------
tensegrity.results.SweepResult
    A dict with one entry per column of the CSV, in its order: numeric columns as float64
    (int64 for whole numbers) numpy arrays, an empty cell NaN; text columns (``status``,
    ``message``, choices) as numpy arrays of str. A result column that repeats an axis
    column of the same name with the same values is given once. ``rows()`` (or ``row(k)``)
    gives the rows as :class:`tensegrity.results.SweepRow` objects (the cells as Python
    scalars, the column names as attributes), ``columns`` the names with their units, and
    ``to_dict()`` the plain dict of columns.
"""


def sweep(spec, threads=None, out=None, shard=None, resume=False, units=False,
          max_memory=None, max_work=None, max_output=None, progress=None):
    limits = {"max_memory": max_memory, "max_work": max_work, "max_output": max_output}
    if isinstance(spec, dict):
        text, is_path = _native.toml_text(dict(spec)), False
    elif isinstance(spec, os.PathLike) or ("\n" not in spec and "=" not in spec):
        text, is_path = os.fspath(spec), True
    else:
        text, is_path = spec, False
    if shard is not None:
        shard = (int(shard[0]), int(shard[1]))
    report = _reporter(progress, "sweep", "cases")
    temporary = out is None
    if temporary:
        fd, path = tempfile.mkstemp(prefix="tensegrity-sweep-", suffix=".csv")
        os.close(fd)
        os.remove(path)
    else:
        path = os.fspath(out)
    try:
        try:
            _native.sweep(text, is_path, path, limits,
                          None if threads is None else int(threads), shard,
                          bool(resume), bool(units), report)
        except Interrupted as e:
            e.partial = read_rows(path) if os.path.exists(path) else None
            raise e from None
        finally:
            _close(report)
        rows = read_rows(path)
        from .results import SweepResult
        return SweepResult(rows, dict(_native.sweep_columns(text, is_path)))
    finally:
        if temporary:
            for p in (path, os.path.join(os.path.dirname(path),
                                         "." + os.path.basename(path) + ".lock")):
                if os.path.exists(p):
                    os.remove(p)


sweep.__doc__ = _SWEEP_DOC


def read_rows(path):
    """The rows of a sweep's CSV as a :class:`tensegrity.results.SweepResult` (a dict of
    numpy columns, see :func:`sweep`; the units of its ``# units:`` line, if it has one)."""
    from .results import SweepResult
    with open(path, newline="", encoding="utf-8") as f:
        lines = list(f)
    units_line = next((line for line in lines if line.startswith("# units:")), None)
    lines = [line for line in lines if not line.startswith("#")]
    rows = list(csv.reader(lines))
    if not rows:
        return SweepResult()
    header, body = rows[0], rows[1:]
    units = {}
    if units_line is not None:
        fields = next(csv.reader([units_line[len("# units:"):].strip()]), [])
        units = {name: ("" if u == "-" else u) for name, u in zip(header, fields)}
    columns = {}
    for j, name in enumerate(header):
        cells = [r[j] if j < len(r) else "" for r in body]
        col = _column(cells)
        if name in columns:
            same = _same(columns[name], col)
            if same:
                continue
            k = 1
            while "{}.{}".format(name, k) in columns:
                k += 1
            units["{}.{}".format(name, k)] = units.get(name, "")
            name = "{}.{}".format(name, k)
        columns[name] = col
    return SweepResult(columns, units)


def _column(cells):
    try:
        numbers = [float(c) if c != "" else float("nan") for c in cells]
    except ValueError:
        return np.array(cells, dtype=str)
    if cells and all(c != "" and c.lstrip("-").isdigit() for c in cells):
        return np.array([int(c) for c in cells], dtype=np.int64)
    if cells and all(c == "" for c in cells):
        return np.array(cells, dtype=str)
    return np.array(numbers, dtype=np.float64)


def _same(a, b):
    if a.shape != b.shape:
        return False
    if a.dtype.kind in "fi" and b.dtype.kind in "fi":
        return bool(np.array_equal(a.astype(float), b.astype(float), equal_nan=True))
    return bool(np.array_equal(a, b))
