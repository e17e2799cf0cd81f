"""Exact derivatives of found forms: :class:`FormSensitivity` (the force density method) and
:class:`RelaxedSensitivity` (dynamic relaxation, with respect to rest lengths and stiffnesses).

A topology with held nodes and a force density on every member (its own or its group's) is
solved by the force density method, ``D_ff X_f = P_f - D_fx X_x``, exactly as
:func:`tensegrity.formfind` solves it, and factored once. Its derivatives with respect to the
force densities, the point loads and the held positions then cost one sparse solve each
(:meth:`FormSensitivity.forward`: nodes, member lengths, forces and reactions), and the
gradient of any scalar objective one solve whatever the number of parameters
(:meth:`FormSensitivity.adjoint`, from the objective's partial derivatives, which a Python
callable may compute). The equations are in the Rust crate ``formfind``, module
``sensitivity``.
"""

from dataclasses import dataclass

import numpy as np

from . import _native

_KINDS = ("force_density", "load", "fixed")


def _vectors(raw):
    return np.frombuffer(raw, dtype=np.float64).reshape(-1, 3)


@dataclass(frozen=True)
class FormDerivative:
    """A form, or its derivative with respect to one parameter (numpy arrays).

    Attributes
    ----------
    nodes : ndarray, shape (n, 3)
        Node positions (m), or their derivatives.
    lengths : ndarray, shape (m,)
        Member lengths (bars then strings), or their derivatives.
    forces : ndarray, shape (m,)
        Member forces q L (N, tension positive), or their derivatives.
    reactions : ndarray, shape (h, 3)
        The supports' forces on the held nodes (N), in the topology's ``fixed`` order, or
        their derivatives.
    """

    nodes: np.ndarray
    lengths: np.ndarray
    forces: np.ndarray
    reactions: np.ndarray


@dataclass(frozen=True)
class FormGradient:
    """The gradient of a scalar objective of a form (numpy arrays).

    Attributes
    ----------
    force_densities : ndarray, shape (m,)
        df/dq, one per member (bars then strings).
    loads : ndarray, shape (n, 3)
        df/dp, one per node (zero at held nodes: their loads go to the reactions).
    fixed : ndarray, shape (h, 3)
        df/dx of each held node's position, in the topology's ``fixed`` order.
    """

    force_densities: np.ndarray
    loads: np.ndarray
    fixed: np.ndarray


def _derivative(raw):
    nodes, lengths, forces, reactions = raw
    return FormDerivative(_vectors(nodes), np.asarray(lengths, dtype=np.float64),
                          np.asarray(forces, dtype=np.float64), _vectors(reactions))


