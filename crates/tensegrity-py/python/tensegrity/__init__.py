"""tensegrity: tensegrity mechanics from Python.

Every command of the ``tensegrity`` command line is a function here — :func:`statics`,
:func:`simulate`, :func:`toroid`, :func:`roll`, :func:`tipover`, :func:`michell`,
:func:`michell_optimize`, :func:`michell_table`, :func:`tbar`, :func:`tbar_roll`,
:func:`formfind`, :func:`solve`, :func:`sweep` — taking the command's parameters as keyword arguments
(the flag names in snake_case, the same defaults; angles in radians or as text such as
``'30deg'`` or ``'pi/8'``) and returning the command's ``--json`` report as a dict, every
vector or matrix a numpy array. A scene argument is a path, TOML text or a
:class:`Structure`.

The functions are built from the engine's registry of commands (:func:`commands`), so their
keywords, defaults and docstrings are the engine's own descriptions. Long computations run
with the GIL released and stop on Ctrl-C (:class:`~tensegrity.errors.Interrupted`, with the
results so far); ``simulate``, ``roll``, ``tipover`` (dynamic or rolling), ``tbar_roll`` and
``sweep`` take ``progress=`` (a callable ``(done, total)``, or ``True`` for a bar). Bad input raises :class:`~tensegrity.errors.InputError` (a ``ValueError``)
with the command line's message.

The command line's exports are :func:`export_mjcf`, :func:`export_json` and
:func:`export_schema`; :func:`figure` writes one of the project's figures (SVG, PNG or PDF),
drawn by the same Rust code as ``tensegrity figures``.

A simulation a controller steps and steers is a :class:`Simulator` (``reset``, ``step`` with
rest lengths or rates, ``get_state``/``set_state``, observations as numpy arrays); Gymnasium
environments built on it are in :mod:`tensegrity.envs` (``pip install gymnasium``).

The exact derivatives of a force density form with held nodes (with respect to its force
densities, loads and held positions; forward, one solve a parameter, and adjoint, one solve
an objective) are a :class:`FormSensitivity`, those of a form found by dynamic relaxation
(with respect to rest lengths and stiffnesses) a :class:`RelaxedSensitivity`, every array
numpy.
"""

import copy as _copy

from . import _native
from ._commands import REGISTRY as _REGISTRY
from ._commands import make as _make
from ._commands import make_roll as _make_roll
from ._commands import make_simulate as _make_simulate
from ._commands import make_tbar as _make_tbar
from ._commands import make_tbar_roll as _make_tbar_roll
from ._commands import make_tipover as _make_tipover
from ._commands import read_rows, sweep
from ._exports import export_json, export_mjcf, export_schema, figure, figures
from .errors import (ComputationError, InputError, Interrupted, ResourceError,
                     TensegrityError)
from .results import Result, SweepResult, SweepRow
from .sensitivity import (DesignProblem, FormDerivative, FormGradient, FormSensitivity,
                          Identification, RelaxedDerivative, RelaxedGradient,
                          RelaxedSensitivity, TrajectorySensitivity, identify,
                          trajectory_sensitivity, EigenSensitivity, StiffnessSensitivity,
                          MarginSensitivity, stiffness_sensitivity, margin_sensitivity)
from .simulator import Actuator, Observation, Simulator
from .structure import Structure

__version__ = "0.1.0"

__all__ = [
    "statics", "simulate", "toroid", "roll", "tipover", "michell", "michell_optimize",
    "michell_table", "tbar", "tbar_roll", "formfind", "design", "solve", "sweep", "run",
    "commands",
    "export_mjcf", "export_json", "export_schema", "figure", "figures",
    "Structure", "Simulator", "Observation", "Actuator", "FormSensitivity", "FormDerivative", "DesignProblem",
    "TrajectorySensitivity", "trajectory_sensitivity", "Identification", "identify",
    "EigenSensitivity", "StiffnessSensitivity", "stiffness_sensitivity", "MarginSensitivity",
    "margin_sensitivity",
    "FormGradient", "RelaxedSensitivity", "RelaxedDerivative", "RelaxedGradient", "Result", "SweepResult", "SweepRow", "read_rows", "TensegrityError", "InputError", "ComputationError",
    "ResourceError", "Interrupted",
]

