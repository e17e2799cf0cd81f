"""Writes the type stubs ``__init__.pyi`` from the engine's registry, so that the stubs list
every parameter of every command with the registry's own description:

    python -m tensegrity._stubgen > crates/tensegrity-py/python/tensegrity/__init__.pyi

The tests regenerate them and compare with the file shipped (tests/test_stubs.py).
"""

import keyword
import sys

from . import SUMMARIES, results
from ._commands import LIMITS, REGISTRY, docstring, params_of, result_class_name

_TYPE = {
    "count": "int",
    "number": "float",
    "angle": "Union[float, str]",
    "flag": "bool",
    "text": "str",
    "counts": "Union[Sequence[int], str]",
    "numbers": "Union[Sequence[float], str]",
}

_HEAD = '''"""Type stubs of the package ``tensegrity`` (generated from the engine's registry by
``python -m tensegrity._stubgen``; do not edit by hand)."""

import os
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np

from .errors import (ComputationError as ComputationError, InputError as InputError,
                     Interrupted as Interrupted, ResourceError as ResourceError,
                     TensegrityError as TensegrityError)
from .sensitivity import (DesignProblem as DesignProblem, Identification as Identification,
                          TrajectorySensitivity as TrajectorySensitivity,
                          identify as identify,
                          trajectory_sensitivity as trajectory_sensitivity,
                          FormDerivative as FormDerivative, FormGradient as FormGradient,
                          FormSensitivity as FormSensitivity,
                          RelaxedDerivative as RelaxedDerivative,
                          RelaxedGradient as RelaxedGradient,
                          RelaxedSensitivity as RelaxedSensitivity,
                          EigenSensitivity as EigenSensitivity,
                          StiffnessSensitivity as StiffnessSensitivity,
                          stiffness_sensitivity as stiffness_sensitivity,
                          MarginSensitivity as MarginSensitivity,
                          margin_sensitivity as margin_sensitivity)
from .simulator import (Actuator as Actuator, Observation as Observation,
                        Simulator as Simulator)
from .structure import Structure as Structure

__version__: str
SUMMARIES: Dict[str, str]

Scene = Union[str, "os.PathLike[str]", Structure]
Size = Union[float, str, None]
'''


def _type(p):
    if p["kind"] == "choice":
        t = "Literal[{}]".format(", ".join(repr(c) for c in p["choices"]))
    else:
        t = _TYPE[p["kind"]]
    if p["name"] == "scene":
        t = "Scene"
    if p["default"] is None and not p["required"]:
        t = "Optional[{}]".format(t)
    return t


def _default(p):
    return "..." if not p["required"] else None


def _indent(text):
    return "\n".join(("    " + line) if line else "" for line in text.splitlines())


def function(name, command_names, summary, positional=(), extra=(), extra_doc=""):
    """The stub of one function."""
    params = params_of(*command_names)
    args = []
    for p in params:
        if p["name"] in positional:
            args.append("{}: {}".format(p["name"], _type(p)))
    args.append("*")
    for p in params:
        if p["name"] not in positional:
            args.append("{}: {} = ...".format(p["name"], _type(p)))
    for n, t in extra:
        args.append("{}: {} = ...".format(n, t))
    for n in LIMITS:
        args.append("{}: Size = ...".format(n))
    doc = docstring(summary, params, extra_doc=extra_doc, returns=name)
    lines = ["def {}(".format(name)]
    lines += ["    {},".format(a) for a in args]
    lines.append(") -> {}:".format(result_class_name(name)))
    lines.append('    """' + _indent(doc).lstrip() + '\n    """')
    lines.append("    ...")
    return "\n".join(lines) + "\n"


_RESULT = 'class Result(Dict[str, Any]):\n    """A command\'s report: a dict whose keys are also attributes."""\n    def __getattr__(self, name: str) -> Any: ...\n    def to_dict(self) -> Dict[str, Any]: ...\n'