class FormSensitivity:
    """A force density form with held nodes, factored for its exact derivatives.

    Parameters
    ----------
    topology : str or os.PathLike, optional
        A topology file (as :func:`tensegrity.formfind` reads it) with ``fixed`` nodes and a
        force density on every member; or
    builtin : str, optional
        A built-in topology with held nodes (``"grid:K"``).
    group, ratio : optional
        Scale a group's force densities, as in :func:`tensegrity.formfind`.

    Examples
    --------
    >>> s = FormSensitivity(builtin="grid:2")
    >>> d = s.forward("force_density", 0)            # d(nodes, lengths, ...)/dq_0
    >>> g = s.adjoint(np.tile([0.0, 0.0, 1.0], (s.n_nodes, 1)))   # f = sum of heights
    >>> bool(np.allclose(g.force_densities[0], d.nodes[:, 2].sum()))
    True
    """

    def __init__(self, topology=None, *, builtin=None, group=None, ratio=None):
        values = {"topology": topology, "builtin": builtin, "group": group, "ratio": ratio}
        self._native = _native.FormSensitivity({k: v for k, v in values.items()
                                                if v is not None})
        self.n_nodes = self._native.n_nodes
        self.held = np.asarray(self._native.held, dtype=np.int64)
        self.force_densities = np.asarray(self._native.force_densities, dtype=np.float64)
        self.n_members = len(self.force_densities)

    def form(self):
        """The form: nodes, member lengths and forces, reactions (:class:`FormDerivative`)."""
        return _derivative(self._native.form())

    def forward(self, kind, index, axis=0):
        """The derivative of the form with respect to one parameter (:class:`FormDerivative`):
        ``kind`` ``"force_density"`` (``index`` the member, bars then strings), ``"load"``
        (``index`` the node, ``axis`` 0, 1, 2 for x, y, z) or ``"fixed"`` (``index`` in the
        topology's ``fixed`` list, ``axis``). One sparse solve."""
        if kind not in _KINDS:
            raise ValueError("kind must be one of {}, not {!r}".format(_KINDS, kind))
        return _derivative(self._native.forward(kind, int(index), int(axis)))

    def adjoint(self, dnodes, dforce_densities=None):
        """The gradient (:class:`FormGradient`) of a scalar objective f from its partial
        derivatives: ``dnodes`` (n, 3), df/dx of every node, and ``dforce_densities`` (m,),
        df/dq at fixed nodes (where f depends on q directly, e.g. through the forces q L;
        default zero). One sparse solve, whatever the number of parameters."""
        dnodes = np.asarray(dnodes, dtype=np.float64)
        if dnodes.shape != (self.n_nodes, 3):
            raise ValueError("dnodes must have shape ({}, 3), not {}".format(self.n_nodes,
                                                                              dnodes.shape))
        if dforce_densities is None:
            dforce_densities = np.zeros(self.n_members)
        dq = np.asarray(dforce_densities, dtype=np.float64).ravel()
        q, loads, fixed = self._native.adjoint(dnodes.ravel().tolist(), dq.tolist())
        return FormGradient(np.asarray(q, dtype=np.float64), _vectors(loads), _vectors(fixed))

    def gradient(self, objective):
        """The value and gradient of ``objective(form)``, a Python callable that takes the
        :class:`FormDerivative` of :meth:`form` and returns ``(f, dnodes, dforce_densities)``
        (its partial derivatives, ``dforce_densities`` may be ``None``): ``(f,``
        :class:`FormGradient` ``)``."""
        f, dnodes, dq = objective(self.form())
        return float(f), self.adjoint(dnodes, dq)


@dataclass(frozen=True)
class RelaxedDerivative:
    """A relaxed form, or its derivative with respect to one parameter (numpy arrays).

    Attributes
    ----------
    nodes : ndarray, shape (n, 3)
        Node positions (m), or their derivatives (zero at held nodes).
    tensions : ndarray, shape (m,)
        Member tensions (N), or their derivatives.
    """

    nodes: np.ndarray
    tensions: np.ndarray


@dataclass(frozen=True)
class RelaxedGradient:
    """The gradient of a scalar objective of a relaxed form's nodes (numpy arrays).

    Attributes
    ----------
    rest_lengths : ndarray, shape (m,)
        df/ds0, one per member (bars then strings).
    stiffnesses : ndarray, shape (m,)
        df/dEA, one per member.
    """

    rest_lengths: np.ndarray
    stiffnesses: np.ndarray


class RelaxedSensitivity:
    """Dynamic relaxation's form with held nodes, its tangent stiffness factored for its exact
    derivatives with respect to the members' rest lengths and axial stiffnesses.

    Parameters
    ----------
    topology : str or os.PathLike
        A topology file (as :func:`tensegrity.formfind` reads it) with ``fixed`` nodes,
        initial ``nodes``, and a ``length`` on every member (its own or its group's).
    stiffness, tolerance, max_iterations : optional
        As in :func:`tensegrity.formfind` (``stiffness``: the EA of a member without its own).

    Examples
    --------
    >>> s = RelaxedSensitivity("net.toml")                        # doctest: +SKIP
    >>> d = s.forward("rest_length", 0)                           # d(nodes, tensions)/ds0_0
    >>> g = s.adjoint(np.tile([0.0, 0.0, 1.0], (s.n_nodes, 1)))  # f = sum of heights
    """

    def __init__(self, topology=None, *, builtin=None, stiffness=None, tolerance=None,
                 max_iterations=None):
        values = {"topology": topology, "builtin": builtin, "stiffness": stiffness,
                  "tolerance": tolerance, "max_iterations": max_iterations}
        self._native = _native.RelaxedSensitivity({k: v for k, v in values.items()
                                                   if v is not None})
        self.n_nodes = self._native.n_nodes

    def form(self):
        """The form: nodes and tensions (:class:`RelaxedDerivative`)."""
        nodes, tensions = self._native.form()
        return RelaxedDerivative(_vectors(nodes), np.asarray(tensions, dtype=np.float64))

    def forward(self, kind, index):
        """The derivatives of the nodes and tensions (:class:`RelaxedDerivative`) with respect
        to ``kind`` ``"rest_length"`` or ``"stiffness"`` of member ``index`` (bars then
        strings). One sparse solve."""
        if kind not in ("rest_length", "stiffness"):
            raise ValueError("kind must be 'rest_length' or 'stiffness', not {!r}".format(kind))
        nodes, tensions = self._native.forward(kind, int(index))
        return RelaxedDerivative(_vectors(nodes), np.asarray(tensions, dtype=np.float64))

    def adjoint(self, dnodes):
        """The gradient (:class:`RelaxedGradient`) of a scalar objective f of the nodes from
        ``dnodes`` (n, 3), df/dx of every node. One sparse solve, whatever the number of
        parameters."""
        dnodes = np.asarray(dnodes, dtype=np.float64)
        if dnodes.shape != (self.n_nodes, 3):
            raise ValueError("dnodes must have shape ({}, 3), not {}".format(self.n_nodes,
                                                                              dnodes.shape))
        s0, ea = self._native.adjoint(dnodes.ravel().tolist())
        return RelaxedGradient(np.asarray(s0, dtype=np.float64), np.asarray(ea, dtype=np.float64))


