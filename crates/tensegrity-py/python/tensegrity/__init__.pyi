"""Type stubs of the package ``tensegrity`` (generated from the engine's registry by
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


class Result(Dict[str, Any]):
    """A command's report: a dict whose keys are also attributes."""
    def __getattr__(self, name: str) -> Any: ...
    def to_dict(self) -> Dict[str, Any]: ...


class StaticsResult(Result):
    """The result of :func:`tensegrity.statics`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    nodes
    bars
    strings
    rank
    self_stress_dim
    mechanisms
    internal_mechanisms
    prestressable
    prestress_margin
    prestress_stable
    smallest_singular_value
    rank_tolerance
    input_rounding : float [m]
    residual : float [N]
    load_carried
    mass_kg : float [kg]
    sizing_warning
    modal_error
    sizing_error
    statics_method
    statics_warning
    spectral_gap.tolerance
    spectral_gap.sigma_above
    spectral_gap.sigma_below
    spectral_gap.ratio
    spectral_gap.block
    """
    nodes: Any
    bars: Any
    strings: Any
    rank: Any
    self_stress_dim: Any
    mechanisms: Any
    internal_mechanisms: Any
    prestressable: Any
    prestress_margin: Any
    prestress_stable: Any
    smallest_singular_value: Any
    rank_tolerance: Any
    input_rounding: float
    residual: float
    load_carried: Any
    mass_kg: float
    sizing_warning: Any
    modal_error: Any
    sizing_error: Any
    statics_method: Any
    statics_warning: Any
    def plot(self, structure: Any = ..., ax: Any = ...) -> Any: ...


class SimulateResult(Result):
    """The result of :func:`tensegrity.simulate`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    t_end : float [s]
    steps
    rhs_evals
    energy_drift
    bar_length_drift : float [m]
    constraint_drift : float [m]
    wall_time_s : float [s]
    valid
    convergence.refinement
    convergence.converged
    convergence.companion
    convergence.order
    convergence.cost
    t : ndarray (samples,) s
        sample times
    trajectory : ndarray (samples, nodes, 3) m
        node positions
    velocities : ndarray (samples, nodes, 3) m/s
        node velocities, if recorded
    member_forces : ndarray (samples, members) N
        axial forces, tension positive (bars, strings, clusters), if recorded
    kinetic_energy : ndarray (samples,) J
        kinetic energy, if recorded
    energy : ndarray (samples,) J
        total energy, if recorded
    contact_nodes : ndarray (contact nodes,)
        the nodes that can touch the ground
    contact_forces : ndarray (samples, contact nodes, 3) N
        ground forces, if recorded
    """
    t_end: float
    steps: Any
    rhs_evals: Any
    energy_drift: Any
    bar_length_drift: float
    constraint_drift: float
    wall_time_s: float
    valid: Any
    t: np.ndarray
    trajectory: np.ndarray
    velocities: np.ndarray
    member_forces: np.ndarray
    kinetic_energy: np.ndarray
    energy: np.ndarray
    contact_nodes: np.ndarray
    contact_forces: np.ndarray
    def plot(self, what: str = ..., ax: Any = ...) -> Any: ...


class ToroidResult(Result):
    """The result of :func:`tensegrity.toroid`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    nodes
    bars
    strings
    stabilize
    rank
    self_stress_dim
    prestressable
    prestress_margin
    internal_mechanisms
    mass_kg : float [kg]
    I1 : float [kg m^2]
    spectral_gap.tolerance
    spectral_gap.sigma_above
    spectral_gap.sigma_below
    spectral_gap.ratio
    spectral_gap.block
    statics_warning
    """
    nodes: Any
    bars: Any
    strings: Any
    stabilize: Any
    rank: Any
    self_stress_dim: Any
    prestressable: Any
    prestress_margin: Any
    internal_mechanisms: Any
    mass_kg: float
    I1: float
    statics_warning: Any
    def plot(self, structure: Any = ..., ax: Any = ...) -> Any: ...


class RollResult(Result):
    """The result of :func:`tensegrity.roll`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    fidelity
    fidelity_reason
    contact
    sides
    incline_rad : float [rad]
    t_end : float [s]
    mass_kg : float [kg]
    I1 : float [kg m^2]
    mu
    restitution
    ground_damping : float [N s/m]
    integrator
    dt : float [s]
    valid
    impacts
    first_impact.t : float [s]
    first_impact.omega_before : float [rad/s]
    first_impact.omega_after : float [rad/s]
    axle_height_oscillation : float [m]
    mean_axle_height : float [m]
    mean_speed : float [m/s]
    final_speed : float [m/s]
    max_reaction : float [N]
    min_normal_force : float [N]
    airborne_fraction
    slip_fraction
    max_penetration : float [m]
    energy_balance_error
    lift_off_time : float [s]
    required_friction
    mean_slip_speed : float [m/s]
    convergence.refinement
    convergence.converged
    convergence.companion
    convergence.order
    convergence.cost
    history : ndarray dict of (samples,) arrays
        every 1 ms sample, the columns of ``roll --out``: t, axle_s, axle_h, omega, pivot_m, normal_N, tangential_N, energy_J, slip_m_s (s, m along the slope, m, rad/s, m, N, N, J, m/s)
    """
    fidelity: Any
    fidelity_reason: Any
    contact: Any
    sides: Any
    incline_rad: float
    t_end: float
    mass_kg: float
    I1: float
    mu: Any
    restitution: Any
    ground_damping: float
    integrator: Any
    dt: float
    valid: Any
    impacts: Any
    axle_height_oscillation: float
    mean_axle_height: float
    mean_speed: float
    final_speed: float
    max_reaction: float
    min_normal_force: float
    airborne_fraction: Any
    slip_fraction: Any
    max_penetration: float
    energy_balance_error: Any
    lift_off_time: float
    required_friction: Any
    mean_slip_speed: float
    history: Dict[str, np.ndarray]
    def plot(self, ax: Any = ...) -> Any: ...


class TipoverResult(Result):
    """The result of :func:`tensegrity.tipover`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    mass_kg : float [kg]
    rho
    epsilon
    sigma
    cot_theta
    critical_lateral_force : float [N]
    normalized_friction
    min_friction_to_tip
    sides
    outer_tread : float [m]
    hub_height : float [m]
    static_threshold : float [N]
    dynamic_threshold : float [N]
    relative_difference
    max_lean : float [rad]
    final_lean : float [rad]
    static_tip_angle : float [rad]
    tipped
    tip_time : float [s]
    max_penetration : float [m]
    valid
    convergence.refinement
    convergence.converged
    convergence.companion
    convergence.order
    convergence.cost
    static_critical_side_slope : float [rad]
    rms_lean : float [rad]
    fell
    fall_time : float [s]
    downhill : float [m]
    history : ndarray dict of (samples,) arrays
        with ``dynamic=True``: every ``output_dt`` sample, the columns of ``tipover --dynamic --out``: t, force, lean, near_normal, far_normal (s, N lateral hub force, rad lean, N summed normal force on the near and the far tread edge); with ``rolling=True`` those of ``tipover --rolling --out``: t, lean, downhill, across (s, rad lean, m hub travel downhill, m hub drift across the slope)
    grid : ndarray dict: sigma (grid_points,), epsilon (grid_points,), normalized_friction (grid_points, grid_points)
        with ``grid=True``: the map of ``tipover --grid`` (Fig. 3.13), F_f/F_e (dimensionless) at [σ, ε]; its axes σ = R_i/R_o and ε = t/T (dimensionless); the CSV's rows are σ outer, ε inner
    """
    mass_kg: float
    rho: Any
    epsilon: Any
    sigma: Any
    cot_theta: Any
    critical_lateral_force: float
    normalized_friction: Any
    min_friction_to_tip: Any
    sides: Any
    outer_tread: float
    hub_height: float
    static_threshold: float
    dynamic_threshold: float
    relative_difference: Any
    max_lean: float
    final_lean: float
    static_tip_angle: float
    tipped: Any
    tip_time: float
    max_penetration: float
    valid: Any
    static_critical_side_slope: float
    rms_lean: float
    fell: Any
    fall_time: float
    downhill: float
    history: Dict[str, np.ndarray]
    grid: Dict[str, np.ndarray]
    def plot(self, ax: Any = ...) -> Any: ...