def result_classes():
    """The stubs of the result classes (:mod:`tensegrity.results`): every scalar field of
    the registry's columns (``float`` where it has a unit) and every array a function adds."""
    out = [_RESULT]
    for name in results.COMMANDS:
        lines = ["class {}(Result):".format(result_class_name(name))]
        lines.append('    """' + _indent(results.fields_doc(name)).lstrip() + '\n    """')
        for column, unit in results.columns(name):
            # a column such as `mass_kg.yield` is a key only (r["mass_kg.yield"])
            if column.isidentifier() and not keyword.iskeyword(column):
                lines.append("    {}: {}".format(column, "float" if unit else "Any"))
        for field, _, _ in results.EXTRA_FIELDS.get(name, ()):
            kind = ("Dict[str, np.ndarray]" if field in ("history", "grid", "table",
                                                         "loop_study", "mass_sweep")
                    else "List[Dict[str, Any]]" if field == "rows" else "np.ndarray")
            lines.append("    {}: {}".format(field, kind))
        lines += ["    " + m for m in results.METHOD_STUBS.get(name, ())]
        out.append("\n".join(lines) + "\n")
    out.append(_SWEEP_CLASSES)
    return out


def _class_doc(cls):
    import inspect
    return '    """' + _indent(inspect.getdoc(cls)).lstrip() + '\n    """'


_SWEEP_CLASSES = "\n".join([
    "class SweepRow(Result):",
    _class_doc(results.SweepRow),
    "",
    "",
    "class SweepResult(Result):",
    _class_doc(results.SweepResult),
    "    def __init__(self, columns: Any = ..., units: Optional[Dict[str, str]] = ...) "
    "-> None: ...",
    "    @property",
    "    def columns(self) -> List[Tuple[str, Optional[str]]]: ...",
    "    def rows(self) -> List[SweepRow]: ...",
    "    def row(self, k: int) -> SweepRow: ...",
] + ["    " + m for m in results.METHOD_STUBS.get("sweep", ())]) + "\n"