class DesignProblem:
    """A design problem (:func:`tensegrity.design`'s file: a topology with a ``[design]``
    table) compiled for its objective and exact gradient at any values of its variables, for
    an optimiser of your own (``scipy.optimize.minimize(..., jac=True, bounds=p.bounds)``) or
    an objective that adds Python terms to the file's. One force density solve and one
    adjoint solve per evaluation (the equations: the Rust crate ``formfind``, module
    ``design``).

    Parameters
    ----------
    design : str or os.PathLike
        The design file, or its TOML text.

    Attributes
    ----------
    start, lower, upper : ndarray, shape (k,)
        The variables' start values (the file's force densities) and bounds (N/m; ±inf for
        none).
    members : list of list of int
        The members (bars then strings) whose force density each variable sets.

    Examples
    --------
    >>> text = '''
    ... [[strings]]
    ... nodes = [0, 1]
    ... force_density = 1.0
    ... [[fixed]]
    ... node = 0
    ... position = [0.0, 0.0, 0.0]
    ... [[loads]]
    ... node = 1
    ... force = [1.0, 0.0, 0.0]
    ... [[design.terms]]
    ... [[design.terms.goals]]
    ... kind = "length"
    ... target = 2.0
    ... '''
    >>> p = DesignProblem(text)
    >>> f, g = p.objective([1.0])        # length 1 / q = 1: f = (1 - 2)^2, df/dq = 2
    >>> float(f), float(g[0])
    (1.0, 2.0)
    """

    def __init__(self, design):
        import os
        self._native = _native.DesignProblem({"design": os.fspath(design)
                                              if isinstance(design, os.PathLike) else design})
        start, lower, upper, members = self._native.variables()
        self.start = np.asarray(start, dtype=np.float64)
        self.lower = np.asarray(lower, dtype=np.float64)
        self.upper = np.asarray(upper, dtype=np.float64)
        self.members = [list(m) for m in members]

    @property
    def bounds(self):
        """The bounds as ``(lower, upper)`` pairs with ``None`` for none (scipy's form)."""
        return [(lo if np.isfinite(lo) else None, up if np.isfinite(up) else None)
                for lo, up in zip(self.lower, self.upper)]

    def objective(self, values):
        """The objective and its gradient (ndarray) at ``values`` (one per variable)."""
        f, g, _ = self._native.objective([float(v) for v in np.asarray(values).ravel()])
        return f, np.asarray(g, dtype=np.float64)

    def residuals(self, values):
        """The residuals r (ndarray, shape (r,); f = |r|^2) and their exact Jacobian (ndarray,
        shape (r, k)) at ``values``, for a file whose every term is a ``squared`` or
        ``mean_squared`` error (else refused naming the term): the model of
        ``method = "levenberg_marquardt"``, for ``scipy.optimize.least_squares(p.residual,
        p.start, jac=p.jacobian, bounds=(p.lower, p.upper))``."""
        r, j = self._native.residuals([float(v) for v in np.asarray(values).ravel()])
        r = np.asarray(r, dtype=np.float64)
        return r, np.frombuffer(j, dtype=np.float64).reshape(len(r), -1)

    def residual(self, values):
        """The residuals alone (see :meth:`residuals`)."""
        return self.residuals(values)[0]

    def jacobian(self, values):
        """The Jacobian alone (see :meth:`residuals`)."""
        return self.residuals(values)[1]

    def terms(self, values):
        """Each term's value at ``values`` (ndarray, in the file's order)."""
        _, _, t = self._native.objective([float(v) for v in np.asarray(values).ravel()])
        return np.asarray(t, dtype=np.float64)


