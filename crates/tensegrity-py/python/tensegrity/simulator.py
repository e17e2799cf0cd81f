"""A simulation you step and steer: :class:`Simulator`.

The scene is read and its run set up exactly as :func:`tensegrity.simulate` does (the same
scene sources and overrides); a controller then advances it one control period at a time,
setting the rest lengths of its actuators (the scene's ``[[actuators]]``, by default every
string then every cluster), and reads the state as numpy arrays (:class:`Observation`).
A stepped run and :func:`tensegrity.simulate` of the same scene with the same rest lengths
as an ``[[actuation]]`` table give the same trajectory (bit for bit under fixed-step
integrators).
"""

from dataclasses import dataclass

import numpy as np

from . import _native

_MODES = {"rest_length": "rest_lengths", "rest_lengths": "rest_lengths",
          "rate": "rates", "rates": "rates"}


@dataclass(frozen=True)
class Observation:
    """The state of a :class:`Simulator` at time ``t`` (read-only numpy arrays).

    Attributes
    ----------
    t : float
        Time (s).
    nodes, velocities : ndarray, shape (n, 3)
        Node positions (m) and velocities (m/s), in the scene's numbering.
    member_forces : ndarray, shape (m,)
        Axial forces (N, tension positive): bars, strings, then clusters.
    contact_forces : ndarray, shape (n, 3)
        The ground's force on each node (N; zero off the ground).
    touching : ndarray of bool, shape (n,)
        The nodes the ground pushes.
    rest_lengths : ndarray, shape (a,)
        The actuators' rest lengths (m).
    kinetic_energy, energy : float
        Kinetic and total energy (J; the strings' potential at their current rest lengths).
    """

    t: float
    nodes: np.ndarray
    velocities: np.ndarray
    member_forces: np.ndarray
    contact_forces: np.ndarray
    touching: np.ndarray
    rest_lengths: np.ndarray
    kinetic_energy: float
    energy: float


@dataclass(frozen=True)
class Actuator:
    """One actuator: the rest length of a ``"string"`` or ``"cluster"`` and its limits
    (m, m, m/s; ``inf`` where unlimited)."""

    kind: str
    index: int
    min_length: float
    max_length: float
    max_rate: float