class MichellResult(Result):
    """The result of :func:`tensegrity.michell`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    params.complexity
    params.r0 : float [m]
    params.beta : float [rad]
    params.phi : float [rad]
    params.geometry.kind
    params.geometry.delta
    params.geometry.epsilon : float [rad]
    method
    material
    prestress : float [N]
    mass_kg.yield : float [kg]
    mass_kg.yield_buckling : float [kg]
    normalized_yield_mass
    """
    method: Any
    material: Any
    prestress: float
    normalized_yield_mass: Any
    def plot(self, ax: Any = ...) -> Any: ...


class MichellOptimizeResult(Result):
    """The result of :func:`tensegrity.michell_optimize`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    geometry.kind
    geometry.delta
    geometry.epsilon : float [rad]
    radius_ratio
    beta : float [rad]
    phi : float [rad]
    complexity
    mass_kg : float [kg]
    member_mass_kg : float [kg]
    joint_mass_kg : float [kg]
    joints
    normalized_yield_mass
    continuum_normalized_mass
    planar_mass_kg : float [kg]
    mass_penalty
    searched_to
    """
    radius_ratio: Any
    beta: float
    phi: float
    complexity: Any
    mass_kg: float
    member_mass_kg: float
    joint_mass_kg: float
    joints: Any
    normalized_yield_mass: Any
    continuum_normalized_mass: Any
    planar_mass_kg: float
    mass_penalty: Any
    searched_to: Any


class MichellTableResult(Result):
    """The result of :func:`tensegrity.michell_table`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    """


class TbarResult(Result):
    """The result of :func:`tensegrity.tbar`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    params.michell.complexity
    params.michell.r0 : float [m]
    params.michell.beta : float [rad]
    params.michell.phi : float [rad]
    params.michell.geometry.kind
    params.michell.geometry.delta
    params.michell.geometry.epsilon : float [rad]
    params.bar_base
    params.layout.kind
    params.layout.offset : float [m]
    params.rim
    nodes
    bars
    rim
    rim_bars
    strings
    treads
    rank
    self_stress_dim
    mechanisms
    internal_mechanisms
    statics_method
    prestressable
    prestress_margin
    load : float [N]
    ea : float [N]
    min_prestress : float [N]
    critical_member.member
    critical_member.kind
    critical_member.index
    critical_member.tread
    critical_member.azimuth : float [rad]
    critical_member.polar : float [rad]
    prestress : float [N]
    slack_fraction
    bar_always_compressed
    min_strings_carrying
    bar_always_carries
    mass_kg : float [kg]
    mass.material
    mass.mass_kg : float [kg]
    mass.yield_mass_kg : float [kg]
    mass.michell_mass_kg : float [kg]
    mass.mass_ratio
    envelope_carried
    spectral_gap.tolerance
    spectral_gap.sigma_above
    spectral_gap.sigma_below
    spectral_gap.ratio
    spectral_gap.block
    statics_warning
    rows : ndarray list of dicts
        with ``loop_study=True`` or ``mass_sweep=True``: the study's rows as its ``--json``
    loop_study : ndarray dict of (6,) arrays
        with ``loop_study=True``: the rows as columns: structure, stance (text), contacts, nodes, members, free_dofs, rank, self_stress_dim, mechanisms (counts), rigid, in_plane, out_of_plane, internal (mechanism counts by kind), prestress_margin (dimensionless)
    mass_sweep : ndarray dict of (complexities × deltas,) arrays
        with ``mass_sweep=True``: the rows as columns: complexity, delta (δ, or ε in rad), min_prestress (N), mass.mass_kg, mass.michell_mass_kg, mass.yield_mass_kg (kg), mass.mass_ratio, mass.material, note (NaN or "" where a tread has no load envelope)
    """
    nodes: Any
    bars: Any
    rim: Any
    rim_bars: Any
    strings: Any
    treads: Any
    rank: Any
    self_stress_dim: Any
    mechanisms: Any
    internal_mechanisms: Any
    statics_method: Any
    prestressable: Any
    prestress_margin: Any
    load: float
    ea: float
    min_prestress: float
    prestress: float
    slack_fraction: Any
    bar_always_compressed: Any
    min_strings_carrying: Any
    bar_always_carries: Any
    mass_kg: float
    envelope_carried: Any
    statics_warning: Any
    rows: List[Dict[str, Any]]
    loop_study: Dict[str, np.ndarray]
    mass_sweep: Dict[str, np.ndarray]
    def plot(self, ax: Any = ...) -> Any: ...


class TbarRollResult(Result):
    """The result of :func:`tensegrity.tbar_roll`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    model
    fidelity
    full_tensegrity_rolling
    structure
    rim
    incline_rad : float [rad]
    t_end : float [s]
    valid
    rows.0.treads
    rows.0.phi : float [rad]
    rows.0.tbar.mass_kg : float [kg]
    rows.0.tbar.I1 : float [kg m^2]
    rows.0.tbar.impact_ratio
    rows.0.tbar.valid
    rows.0.tbar.impacts
    rows.0.tbar.first_impact.t : float [s]
    rows.0.tbar.axle_height_oscillation : float [m]
    rows.0.tbar.mean_speed : float [m/s]
    rows.0.tbar.final_speed : float [m/s]
    rows.0.tbar.min_normal_force : float [N]
    rows.0.tbar.airborne_fraction
    rows.0.tbar.slip_fraction
    rows.0.tbar.max_penetration : float [m]
    rows.0.tbar.energy_balance_error
    rows.0.tbar.convergence.converged
    rows.0.toroid.mass_kg : float [kg]
    rows.0.toroid.I1 : float [kg m^2]
    rows.0.toroid.valid
    rows.0.toroid.impacts
    rows.0.toroid.axle_height_oscillation : float [m]
    rows.0.toroid.mean_speed : float [m/s]
    rows.0.tipover.critical_lateral_force : float [N]
    rows.0.tipover.min_friction_to_tip
    table : ndarray dict of (tread counts,) arrays
        the rows of ``tbar roll --out``, one per number of treads, by the CSV's column names (treads; phi rad; tbar.mass_kg kg; tbar.I1 kg m²; speeds m/s; forces N; lengths m; flags as bool; NaN for an empty cell)
    history : ndarray dict of (samples,) arrays
        every 1 ms sample of the first row's T-bar run, the columns of ``roll``'s history: t, axle_s, axle_h, omega, pivot_m, normal_N, tangential_N, energy_J, slip_m_s (s, m along the slope, m, rad/s, m, N, N, J, m/s)
    """
    model: Any
    fidelity: Any
    full_tensegrity_rolling: Any
    structure: Any
    rim: Any
    incline_rad: float
    t_end: float
    valid: Any
    table: Dict[str, np.ndarray]
    history: Dict[str, np.ndarray]
    def plot(self, ax: Any = ...) -> Any: ...