def _scene(scene):
    import os
    return os.fspath(scene) if isinstance(scene, os.PathLike) else scene


def _parameters(parameters):
    """``("stiffness", 3)`` or ``("initial_velocity", 0, 2)`` as (kind, index, axis)."""
    out = []
    for p in parameters:
        p = tuple(p)
        if len(p) not in (2, 3):
            raise ValueError("a parameter is (kind, index) or (kind, bar, axis), not {!r}"
                             .format(p))
        out.append((str(p[0]), int(p[1]), int(p[2]) if len(p) == 3 else 0))
    return out


@dataclass(frozen=True)
class TrajectorySensitivity:
    """A trajectory and its sensitivities (numpy arrays).

    Attributes
    ----------
    times : ndarray, shape (s,)
        The sample times (s), 0 first.
    nodes : ndarray, shape (s, n, 3)
        The node positions at each sample (m).
    sensitivities : ndarray, shape (s, k, n, 3)
        d(node position)/d(parameter) at each sample, one slice per parameter.
    events : list of (float, str)
        The kinks met (a string slack or taut, a node touching or leaving the ground): the
        start of the step and what.
    rhs_evaluations : int
        Right-hand side evaluations made.
    bar_length_drift : float
        The largest bar-length error over the run relative to the shortest bar (the RK4
        steps are not projected on the bar lengths).
    warnings : list of str
        A drift past ``simulate``'s limit (10⁻⁶): the trajectory and its derivatives are
        then those of a model whose bars stretched; use a smaller ``dt``.
    """

    times: np.ndarray
    nodes: np.ndarray
    sensitivities: np.ndarray
    events: list
    rhs_evaluations: int
    bar_length_drift: float
    warnings: list


def trajectory_sensitivity(scene, parameters, *, dt, t_end, every=1):
    """The trajectory of a scene's rigid-bar dynamics (RK4 steps of ``dt`` to ``t_end``, a
    sample every ``every`` steps) and its exact forward sensitivities, integrated alongside
    the state, to ``parameters``: ``("stiffness", j)``, ``("damping", j)``,
    ``("rest_length", j)`` of string j, ``("mass", k)`` of bar k,
    ``("initial_position", k, axis)`` and ``("initial_velocity", k, axis)`` of bar k (both
    ends moved together). ``scene`` as :func:`tensegrity.simulate` takes it (its
    ``[ground]`` included; ``[[actuation]]``, elastic bars and clusters are refused). The
    equations: the Rust crate ``tensegrity-dynamics``, module ``sensitivity``.
    Returns a :class:`TrajectorySensitivity`.

    Examples
    --------
    >>> s = trajectory_sensitivity("examples/prism_drop.toml", [("mass", 0)],
    ...                            dt=1e-3, t_end=0.05)            # doctest: +SKIP
    >>> s.sensitivities.shape                                        # doctest: +SKIP
    (51, 1, 6, 3)
    """
    params = _parameters(parameters)
    times, nodes, sens, events, evals, drift, warnings = _native.trajectory_sensitivity(
        {"scene": _scene(scene)}, params, float(dt), float(t_end), int(every))
    times = np.asarray(times, dtype=np.float64)
    nodes = np.frombuffer(nodes, dtype=np.float64).reshape(len(times), -1, 3)
    sens = np.frombuffer(sens, dtype=np.float64).reshape(len(times), len(params),
                                                         nodes.shape[1], 3)
    return TrajectorySensitivity(times, nodes, sens, list(events), int(evals), float(drift),
                                 list(warnings))