def stubs():
    """The text of ``__init__.pyi``."""
    out = [_HEAD] + result_classes()
    scene = "``scene`` is a scene file's path, the TOML text of a scene, or a Structure."
    out.append(function("statics", ["statics"], SUMMARIES["statics"] + "\n\n" + scene,
                        positional=("scene",)))
    progress = ("progress", "Union[bool, Callable[[float, float], Any], None]")
    progress_doc = ("progress : callable or bool, optional\n    ``callback(done, total)`` "
                    "(simulated seconds, end time) while the run goes on; ``True``: a tqdm bar, "
                    "else lines on stderr. Default: none.")
    out.append(function(
        "simulate", ["simulate"], SUMMARIES["simulate"] + "\n\n" + scene, positional=("scene",),
        extra=(("trajectory", "bool"), progress),
        extra_doc="trajectory : bool, optional\n    Keep the samples at the output times: the "
                  "result also holds ``t``, ``trajectory`` and the histories the scene records "
                  "(SimulateResult lists them). Default: True.\n" + progress_doc))
    out.append(function("toroid", ["toroid"], SUMMARIES["toroid"]))
    out.append(function(
        "roll", ["roll"], SUMMARIES["roll"], extra=(progress,),
        extra_doc="The result's ``history``: every 1 ms sample as arrays (RollResult lists "
                  "its columns).\n" + progress_doc))
    out.append(function(
        "tipover", ["tipover", "tipover_dynamic", "tipover_rolling"], SUMMARIES["tipover"],
        extra=(("dynamic", "bool"), ("rolling", "bool"), ("grid", "bool"),
               ("grid_points", "Optional[int]"), ("eps_max", "Optional[float]"), progress),
        extra_doc="dynamic : bool, optional\n    The threshold checked by the full dynamics; "
                  "the result's ``history`` holds the samples of ``--out``.\n"
                  "rolling : bool, optional\n    The lean while rolling down a side slope; "
                  "``history`` as for dynamic.\n"
                  "grid : bool, optional\n    The F_f/F_e map over σ × ε (Fig. 3.13) in the "
                  "result's ``grid``.\n"
                  "grid_points : int, optional\n    Grid points per axis (default 50).\n"
                  "eps_max : float, optional\n    Largest ε of the grid (default 1.0).\n"
                  "progress : callable or bool, optional\n    With dynamic or rolling only: "
                  "``callback(done, total)`` (simulated seconds, end time; paced by the "
                  "work estimate until the run ends); ``True``: a tqdm bar, else lines on "
                  "stderr. Default: none."))
    for name in ("michell", "michell_optimize", "michell_table"):
        out.append(function(name, [name], SUMMARIES[name]))
    out.append(function(
        "tbar", ["tbar"], SUMMARIES["tbar"],
        extra=(("loop_study", "bool"), ("mass_sweep", "bool"),
               ("sweep_complexities", "Optional[Sequence[int]]"),
               ("sweep_deltas", "Optional[Sequence[float]]")),
        extra_doc="loop_study : bool, optional\n    The single loop against the extended "
                  "wheel (``rows``, ``loop_study``).\n"
                  "mass_sweep : bool, optional\n    The mass price against the Michell truss "
                  "(``rows``, ``mass_sweep``).\n"
                  "sweep_complexities : sequence of int, optional\n    Default (1, 2, 3).\n"
                  "sweep_deltas : sequence of float, optional\n    Default (0.05, 0.1, 0.25, "
                  "0.5, 1.0)."))
    out.append(function(
        "tbar_roll", ["tbar_roll"], SUMMARIES["tbar_roll"], extra=(progress,),
        extra_doc="The result's ``table``: the rows of ``tbar roll --out``; its ``history``: "
                  "the 1 ms samples of the first row's T-bar run (TbarRollResult lists both).\n"
                  "progress : callable or bool, optional\n    ``callback(done, total)`` "
                  "(simulated seconds of every row's T-bar run, tread counts × t_end); "
                  "``True``: a tqdm bar, else lines on stderr. Default: none."))
    if "formfind" in REGISTRY:
        out.append(function("formfind", ["formfind"], SUMMARIES["formfind"]))
    else:
        out.append('def formfind(**kwargs: Any) -> Dict[str, Any]:\n'
                   '    """Form-finding (not in this build of the engine)."""\n    ...\n')
    out.append(function("solve", ["solve"], SUMMARIES["solve"] + "\n\n" + scene,
                        positional=("scene",)))
    out.append(function("design", ["design"], SUMMARIES["design"] + "\n\n``design`` is a "
                        "design file's path or its TOML text.", positional=("design",)))
    out.append('''def sweep(
    spec: Union[Dict[str, Any], str, "os.PathLike[str]"],
    threads: Optional[int] = ...,
    out: Union[str, "os.PathLike[str]", None] = ...,
    shard: Optional[Tuple[int, int]] = ...,
    resume: bool = ...,
    units: bool = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
    progress: Union[bool, Callable[[float, float], Any], None] = ...,
) -> SweepResult:
    """Run a parameter study (``tensegrity sweep SPEC --out FILE``): the spec as a dict,
    TOML text or a path; ``threads`` workers; ``progress``: ``callback(done, total)`` (cases
    written, cases) or ``True`` for a bar; the rows as a SweepResult, a dict of numpy
    columns with ``rows()``, ``row(k)`` and ``columns`` (names with units)."""
    ...

def read_rows(path: Union[str, "os.PathLike[str]"]) -> SweepResult:
    """The rows of a sweep's CSV as a SweepResult (a dict of numpy columns)."""
    ...

def run(command: str, **kwargs: Any) -> Dict[str, Any]:
    """Run any command of the registry by name on its parameters as keywords."""
    ...

def commands() -> Dict[str, Dict[str, Any]]:
    """The engine's registry: every command with its parameters and result columns."""
    ...

def export_mjcf(
    scene: Scene,
    path: Union[str, "os.PathLike[str]", None] = ...,
    *,
    timestep: Optional[float] = ...,
    ground_height: Optional[float] = ...,
    source: Optional[str] = ...,
) -> str:
    """MuJoCo's MJCF of a scene (``tensegrity export mjcf``): the XML text, also written to
    ``path`` if given; ``timestep`` in s (default 0.001), ``ground_height`` in m."""
    ...

def export_json(scene: Scene, path: Union[str, "os.PathLike[str]", None] = ...) -> str:
    """The scene as JSON (``tensegrity export json``): the text, also written to ``path``."""
    ...

def export_schema(path: Union[str, "os.PathLike[str]", None] = ...) -> Dict[str, Any]:
    """The JSON Schema of scene files (``tensegrity export schema``), also written to
    ``path`` if given."""
    ...

def figures() -> Dict[str, str]:
    """The project's figures: number → description."""
    ...

def figure(
    name: str,
    path: Union[str, "os.PathLike[str]"],
    size: Optional[str] = ...,
    dpi: Optional[float] = ...,
    *,
    quick: bool = ...,
    data: Union[bool, str, "os.PathLike[str]"] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> str:
    """Writes the project's figure ``name`` (``"3.10"``) to ``path`` (SVG, PNG or PDF by its
    extension; ``size`` such as ``"6x4in"``, ``dpi`` for PNG), as ``tensegrity figures``
    draws it; its data table beside it as CSV (``data``). Returns the path."""
    ...
''')
    return "\n\n".join(out)


if __name__ == "__main__":
    sys.stdout.write(stubs())