class FormfindResult(Result):
    """The result of :func:`tensegrity.formfind`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    source
    n_nodes
    n_bars
    n_strings
    method
    self_stress_dim
    prestressable
    prestress_stable
    residual
    iterations
    tolerance
    height : float [m]
    max_bar_length : float [m]
    prestress : float [N]
    """
    source: Any
    n_nodes: Any
    n_bars: Any
    n_strings: Any
    method: Any
    self_stress_dim: Any
    prestressable: Any
    prestress_stable: Any
    residual: Any
    iterations: Any
    tolerance: Any
    height: float
    max_bar_length: float
    prestress: float
    def plot(self, structure: Any = ..., ax: Any = ...) -> Any: ...


class SolveResult(Result):
    """The result of :func:`tensegrity.solve`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    method
    final_load_factor
    max_displacement : float [m]
    points
    limit_points
    first_limit_load_factor
    bifurcations
    first_slack_load_factor
    slack_strings
    stability
    stop
    """
    method: Any
    final_load_factor: Any
    max_displacement: float
    points: Any
    limit_points: Any
    first_limit_load_factor: Any
    bifurcations: Any
    first_slack_load_factor: Any
    slack_strings: Any
    stability: Any
    stop: Any
    def plot(self, ax: Any = ...) -> Any: ...


class DesignResult(Result):
    """The result of :func:`tensegrity.design`: its ``--json`` report as a dict
    whose keys are also attributes (``to_dict()`` gives the plain dict).

    Fields: the report's scalars (with a unit: a float in that unit; without: a
    count, a flag or a name), a dotted name ``a.b`` being ``r['a']['b']``; the
    report also holds its vectors and tables, every one a numpy array.

    Fields
    ------
    source
    initial_objective
    objective
    converged
    stationary
    projected_gradient
    stop
    method
    iterations
    evaluations
    """
    source: Any
    initial_objective: Any
    objective: Any
    converged: Any
    stationary: Any
    projected_gradient: Any
    stop: Any
    method: Any
    iterations: Any
    evaluations: Any


class SweepRow(Result):
    """One row of a sweep (:meth:`SweepResult.rows`, :meth:`SweepResult.row`): a dict of
    the row's CSV cells by column name whose keys are also attributes (``row.case``,
    ``row.sides``; a dotted name such as ``mass.mass_kg`` by key), each a Python scalar:
    ``int`` in a column of whole numbers, ``float`` in a numeric one (``nan`` for an empty
    cell), ``str`` in a text one (``status``, ``message``, choices).
    """


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
    def __init__(self, columns: Any = ..., units: Optional[Dict[str, str]] = ...) -> None: ...
    @property
    def columns(self) -> List[Tuple[str, Optional[str]]]: ...
    def rows(self) -> List[SweepRow]: ...
    def row(self, k: int) -> SweepRow: ...
    def plot(self, x: str, y: str, group: Optional[str] = ..., ax: Any = ...) -> Any: ...