@dataclass(frozen=True)
class Identification:
    """The result of :func:`identify`.

    Attributes
    ----------
    values, standard_errors : ndarray, shape (k,)
        The identified parameters and their standard errors.
    rms_start, rms : float
        The root-mean-square position residual at the start and identified (m).
    iterations : int
        Levenberg–Marquardt iterations.
    converged : bool
        Whether no parameter moved by more than the tolerance in the last iteration.
    bar_length_drift : float
        The bar-length drift of the run at the identified values (as
        :class:`TrajectorySensitivity` reports it).
    warnings : list of str
        That run's drift past ``simulate``'s limit, if any: the fit is then that of a model
        whose bars stretched; use a smaller ``dt``.
    """

    values: np.ndarray
    standard_errors: np.ndarray
    rms_start: float
    rms: float
    iterations: int
    converged: bool
    bar_length_drift: float
    warnings: list


def identify(scene, parameters, measured, *, dt, every=1, observed=None, max_iterations=50,
             tolerance=1e-9):
    """System identification: the ``parameters`` (as :func:`trajectory_sensitivity` names
    them; model parameters only) of a scene whose simulated motion best fits ``measured``,
    the positions of the ``observed`` nodes (default: all) at every sample (shape (s, o, 3):
    sample 0 the start, sample i at i * every * dt), by Levenberg–Marquardt on the exact
    sensitivities. The scene's values are the start. Returns an :class:`Identification`."""
    params = _parameters(parameters)
    measured = np.asarray(measured, dtype=np.float64)
    if measured.ndim != 3 or measured.shape[2] != 3:
        raise ValueError("measured must have shape (samples, observed nodes, 3), not {}"
                         .format(measured.shape))
    if observed is None:
        observed = list(range(measured.shape[1]))
    values, errors, rms0, rms, iterations, converged, drift, warnings = _native.identify(
        {"scene": _scene(scene)}, params, [int(i) for i in observed], measured.ravel().tolist(),
        float(dt), int(every), int(max_iterations), float(tolerance))
    return Identification(np.asarray(values), np.asarray(errors), rms0, rms, iterations,
                          converged, float(drift), list(warnings))


@dataclass(frozen=True)
class EigenSensitivity:
    """An eigenvalue of the tangent stiffness (N/m) or a natural frequency (Hz) and its exact
    derivatives (numpy arrays; ``None`` when the value is repeated, which has none).

    Attributes
    ----------
    value : float
        The eigenvalue, or the frequency.
    multiplicity : int
        How many eigenvalues share it: 1 for a simple one, whose derivatives follow.
    force_densities, axial_stiffnesses : ndarray, shape (m,), or None
        d value / d q_k and d value / d a_k, one per member (bars then strings).
    prestress_level : float or None
        d value / d α for the force densities scaled by α at α = 1.
    nodes : ndarray, shape (n, 3), or None
        d value / d x_i at fixed force densities and axial stiffnesses (held nodes too).
    """

    value: float
    multiplicity: int
    force_densities: np.ndarray
    axial_stiffnesses: np.ndarray
    prestress_level: float
    nodes: np.ndarray


@dataclass(frozen=True)
class StiffnessSensitivity:
    """The result of :func:`stiffness_sensitivity`.

    Attributes
    ----------
    force_densities, axial_stiffnesses : ndarray, shape (m,)
        The state differentiated about: the equilibrium force densities (N/m) of the
        strings' rest lengths and stiffnesses (the bars' balancing them) and the members'
        axial stiffnesses (N/m: a string's k, a bar's E A / l).
    smallest_eigenvalue : EigenSensitivity or None
        The smallest nonzero eigenvalue of the tangent stiffness (None when every one is zero).
    frequencies : list of EigenSensitivity
        The lowest nonzero natural frequencies asked for (lumped mass).
    equilibrium_residual : float
        ‖A q − w‖ (N): how far the strings' force densities, the bars' and the loads are from
        balance.
    warnings : list of str
        A state out of balance (residual above 1e-6 of the largest force): the stiffness and
        its derivatives are then those of no equilibrium.
    """

    force_densities: np.ndarray
    axial_stiffnesses: np.ndarray
    smallest_eigenvalue: object
    frequencies: list
    equilibrium_residual: float
    warnings: list