#: One line per function: what the command does (its parameters come from the registry).
SUMMARIES = {
    "statics": "Statics of a scene: rank of the equilibrium matrix, self-stress, mechanisms, "
               "prestressability, load solve, reactions and minimum-mass sizing "
               "(``tensegrity statics SCENE --json``).",
    "simulate": "Simulate a scene in time: rigid-bar dynamics with strings, gravity, "
                "ground contact and actuation (``tensegrity simulate SCENE --json``).",
    "toroid": "Build and analyse the 3-bar-prism tensegrity toroid wheel: counts, rank, "
              "prestress, flexes, inertia (``tensegrity toroid --json``).",
    "roll": "Roll the toroid wheel down an incline, rigid or full model, with its validity "
            "(``tensegrity roll --json``).",
    "tipover": "Tip-over of the toroid wheel under a lateral force; ``dynamic=True`` checks "
               "the threshold with the full dynamics, ``rolling=True`` the lean while rolling "
               "down a side slope (``tensegrity tipover [--dynamic|--rolling] --json``).",
    "michell": "Discrete Michell truss (planar, cylindrical or spherical) under a tip load: "
               "nodes, member forces, sizing (``tensegrity michell --json``).",
    "michell_optimize": "Mass-optimal Michell truss for a fixed radius ratio "
                        "(``tensegrity michell optimize --json``).",
    "michell_table": "Michell truss mass against complexity, planar and 3-D (thesis Fig. 4.18; "
                     "``tensegrity michell-table``).",
    "tbar": "T-bar tread or wheel (thesis ch. 5): geometry, statics, omnidirectional load "
            "envelope, mass (``tensegrity tbar --json``).",
    "tbar_roll": "Roll the T-bar wheel beside the toroid of equal outer radius, with tip-over "
                 "(``tensegrity tbar roll --json``).",
    "formfind": "Form-finding: a connectivity (built-in topology or file) to a geometry in "
                "equilibrium with a self-stress (``tensegrity formfind --json``).",
    "design": "Inverse form-finding: the force densities (within bounds, shared by groups) "
              "whose force density form best meets a design file's goals (node positions or "
              "shape, member lengths, forces and directions, reactions, load path, "
              "smoothness), by L-BFGS-B on the exact gradient (or Levenberg-Marquardt on the "
              "residuals' exact Jacobian); the designed form and the "
              "history (``tensegrity design DESIGN.toml --json``).",
    "solve": "Load path of a scene: elastic bars and tension-only strings under its loads "
             "scaled by a load factor, with large displacements, through limit points (arc "
             "length) or in load steps, a stability verdict at every point "
             "(``tensegrity solve SCENE --json``).",
}

_SCENE_DOC = """\
``scene`` is a scene file's path, the TOML text of a scene, or a :class:`Structure`."""

statics = _make("statics", "statics", SUMMARIES["statics"], ("scene",), _SCENE_DOC)
simulate = _make_simulate(SUMMARIES["simulate"], _SCENE_DOC)
toroid = _make("toroid", "toroid", SUMMARIES["toroid"])
roll = _make_roll(SUMMARIES["roll"], "")
tipover = _make_tipover(SUMMARIES["tipover"], "")
michell = _make("michell", "michell", SUMMARIES["michell"])
michell_optimize = _make("michell_optimize", "michell_optimize", SUMMARIES["michell_optimize"])
michell_table = _make("michell_table", "michell_table", SUMMARIES["michell_table"])
tbar = _make_tbar(SUMMARIES["tbar"], "")
tbar_roll = _make_tbar_roll(SUMMARIES["tbar_roll"], "")
solve = _make("solve", "solve", SUMMARIES["solve"], ("scene",), _SCENE_DOC)
design = _make("design", "design", SUMMARIES["design"], ("design",),
               "``design`` is a design file's path or its TOML text.")

if "formfind" in _REGISTRY:
    formfind = _make("formfind", "formfind", SUMMARIES["formfind"])
else:
    def formfind(**kwargs):
        """Form-finding (not in this build of the engine: its registry has no ``formfind``
        command yet)."""
        raise ComputationError("the engine of this build has no `formfind` command")


def run(command, **kwargs):
    """Run any command of the registry by name (``integrators``, ``tipover_dynamic``, …) on
    its parameters as keywords (and ``max_memory``, ``max_work``, ``max_output``): its
    report as a dict with numpy arrays."""
    from . import _commands
    if command not in _REGISTRY:
        raise InputError("no command `{}` (known: {})".format(command, ", ".join(_REGISTRY)))
    fn = _commands.make(command, command, command)
    return fn(**kwargs)


def commands():
    """The engine's registry: ``{name: {"params": [...], "columns": [...], "aliases": [...]}}``
    with every parameter's name, kind, choices, unit, help, rule and default."""
    return _copy.deepcopy(_REGISTRY)


def _export_results():
    """The result classes (:mod:`tensegrity.results`) as names of the package."""
    from . import results
    for name in results.COMMANDS:
        cls = results.result_class(name)
        globals()[cls.__name__] = cls
        __all__.append(cls.__name__)


_export_results()