class Simulator:
    """A rigid-bar simulation advanced one control period at a time.

    Parameters
    ----------
    scene : str, os.PathLike or Structure
        The scene, as :func:`tensegrity.simulate` takes it (its ``[simulation]``,
        ``[ground]``, ``[[actuation]]`` and ``[[actuators]]`` tables are read).
    integrator, dt, rtol, atol : optional
        Overrides, as in :func:`tensegrity.simulate`. ``dt`` is the control tick: a call of
        :meth:`step` lasts ``n_steps * dt`` seconds (default: the scene's, else the
        integrator's default step; adaptive integrators 0.01 s, their largest step).

    Examples
    --------
    >>> sim = Simulator("examples/prism_drop.toml")             # doctest: +SKIP
    >>> obs = sim.reset()
    >>> obs = sim.step(obs.rest_lengths * 0.95, n_steps=100)    # pull every string 5 %
    """

    def __init__(self, scene, *, integrator=None, dt=None, rtol=None, atol=None):
        values = {"scene": scene, "integrator": integrator, "dt": dt, "rtol": rtol,
                  "atol": atol}
        self._native = _native.Stepper({k: v for k, v in values.items() if v is not None})
        self.n_nodes = self._native.n_nodes
        self.actuators = tuple(Actuator(*a) for a in self._native.actuators)
        self.n_actuators = len(self.actuators)
        limits = np.array([[a.min_length, a.max_length, a.max_rate] for a in self.actuators],
                          dtype=np.float64).reshape(-1, 3)
        self.min_length, self.max_length, self.max_rate = (limits[:, 0].copy(),
                                                           limits[:, 1].copy(),
                                                           limits[:, 2].copy())
        self._n_members = None

    @property
    def t(self):
        """Time (s)."""
        return self._native.t

    @property
    def dt(self):
        """The control tick (s)."""
        return self._native.dt

    @property
    def warnings(self):
        """The drifts past their limits since the last reset (as ``simulate`` reports them;
        energy is judged only while no actuator has moved)."""
        return list(self._native.warnings)

    @property
    def stats(self):
        """``(steps, rejected_steps, rhs_evals)`` since the last reset."""
        return self._native.stats

    def reset(self, state=None, *, seed=None, angle=None):
        """Back to the start and the observation there.

        ``state`` (from :meth:`get_state`) restores that state instead; ``angle`` (rad) turns
        the initial state about the vertical through its centroid (a rigid motion: a robot
        at rest on level ground stays at rest); ``seed`` draws that angle uniformly in
        [0, 2π) from ``numpy.random.default_rng(seed)``.
        """
        if state is not None:
            self._native.set_state(state)
            return self.observe()
        if seed is not None and angle is None:
            angle = float(np.random.default_rng(seed).uniform(0.0, 2.0 * np.pi))
        self._native.reset(None if angle is None else float(angle))
        return self.observe()

    def step(self, action=None, n_steps=None, *, duration=None, mode="rest_length",
             observe=True):
        """Advances ``n_steps`` ticks of ``dt`` (default 1), or ``duration`` seconds (a whole
        number of ticks), and returns the observation (``None`` with ``observe=False``).

        ``action``: one value per actuator, the rest lengths (m) to reach at the end of the
        period (``mode="rest_length"``) or their rates (m/s, ``mode="rate"``); the rest
        length moves linearly over the period within the actuator's limits (a target is
        clamped to [min_length, max_length], then the change to max_rate × period; a rate
        to ±max_rate). ``None`` holds every rest length.
        """
        if duration is not None:
            if n_steps is not None:
                raise TypeError("step(): give n_steps or duration, not both")
            ticks = float(duration) / self.dt
            n_steps = round(ticks)
            if not abs(ticks - n_steps) <= 1e-9 * max(1.0, ticks):
                raise ValueError(f"duration = {duration}: not a whole number of ticks of "
                                 f"dt = {self.dt}")
        n_steps = 1 if n_steps is None else int(n_steps)
        if n_steps < 1:
            raise ValueError(f"n_steps = {n_steps}: must be at least 1")
        if action is None:
            self._native.step("hold", [], n_steps)
        else:
            kind = _MODES.get(mode)
            if kind is None:
                raise ValueError(f"mode: {mode!r} is not 'rest_length' or 'rate'")
            values = np.asarray(action, dtype=np.float64).reshape(-1).tolist()
            self._native.step(kind, values, n_steps)
        return self.observe() if observe else None

    def observe(self):
        """The :class:`Observation` now."""
        raw = np.frombuffer(self._native.observe(), dtype=np.float64)
        n, a = self.n_nodes, self.n_actuators
        m = raw.size - 9 * n - a - 2
        nodes = raw[: 3 * n].reshape(n, 3)
        velocities = raw[3 * n: 6 * n].reshape(n, 3)
        forces = raw[6 * n: 6 * n + m]
        contact = raw[6 * n + m: 9 * n + m].reshape(n, 3)
        rest = raw[9 * n + m: 9 * n + m + a]
        touching = np.any(contact != 0.0, axis=1)
        return Observation(self.t, nodes, velocities, forces, contact, touching, rest,
                           float(raw[-2]), float(raw[-1]))

    def nodes(self):
        """The node positions (n, 3) alone: the cheapest observation."""
        return np.frombuffer(self._native.nodes(), dtype=np.float64).reshape(self.n_nodes, 3)

    def get_state(self):
        """The state now (opaque; its ``t`` and ``rest_lengths`` readable), for
        :meth:`set_state` or ``reset(state)``."""
        return self._native.get_state()

    def set_state(self, state):
        """Restores a state from :meth:`get_state` (fixed-step integrators then go on bit
        for bit as from the original)."""
        self._native.set_state(state)