def _eigen(t):
    value, multiplicity, dq, da, level, nodes = t
    if multiplicity != 1:
        return EigenSensitivity(float(value), int(multiplicity), None, None, None, None)
    return EigenSensitivity(float(value), int(multiplicity),
                            np.asarray(dq, dtype=np.float64), np.asarray(da, dtype=np.float64),
                            float(level), np.frombuffer(nodes, dtype=np.float64).reshape(-1, 3))


def stiffness_sensitivity(scene, *, modes=0):
    """The smallest nonzero eigenvalue of a scene's tangent stiffness and its ``modes``
    lowest nonzero natural frequencies, with their exact derivatives with respect to every
    force density, every axial stiffness, the prestress level and every node's position, about
    the equilibrium force densities of its strings (rest lengths and stiffnesses needed; bars
    need material and radius, and mass for the frequencies). ``scene`` as
    :func:`tensegrity.statics` takes it. The equations: the Rust crate
    ``tensegrity-statics``, module ``sensitivity``. Returns a :class:`StiffnessSensitivity`.
    """
    q, a, smallest, freqs, residual, warnings = _native.stiffness_sensitivity(
        {"scene": _scene(scene)}, int(modes))
    return StiffnessSensitivity(np.asarray(q, dtype=np.float64), np.asarray(a, dtype=np.float64),
                                None if smallest is None else _eigen(smallest),
                                [_eigen(f) for f in freqs], float(residual), list(warnings))


@dataclass(frozen=True)
class MarginSensitivity:
    """The result of :func:`margin_sensitivity`.

    Attributes
    ----------
    margin : float
        The prestress margin t* in [0, 1] (the statics report's ``prestress_margin``).
    smoothness : str
        ``"differentiable"``; ``"no_self_stress"`` (margin 0 nearby, zero gradient);
        ``"at_zero"`` (a self-stress, none sign-consistent); ``"tie"`` (more members at the
        margin or the bound than unknowns, typical of symmetric structures: a kink);
        ``"not_unique"`` (the slope differs across a face of optima); ``"special_geometry"``
        (the self-stress couples with a mechanism and lives only on this geometry, as a
        Snelson prism's does: no derivative at all).
    detail : dict
        The numbers behind ``smoothness``: ``at_margin``, ``at_bound``, ``unknowns`` for a
        tie, ``directions`` for not_unique, ``mechanisms`` and ``coupling`` for
        special_geometry.
    stress : ndarray, shape (m,)
        The optimal self-stress (force densities, max |q| = 1).
    at_margin, at_bound : list of int
        The members that limit the margin, and those at |q| = 1.
    nodes : ndarray, shape (n, 3), or None
        d margin / d x_i (held nodes too); None when not differentiable.
    prestress_level : float
        0: the margin does not depend on the prestress level.
    axial_stiffnesses : ndarray, shape (m,)
        Zeros: nor on the members' stiffnesses.
    """

    margin: float
    smoothness: str
    detail: dict
    stress: np.ndarray
    at_margin: list
    at_bound: list
    nodes: object
    prestress_level: float
    axial_stiffnesses: np.ndarray


_DETAIL = {"tie": ("at_margin", "at_bound", "unknowns"), "not_unique": ("directions",),
           "special_geometry": ("mechanisms", "coupling")}


def margin_sensitivity(scene):
    """The prestress margin of a scene (bars compressed, strings in tension) with its exact
    derivative with respect to every node's position where it has one, and why not where it
    has none (:class:`MarginSensitivity`); its derivatives with respect to the prestress
    level and the stiffnesses are zero. ``scene`` as :func:`tensegrity.statics` takes it.
    The equations: the Rust crate ``tensegrity-statics``, module ``sensitivity::margin``."""
    (margin, kind, numbers, stress, at_margin, at_bound, nodes, level,
     axial) = _native.margin_sensitivity({"scene": _scene(scene)})
    detail = {k: (int(v) if k != "coupling" else float(v))
              for k, v in zip(_DETAIL.get(kind, ()), numbers)}
    grad = np.frombuffer(nodes, dtype=np.float64).reshape(-1, 3)
    return MarginSensitivity(float(margin), kind, detail, np.asarray(stress, dtype=np.float64),
                             list(at_margin), list(at_bound),
                             grad if kind in ("differentiable", "no_self_stress") else None,
                             float(level), np.asarray(axial, dtype=np.float64))