def statics(
    scene: Scene,
    *,
    rank_tol: Optional[float] = ...,
    input_precision: Optional[float] = ...,
    modes: Optional[int] = ...,
    mass: Literal['lumped', 'consistent'] = ...,
    least_squares: bool = ...,
    response: bool = ...,
    method: Literal['auto', 'dense', 'sparse'] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> StaticsResult:
    """Statics of a scene: rank of the equilibrium matrix, self-stress, mechanisms, prestressability, load solve, reactions and minimum-mass sizing (``tensegrity statics SCENE --json``).

    ``scene`` is a scene file's path, the TOML text of a scene, or a Structure.

    Parameters
    ----------
    scene : str, os.PathLike or Structure
        The scene file (TOML), or the scene's TOML text (a value naming no file, with a line
        break or an `=`, and not one line ending in .toml). Required
    rank_tol : float, optional
        Relative rank tolerance of the SVD, in (0, 1) (default: max(rows, cols) · machine
        epsilon); must be finite and positive
    input_precision : float, optional
        Relative precision of the node coordinates, a fraction of the largest one, in [0,
        0.1) (default: judged from their digits, e.g. 5e-10 for coordinates written to 9
        significant digits; 0: exact); the rank decision discounts the singular values
        rounding of this size can create; must be finite
    modes : int, optional
        Also report the K lowest natural frequencies about the current state (strings need
        stiffness and rest length, bars mass, material and radius); must be finite
    mass : {'lumped', 'consistent'}
        Mass matrix of the modes: lumped (half of each bar at each end) or consistent (the
        rigid-bar mass matrix of the dynamics). Default: 'lumped'
    least_squares : bool
        When the loads cannot be carried (the structure is a mechanism for them), report the
        least-squares force densities marked `load_carried: false`, without sizing, instead
        of failing
    response : bool
        Also report the linear response at the scene's geometry: node displacements, member
        force changes and reactions under the loads, from the tangent stiffness (bars need
        material and radius, strings stiffness); computed whenever a support has a
        `displacement`
    method : {'auto', 'dense', 'sparse'}
        Factorisation: auto (the dense SVD for small structures, the sparse rank-revealing
        QR from 50 dofs and members on, 300 for coordinates judged rounded), dense or
        sparse. Default: 'auto'
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.StaticsResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def simulate(
    scene: Scene,
    *,
    t_end: Optional[float] = ...,
    integrator: Optional[Literal['rk4', 'rk45', 'rattle', 'sdirk', 'imex', 'imex-ark', 'rk4-flight', 'newmark']] = ...,
    dt: Optional[float] = ...,
    rtol: Optional[float] = ...,
    atol: Optional[float] = ...,
    output_interval: Optional[float] = ...,
    strict: bool = ...,
    convergence_check: bool = ...,
    trajectory: bool = ...,
    progress: Union[bool, Callable[[float, float], Any], None] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> SimulateResult:
    """Simulate a scene in time: rigid-bar dynamics with strings, gravity, ground contact and actuation (``tensegrity simulate SCENE --json``).

    ``scene`` is a scene file's path, the TOML text of a scene, or a Structure.

    Parameters
    ----------
    scene : str, os.PathLike or Structure
        The scene file (TOML) with an optional `[simulation]`, `[ground]`, `[[actuation]]`,
        or the scene's TOML text. Required
    t_end : float, optional
        End time; overrides `[simulation] t_end` (s); must be finite and positive
    integrator : {'rk4', 'rk45', 'rattle', 'sdirk', 'imex', 'imex-ark', 'rk4-flight', 'newmark'}, optional
        Integrator; overrides `[simulation] integrator` (default rk4): fixed-step RK4,
        adaptive RK45, constraint-preserving RATTLE, adaptive L-stable SDIRK for stiff
        strings and contact, IMEX (penalty contact split off, linearly implicit), IMEX-ARK
        (penalty contact implicit in every stage), RK4-flight (RK4, 5x longer steps while no
        contact node is near the ground); imex, imex-ark and rk4-flight project onto the
        constraints after every step; an elastic scene takes rk4, rk45 or newmark (implicit
        trapezoidal rule, stable at any step)
    dt : float, optional
        Fixed step, at most the output interval (default: rk4, rattle and rk4-flight 1e-3,
        imex 5e-4, imex-ark 2.5e-4, shortened to the output interval; rk4-flight's contact
        step, 5x in flight) or maximum step (rk45, sdirk; default t_end) (s); must be finite
        and positive
    rtol : float, optional
        Relative tolerance (rk45, sdirk); must be finite and positive
    atol : float, optional
        Absolute tolerance (rk45, sdirk); must be finite and positive
    output_interval : float, optional
        Sampling interval of the written trajectory; default: the scene's output times, else
        t_end/200 (s); must be finite and positive
    strict : bool
        Fail (after writing the outputs) when the run has a drift warning or its final state
        did not converge
    convergence_check : bool
        Re-run at a companion resolution beside the run (twice a fixed step where that stays
        stable and accurate, half a run's work; else half the step) and report each headline
        quantity's change, extrapolated error and status, and the check's cost, in
        `convergence`; rolling: the companion starts turned by 1e-6 rad, and where a
        quantity moved a second run tells chaotic quantities; an unconverged result is not
        valid
    trajectory : bool, optional
        Keep the samples at the output times: the result also holds ``t``, ``trajectory`` and the histories the scene records (SimulateResult lists them). Default: True.
    progress : callable or bool, optional
        ``callback(done, total)`` (simulated seconds, end time) while the run goes on; ``True``: a tqdm bar, else lines on stderr. Default: none.
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.SimulateResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def toroid(
    *,
    sides: int = ...,
    outer_tread: float = ...,
    inner_tread: float = ...,
    offset: float = ...,
    outer_radius: float = ...,
    inner_radius: float = ...,
    rim_radius: float = ...,
    stabilize: str = ...,
    bar_density: float = ...,
    scale_with_n: bool = ...,
    prism_only: bool = ...,
    min_tension: float = ...,
    rim_window: bool = ...,
    string_stiffness: Optional[float] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> ToroidResult:
    """Build and analyse the 3-bar-prism tensegrity toroid wheel: counts, rank, prestress, flexes, inertia (``tensegrity toroid --json``).

    Parameters
    ----------
    sides : int
        Number of sides (prisms) n, at least 3; must be finite. Default: 8
    outer_tread : float
        Outer tread width T (m); must be finite and positive. Default: 0.4
    inner_tread : float
        Inner tread width t (m); must be finite and positive. Default: 0.3
    offset : float
        Tread offset D (m); must be finite and non-negative. Default: 0.1
    outer_radius : float
        Outer radius R_o (m); must be finite and positive. Default: 1.0
    inner_radius : float
        Inner radius R_i < R_o (m); must be finite and positive. Default: 0.6
    rim_radius : float
        Rim radius R_m (m); must be finite and positive. Default: 0.8
    stabilize : str
        Stabilising strings: comma-separated spokes, inner, outer, or none. Default:
        'spokes,inner'
    bar_density : float
        Bar mass per length (kg/m); must be finite and positive. Default: 1.0
    scale_with_n : bool
        Scale the tread offset with the sides: D_n = D·8/n (0.8/n for the reference D =
        0.1), so large wheels stay prestressable
    prism_only : bool
        Analyse a single prism (six nodes, K6) instead of the whole wheel
    min_tension : float
        Minimum string tension of the prestress design (N); must be finite and positive.
        Default: 10.0
    rim_window : bool
        Also search the rim radii R_m for which a single prism is prestressable
    string_stiffness : float, optional
        Give every string of the exported structure this stiffness and the rest length that
        realises the prestress design (N/m); must be finite and positive
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.ToroidResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def roll(
    *,
    sides: int = ...,
    outer_tread: float = ...,
    inner_tread: float = ...,
    offset: float = ...,
    outer_radius: float = ...,
    inner_radius: float = ...,
    rim_radius: float = ...,
    stabilize: str = ...,
    bar_density: float = ...,
    scale_with_n: bool = ...,
    incline: Union[float, str] = ...,
    t_end: float = ...,
    dt: Optional[float] = ...,
    fidelity: Literal['rigid', 'full', 'auto'] = ...,
    contact: Literal['penalty', 'thesis', 'stick'] = ...,
    ground_damping: Optional[float] = ...,
    ground_stiffness: float = ...,
    mu: float = ...,
    restitution: float = ...,
    string_stiffness: float = ...,
    min_tension: float = ...,
    integrator: Literal['rk4', 'rk45', 'rattle', 'sdirk', 'imex', 'imex-ark', 'rk4-flight'] = ...,
    gravity: float = ...,
    strict: bool = ...,
    convergence_check: bool = ...,
    ensemble: int = ...,
    progress: Union[bool, Callable[[float, float], Any], None] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> RollResult:
    """Roll the toroid wheel down an incline, rigid or full model, with its validity (``tensegrity roll --json``).

    Parameters
    ----------
    sides : int
        Number of sides (prisms) n, at least 3; must be finite. Default: 8
    outer_tread : float
        Outer tread width T (m); must be finite and positive. Default: 0.4
    inner_tread : float
        Inner tread width t (m); must be finite and positive. Default: 0.3
    offset : float
        Tread offset D (m); must be finite and non-negative. Default: 0.1
    outer_radius : float
        Outer radius R_o (m); must be finite and positive. Default: 1.0
    inner_radius : float
        Inner radius R_i < R_o (m); must be finite and positive. Default: 0.6
    rim_radius : float
        Rim radius R_m (m); must be finite and positive. Default: 0.8
    stabilize : str
        Stabilising strings: comma-separated spokes, inner, outer, or none. Default:
        'spokes,inner'
    bar_density : float
        Bar mass per length (kg/m); must be finite and positive. Default: 1.0
    scale_with_n : bool
        Scale the tread offset with the sides: D_n = D·8/n (0.8/n for the reference D =
        0.1), so large wheels stay prestressable
    incline : float or str
        Slope angle (e.g. `50deg`, `pi/4`, radians) (rad); radians, or a string such as
        '30deg', 'pi/8', '3pi/4'; must lie in [0, 1.5707963267948966). Default:
        0.8726646259971648
    t_end : float
        Simulated time (s); must be finite and positive. Default: 10.0
    dt : float, optional
        Integration step, at most the 1 ms output interval (unset: 1e-4 s; for the full
        model on a penalty or stick ground 5e-4 s under IMEX and 2.5e-4 s under IMEX-ARK,
        shorter for strings stiffer than 2e4 N/m) (s); must be finite and positive
    fidelity : {'rigid', 'full', 'auto'}
        Model: rigid polygon, full tensegrity, or auto (the cheapest valid one). Default:
        'auto'
    contact : {'penalty', 'thesis', 'stick'}
        Ground contact of the full model. Default: 'penalty'
    ground_damping : float, optional
        Ground damping per contact node (unset: from the restitution) (N s/m); must be
        finite and non-negative
    ground_stiffness : float
        Penalty ground stiffness per contact node (N/m); must be finite and positive.
        Default: 100000.0
    mu : float
        Static friction coefficient μ_s (μ_k = 0.75 μ_s); must be finite and non-negative.
        Default: 0.8
    restitution : float
        Normal coefficient of restitution e of an impact, in [0, 1]; must lie in [0, 1].
        Default: 0.0
    string_stiffness : float
        String stiffness of the full model (N/m); must be finite and positive. Default:
        20000.0
    min_tension : float
        Smallest string tension of the full model's prestress (N); must be finite and
        positive. Default: 20.0
    integrator : {'rk4', 'rk45', 'rattle', 'sdirk', 'imex', 'imex-ark', 'rk4-flight'}
        Integrator of the full model. Default: 'imex-ark'
    gravity : float
        Gravity (m/s^2); must be finite and positive. Default: 9.81
    strict : bool
        Fail (exit 1, after writing the outputs) when the result is not valid: outside its
        model's assumptions or not converged
    convergence_check : bool
        Re-run at a companion resolution beside the run (twice a fixed step where that stays
        stable and accurate, half a run's work; else half the step) and report each headline
        quantity's change, extrapolated error and status, and the check's cost, in
        `convergence`; rolling: the companion starts turned by 1e-6 rad, and where a
        quantity moved a second run tells chaotic quantities; an unconverged result is not
        valid
    ensemble : int
        Also roll K copies from starting poses turned by ±1e-6 rad, ±2e-6 rad, … (in
        parallel) and report the mean and 95 % interval of every headline quantity against
        the other model (0: none); must be finite. Default: 0
    The result's ``history``: every 1 ms sample as arrays (RollResult lists its columns).
    progress : callable or bool, optional
        ``callback(done, total)`` (simulated seconds, end time) while the run goes on; ``True``: a tqdm bar, else lines on stderr. Default: none.
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.RollResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def tipover(
    *,
    sides: int = ...,
    outer_tread: float = ...,
    inner_tread: float = ...,
    offset: float = ...,
    outer_radius: float = ...,
    inner_radius: float = ...,
    rim_radius: float = ...,
    stabilize: str = ...,
    bar_density: float = ...,
    scale_with_n: bool = ...,
    gravity: float = ...,
    sigma: Optional[float] = ...,
    epsilon: Optional[float] = ...,
    string_stiffness: float = ...,
    min_tension: float = ...,
    string_damping: float = ...,
    ground_stiffness: float = ...,
    ground_damping: float = ...,
    mu: float = ...,
    friction_regularization: float = ...,
    dt: float = ...,
    output_dt: float = ...,
    settle: float = ...,
    ramp_time: float = ...,
    ramp_to: float = ...,
    hold: float = ...,
    strict: bool = ...,
    convergence_check: bool = ...,
    incline: Union[float, str] = ...,
    side_slope: Union[float, str] = ...,
    t_end: float = ...,
    dynamic: bool = ...,
    rolling: bool = ...,
    grid: bool = ...,
    grid_points: Optional[int] = ...,
    eps_max: Optional[float] = ...,
    progress: Union[bool, Callable[[float, float], Any], None] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> TipoverResult:
    """Tip-over of the toroid wheel under a lateral force; ``dynamic=True`` checks the threshold with the full dynamics, ``rolling=True`` the lean while rolling down a side slope (``tensegrity tipover [--dynamic|--rolling] --json``).

    Parameters
    ----------
    sides : int
        Number of sides (prisms) n, at least 3; must be finite. Default: 8
    outer_tread : float
        Outer tread width T (m); must be finite and positive. Default: 0.4
    inner_tread : float
        Inner tread width t (m); must be finite and positive. Default: 0.3
    offset : float
        Tread offset D (m); must be finite and non-negative. Default: 0.1
    outer_radius : float
        Outer radius R_o (m); must be finite and positive. Default: 1.0
    inner_radius : float
        Inner radius R_i < R_o (m); must be finite and positive. Default: 0.6
    rim_radius : float
        Rim radius R_m (m); must be finite and positive. Default: 0.8
    stabilize : str
        Stabilising strings: comma-separated spokes, inner, outer, or none. Default:
        'spokes,inner'
    bar_density : float
        Bar mass per length (kg/m); must be finite and positive. Default: 1.0
    scale_with_n : bool
        Scale the tread offset with the sides: D_n = D·8/n (0.8/n for the reference D =
        0.1), so large wheels stay prestressable
    gravity : float
        Gravity (m/s^2); must be finite and positive. Default: 9.81
    sigma : float, optional
        σ = R_i/R_o: sets inner_radius = σ outer_radius; must be finite
    epsilon : float, optional
        ε = t/T: sets inner_tread = ε outer_tread; must be finite
    string_stiffness : float
        String stiffness of the wheel: the threshold is the rigid one only for a stiff wheel
        (a soft one deforms and tips early) (N/m); must be finite and positive. Default:
        2000000.0
    min_tension : float
        Smallest string tension of the prestress (N); must be finite and positive. Default:
        2000.0
    string_damping : float
        Axial damping of every string (N s/m); must be finite and non-negative. Default:
        200.0
    ground_stiffness : float
        Penalty ground stiffness (N/m); must be finite and positive. Default: 1000000.0
    ground_damping : float
        Penalty ground damping (N s/m); must be finite and non-negative. Default: 2000.0
    mu : float
        Static friction coefficient of the ground (kinetic = 0.75 μ); must be finite and
        non-negative. Default: 1.0
    friction_regularization : float
        Regularisation velocity of the friction law (m/s); must be finite and positive.
        Default: 0.01
    dt : float
        RK4 step; stiffer strings need a smaller one (default 1e-4 s for the standing wheel
        under a ramp, 2.5e-5 s for the rolling one, whose wobble coarser steps damp away)
        (s); must be finite and positive. Default: 0.0001
    output_dt : float
        Output interval of the history (s); must be finite and positive. Default: 0.002
    settle : float
        Time at rest before the ramp starts (s); must be finite and non-negative. Default:
        0.5
    ramp_time : float
        Ramp duration, from 0 to ramp_to × the static threshold (s); must be finite and
        positive. Default: 4.0
    ramp_to : float
        Largest force of the ramp, as a multiple of the static threshold; must be finite and
        positive. Default: 1.3
    hold : float
        Time the largest force is held after the ramp (s); must be finite and non-negative.
        Default: 0.0
    strict : bool
        Fail (exit 1, after writing the outputs) when the result is not valid: outside its
        model's assumptions or not converged
    convergence_check : bool
        Re-run at a companion resolution beside the run (twice a fixed step where that stays
        stable and accurate, half a run's work; else half the step) and report each headline
        quantity's change, extrapolated error and status, and the check's cost, in
        `convergence`; rolling: the companion starts turned by 1e-6 rad, and where a
        quantity moved a second run tells chaotic quantities; an unconverged result is not
        valid
    incline : float or str
        Incline downhill, e.g. `30deg` (rad); radians, or a string such as '30deg', 'pi/8',
        '3pi/4'; must lie in [0, 1.5707963267948966). Default: 0.5235987755982988
    side_slope : float or str
        Side slope across, e.g. `5deg` (rad); radians, or a string such as '30deg', 'pi/8',
        '3pi/4'; must be finite. Default: 0.08726646259971647
    t_end : float
        Simulated time (s); must be finite and positive. Default: 3.0
    dynamic : bool, optional
        The threshold checked by the full dynamics; the result's ``history`` holds the samples of ``--out``.
    rolling : bool, optional
        The lean while rolling down a side slope; ``history`` as for dynamic.
    grid : bool, optional
        The F_f/F_e map over σ × ε (Fig. 3.13) in the result's ``grid``.
    grid_points : int, optional
        Grid points per axis (default 50).
    eps_max : float, optional
        Largest ε of the grid (default 1.0).
    progress : callable or bool, optional
        With dynamic or rolling only: ``callback(done, total)`` (simulated seconds, end time; paced by the work estimate until the run ends); ``True``: a tqdm bar, else lines on stderr. Default: none.
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.TipoverResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def michell(
    *,
    complexity: int = ...,
    planar: bool = ...,
    cylindrical: Optional[float] = ...,
    spherical: Optional[Union[float, str]] = ...,
    beta: Union[float, str] = ...,
    phi: Union[float, str] = ...,
    r0: float = ...,
    load: float = ...,
    azimuth: Union[float, str] = ...,
    polar: Union[float, str] = ...,
    material: str = ...,
    extra_strings: Optional[str] = ...,
    method: Literal['recursive', 'global'] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> MichellResult:
    """Discrete Michell truss (planar, cylindrical or spherical) under a tip load: nodes, member forces, sizing (``tensegrity michell --json``).

    Parameters
    ----------
    complexity : int
        Complexity q (number of member levels; level-q nodes are supports); must be at least
        1. Required
    planar : bool
        Skelton's planar truss in the y–z plane
    cylindrical : float, optional
        3-D truss, cylindrical parameterisation with dimensionless offset δ (eq. 4.11); must
        be finite
    spherical : float or str, optional
        3-D truss, spherical parameterisation with angle ε (eq. 4.12), e.g. `pi/24` (rad);
        radians, or a string such as '30deg', 'pi/8', '3pi/4'; must be finite
    beta : float or str
        Departure angle β, e.g. `pi/6` or `30deg` (rad); radians, or a string such as
        '30deg', 'pi/8', '3pi/4'; must be finite. Required
    phi : float or str
        Segmentation angle φ, e.g. `pi/8` (rad); radians, or a string such as '30deg',
        'pi/8', '3pi/4'; must be finite. Required
    r0 : float
        Initial radius r₀ (m); must be finite and positive. Default: 1.0
    load : float
        Tip load magnitude w₀ (N); must be finite and positive. Default: 1000.0
    azimuth : float or str
        Load azimuth φ_w (eq. 4.13); with the default polar angle the load is −ι̂₃ (rad);
        radians, or a string such as '30deg', 'pi/8', '3pi/4'; must be finite. Default: 0.0
    polar : float or str
        Load polar angle γ from ι̂₃ (eq. 4.13) (rad); radians, or a string such as '30deg',
        'pi/8', '3pi/4'; must be finite. Default: 3.141592653589793
    material : str
        Material of bars and strings (aluminium, steel, titanium, carbon_fibre, nylon,
        uhmwpe). Default: 'steel'
    extra_strings : str, optional
        Add the extra strings of §4.6 (q ≥ 2, 3-D), each pretensioned to this many newtons,
        or `auto`: to the smallest prestress above which no member but the tip members
        changes sign over the nominal load region of complexity 1
    method : {'recursive', 'global'}
        Force propagation method. Default: 'recursive'
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.MichellResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def michell_optimize(
    *,
    planar: bool = ...,
    cylindrical: Optional[float] = ...,
    spherical: Optional[Union[float, str]] = ...,
    radius_ratio: float = ...,
    complexity: Optional[int] = ...,
    joint_mass: float = ...,
    max_complexity: int = ...,
    material: str = ...,
    load: float = ...,
    r0: float = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> MichellOptimizeResult:
    """Mass-optimal Michell truss for a fixed radius ratio (``tensegrity michell optimize --json``).

    Parameters
    ----------
    planar : bool
        Skelton's planar truss in the y–z plane
    cylindrical : float, optional
        3-D truss, cylindrical parameterisation with dimensionless offset δ (eq. 4.11); must
        be finite
    spherical : float or str, optional
        3-D truss, spherical parameterisation with angle ε (eq. 4.12), e.g. `pi/24` (rad);
        radians, or a string such as '30deg', 'pi/8', '3pi/4'; must be finite
    radius_ratio : float
        ρ = r_q / r₀ in (0, 1): the support circle over the tip radius; must be finite.
        Required
    complexity : int, optional
        The complexity q; optimised when left out (then joint_mass is needed); must be at
        least 1
    joint_mass : float
        Mass of each joint, added per node (kg); must be finite and non-negative. Default:
        0.0
    max_complexity : int
        Largest complexity the search tries; must be finite. Default: 60
    material : str
        Material of bars and strings. Default: 'steel'
    load : float
        Tip load w₀, perpendicular to the tip radius (−ι̂₃) (N); must be finite and
        positive. Default: 1000.0
    r0 : float
        Initial (tip) radius r₀ (m); must be finite and positive. Default: 1.0
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.MichellOptimizeResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def michell_table(
    *,
    max_complexity: int = ...,
    load: float = ...,
    material: str = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> MichellTableResult:
    """Michell truss mass against complexity, planar and 3-D (thesis Fig. 4.18; ``tensegrity michell-table``).

    Parameters
    ----------
    max_complexity : int
        Largest complexity (the table runs q = 2..=Q, at most the 3-D families' 100); must
        lie in [2, 100]. Default: 35
    load : float
        Tip load w₀, along −ι̂₃ (N); must be finite and positive. Default: 1000.0
    material : str
        Material of bars and strings. Default: 'steel'
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.MichellTableResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def tbar(
    *,
    complexity: int = ...,
    beta: Union[float, str] = ...,
    phi: Union[float, str] = ...,
    cylindrical: Optional[float] = ...,
    spherical: Optional[Union[float, str]] = ...,
    r0: float = ...,
    wheel: bool = ...,
    extended: Optional[float] = ...,
    bar_base: Literal['rim', 'chord'] = ...,
    rim: Literal['fixed', 'body'] = ...,
    load: float = ...,
    ea: float = ...,
    prestress: Optional[float] = ...,
    directions: int = ...,
    material: str = ...,
    loop_study: bool = ...,
    mass_sweep: bool = ...,
    sweep_complexities: Optional[Sequence[int]] = ...,
    sweep_deltas: Optional[Sequence[float]] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> TbarResult:
    """T-bar tread or wheel (thesis ch. 5): geometry, statics, omnidirectional load envelope, mass (``tensegrity tbar --json``).

    Parameters
    ----------
    complexity : int
        Complexity q (lattice levels; level q lies on the rim); must be at least 1. Default:
        1
    beta : float or str
        Departure angle β (e.g. `pi/6`, `30deg`) (rad); radians, or a string such as
        '30deg', 'pi/8', '3pi/4'; must be finite. Required
    phi : float or str
        Segmentation angle φ; a wheel needs π/φ integer (rad); radians, or a string such as
        '30deg', 'pi/8', '3pi/4'; must be finite. Required
    cylindrical : float, optional
        Cylindrical parameterisation with offset δ (dimensionless, eq. 4.11); must be finite
    spherical : float or str, optional
        Spherical parameterisation with angle ε (eq. 4.12) (rad); radians, or a string such
        as '30deg', 'pi/8', '3pi/4'; must be finite
    r0 : float
        Tip radius r₀ (m); must be finite and positive. Default: 1.0
    wheel : bool
        Build the wheel: π/φ treads every 2φ about ι̂₁
    extended : float, optional
        Build the extended wheel: the wheel and a copy translated by this offset along ι̂₁
        (m); must be finite
    bar_base : {'rim', 'chord'}
        Base of the radial bar. Default: 'rim'
    rim : {'fixed', 'body'}
        Rim: rigid supports (`fixed`) or a free rim body of bars with a hub (`body`).
        Default: 'fixed'
    load : float
        Tip load magnitude w₀ of the load envelope (N); must be finite and positive.
        Default: 1.0
    ea : float
        Axial stiffness EA of every member (N); must be finite and positive. Default:
        1000000.0
    prestress : float, optional
        Bar compression P of the slack map (N); must be finite and positive
    directions : int
        Directions of the slack map (quasi-uniform sphere); must lie in [1, 1000000].
        Default: 2000
    material : str
        Material of the sizing (built-in table). Default: 'steel'
    loop_study : bool, optional
        The single loop against the extended wheel (``rows``, ``loop_study``).
    mass_sweep : bool, optional
        The mass price against the Michell truss (``rows``, ``mass_sweep``).
    sweep_complexities : sequence of int, optional
        Default (1, 2, 3).
    sweep_deltas : sequence of float, optional
        Default (0.05, 0.1, 0.25, 0.5, 1.0).
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.TbarResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def tbar_roll(
    *,
    complexity: int = ...,
    beta: Union[float, str] = ...,
    cylindrical: Optional[float] = ...,
    spherical: Optional[Union[float, str]] = ...,
    r0: float = ...,
    extended: Optional[float] = ...,
    bar_base: Literal['rim', 'chord'] = ...,
    rim: Optional[Literal['fixed', 'body']] = ...,
    fidelity: Literal['rigid', 'full', 'auto'] = ...,
    treads: Optional[Union[Sequence[int], str]] = ...,
    incline: Union[float, str] = ...,
    t_end: Optional[float] = ...,
    dt: Optional[float] = ...,
    gravity: float = ...,
    bar_density: float = ...,
    mu_static: float = ...,
    mu_kinetic: Optional[float] = ...,
    restitution: float = ...,
    rim_density: Optional[float] = ...,
    string_stiffness: float = ...,
    min_tension: Optional[float] = ...,
    contact: Literal['penalty', 'thesis', 'stick'] = ...,
    ground_stiffness: float = ...,
    ground_damping: Optional[float] = ...,
    strict: bool = ...,
    convergence_check: bool = ...,
    progress: Union[bool, Callable[[float, float], Any], None] = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> TbarRollResult:
    """Roll the T-bar wheel beside the toroid of equal outer radius, with tip-over (``tensegrity tbar roll --json``).

    Parameters
    ----------
    complexity : int
        Complexity q; must be at least 1. Default: 1
    beta : float or str
        Departure angle β (rad); radians, or a string such as '30deg', 'pi/8', '3pi/4'; must
        be finite. Default: 0.5235987755982988
    cylindrical : float, optional
        Cylindrical parameterisation with offset δ (neither given: δ = 0.25); must be finite
    spherical : float or str, optional
        Spherical parameterisation with angle ε (rad); radians, or a string such as '30deg',
        'pi/8', '3pi/4'; must be finite
    r0 : float
        Tip radius r₀: the rolling polygon's circumradius (m); must be finite and positive.
        Default: 1.0
    extended : float, optional
        Roll the extended wheel with its copy at this offset (m); must be finite
    bar_base : {'rim', 'chord'}
        Base of the radial bar. Default: 'rim'
    rim : {'fixed', 'body'}, optional
        Rim mass: fixed (massless rigid rim; rigid default) or body (full: only choice)
    fidelity : {'rigid', 'full', 'auto'}
        Rolling model (auto: rigid only where rigid and full agree within their uncertainty
        on this scene class, else full; takes the full model's defaults). Default: 'rigid'
    treads : sequence of int or str, optional
        Numbers of treads n = π/φ, each at least 3 (default 8,12,16,24 rigid, 8 full); must
        be at least 3
    incline : float or str
        Slope angle (e.g. `50deg`, `pi/4`, radians) (rad); radians, or a string such as
        '30deg', 'pi/8', '3pi/4'; must lie in [0, 1.5707963267948966). Default:
        0.5235987755982988
    t_end : float, optional
        Simulated time (default 10 s rigid, 1 s full) (s); must be finite and positive
    dt : float, optional
        Integration step, at most the 1 ms output interval (unset: 1e-4 s; for the full
        model on a penalty or stick ground 5e-4 s under IMEX and 2.5e-4 s under IMEX-ARK,
        shorter for strings stiffer than 2e4 N/m) (s); must be finite and positive
    gravity : float
        Gravity (m/s^2); must be finite and positive. Default: 9.81
    bar_density : float
        Bar density of both wheels (kg/m); must be finite and positive. Default: 1.0
    mu_static : float
        Static friction coefficient; must be finite and non-negative. Default: 0.8
    mu_kinetic : float, optional
        Kinetic friction coefficient (default 0.75 μ_s); must be finite and non-negative
    restitution : float
        Normal coefficient of restitution e of an impact, in [0, 1]; must lie in [0, 1].
        Default: 0.0
    rim_density : float, optional
        Density of the rim body's bars (default: bar_density for the rigid model, 0.05 kg/m
        for full and auto) (kg/m); must be finite and positive
    string_stiffness : float
        String stiffness of the full model (N/m); must be finite and positive. Default:
        20000.0
    min_tension : float, optional
        Full model: smallest string tension of the prestress (default: twice the weight per
        tip) (N); must be finite and positive
    contact : {'penalty', 'thesis', 'stick'}
        Ground contact of the full model, T-bar and toroid (default stick: friction that
        holds a stick). Default: 'stick'
    ground_stiffness : float
        Penalty ground stiffness per contact node (N/m); must be finite and positive.
        Default: 1000000.0
    ground_damping : float, optional
        Ground damping per contact node (unset: from the restitution) (N s/m); must be
        finite and non-negative
    strict : bool
        Fail (exit 1, after writing the outputs) when the result is not valid: outside its
        model's assumptions or not converged
    convergence_check : bool
        Re-run at a companion resolution beside the run (twice a fixed step where that stays
        stable and accurate, half a run's work; else half the step) and report each headline
        quantity's change, extrapolated error and status, and the check's cost, in
        `convergence`; rolling: the companion starts turned by 1e-6 rad, and where a
        quantity moved a second run tells chaotic quantities; an unconverged result is not
        valid
    The result's ``table``: the rows of ``tbar roll --out``; its ``history``: the 1 ms samples of the first row's T-bar run (TbarRollResult lists both).
    progress : callable or bool, optional
        ``callback(done, total)`` (simulated seconds of every row's T-bar run, tread counts × t_end); ``True``: a tqdm bar, else lines on stderr. Default: none.
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.TbarRollResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def formfind(
    *,
    topology: Optional[str] = ...,
    builtin: Optional[str] = ...,
    n: Optional[int] = ...,
    method: Optional[Literal['fdm', 'adaptive', 'dr', 'auto']] = ...,
    group: Optional[str] = ...,
    ratio: float = ...,
    prestress: float = ...,
    stiffness: float = ...,
    bar_mass: float = ...,
    tolerance: float = ...,
    max_iterations: int = ...,
    analyse: bool = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> FormfindResult:
    """Form-finding: a connectivity (built-in topology or file) to a geometry in equilibrium with a self-stress (``tensegrity formfind --json``).

    Parameters
    ----------
    topology : str, optional
        The topology file (TOML: bars, strings, groups, fixed nodes), or its TOML text (a
        value naming no file, with a line break or an `=`, and not one line ending in .toml)
    builtin : str, optional
        A built-in form instead of a topology: prism:N, octahedron, tower:N:M, grid:K
    n : int, optional
        The last size of the built-in form, appended to its name (builtin prism, n 5:
        prism:5), for sweeps; must be at least 1
    method : {'fdm', 'adaptive', 'dr', 'auto'}, optional
        Method: fdm (force density, every member's given), adaptive (force densities found
        from the connectivity), dr (dynamic relaxation from every member's length and
        stiffness) or auto (as the default, but falling back from fdm to adaptive with a
        warning); default: fdm when every member has a force density, dr when every member
        has a length, adaptive when neither is given (data given is never ignored, and fdm
        failing is an error)
    group : str, optional
        The group of the topology whose force density `ratio` multiplies
    ratio : float
        Factor on the force density of the members of `group`; must be finite and positive.
        Default: 1.0
    prestress : float
        Prestress level of the exported structure: the largest string tension (N); must be
        finite and positive. Default: 100.0
    stiffness : float
        Axial stiffness EA of the members that give none (strings' rest lengths, dynamic
        relaxation) (N); must be finite and positive. Default: 100000.0
    bar_mass : float
        Mass of each bar of the exported structure (kg); must be finite and positive.
        Default: 1.0
    tolerance : float
        Convergence tolerance of the iterative methods (relative residual); must be finite
        and positive. Default: 1e-12
    max_iterations : int
        Iteration cap of the iterative methods; must be at least 1. Default: 10000
    analyse : bool
        Analyse the found form: self-stress dimension (the rank of the equilibrium matrix),
        prestressability (the prestress-margin LP where the force densities are no witness)
        and prestress stability, the costly part on a large form; without it those report
        fields are null
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.FormfindResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def solve(
    scene: Scene,
    *,
    load_steps: Optional[int] = ...,
    target: float = ...,
    max_steps: int = ...,
    switch_branch: bool = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> SolveResult:
    """Load path of a scene: elastic bars and tension-only strings under its loads scaled by a load factor, with large displacements, through limit points (arc length) or in load steps, a stability verdict at every point (``tensegrity solve SCENE --json``).

    ``scene`` is a scene file's path, the TOML text of a scene, or a Structure.

    Parameters
    ----------
    scene : str, os.PathLike or Structure
        The scene file (TOML), or the scene's TOML text: bars with a material and a radius
        (elastic, EA = E π r²), strings with a stiffness and a rest length, supports and
        loads. Required
    load_steps : int, optional
        Load control in K equal steps of the load factor, Newton at each (it cannot pass a
        limit point; default: the arc-length path, which can); must be finite
    target : float
        The load factor λ to reach: the load is λ times the scene's loads (negative:
        reversed); must be finite. Default: 1.0
    max_steps : int
        The largest number of points of the arc-length path; must be finite. Default: 500
    switch_branch : bool
        At the first bifurcation of the arc-length path, leave it along the critical mode
        and follow the other branch (dense and sparse tangents alike: the mode is computed
        on both)
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.SolveResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def design(
    design: Optional[str],
    *,
    max_iterations: Optional[int] = ...,
    method: Optional[Literal['lbfgsb', 'levenberg_marquardt']] = ...,
    prestress: float = ...,
    stiffness: float = ...,
    bar_mass: float = ...,
    max_memory: Size = ...,
    max_work: Size = ...,
    max_output: Size = ...,
) -> DesignResult:
    """Inverse form-finding: the force densities (within bounds, shared by groups) whose force density form best meets a design file's goals (node positions or shape, member lengths, forces and directions, reactions, load path, smoothness), by L-BFGS-B on the exact gradient (or Levenberg-Marquardt on the residuals' exact Jacobian); the designed form and the history (``tensegrity design DESIGN.toml --json``).

    ``design`` is a design file's path or its TOML text.

    Parameters
    ----------
    design : str, optional
        The design file (TOML: a topology with a [design] table of parameters, terms and
        goals), or its TOML text
    max_iterations : int, optional
        Iteration cap of the optimiser (default: the file's, else 1000); must be at least 1
    method : {'lbfgsb', 'levenberg_marquardt'}, optional
        Optimiser: lbfgsb (bound-constrained quasi-Newton, any objective) or
        levenberg_marquardt (projected Levenberg-Marquardt on the residuals' exact Jacobian,
        for terms with squared or mean_squared errors: fast where L-BFGS crawls along a flat
        valley); default: the file's, else lbfgsb
    prestress : float
        Prestress level of the written scene of a form without loads (a loaded form's forces
        are those of its loads) (N); must be finite and positive. Default: 100.0
    stiffness : float
        Axial stiffness EA of the members that give none (the scene's rest lengths) (N);
        must be finite and positive. Default: 100000.0
    bar_mass : float
        Mass of each bar of the written scene (kg); must be finite and positive. Default:
        1.0
    max_memory : float or str, optional
        Refuse the call when its estimated peak memory is above this (bytes, or a size such as
        ``"500M"``, ``"16Gi"``; default: the smaller of 8 GiB and 3/4 of the available memory).
    max_work : float, optional
        Refuse the call when its estimated work is above this many seconds (default 60).
    max_output : float or str, optional
        Refuse the call when its estimated output is above this (default 1 GiB).

    Returns
    -------
    tensegrity.results.DesignResult
        The command's ``--json`` report, every vector or matrix a numpy array (a dict
        whose keys are also attributes; its fields and units: the class's docstring).
    """
    ...


def sweep(
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
