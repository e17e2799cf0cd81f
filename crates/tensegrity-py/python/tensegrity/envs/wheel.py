"""``tensegrity/ToroidWheel-v0``: the thesis's toroid wheel keeps rolling without tipping.

* **Model**: :func:`tensegrity.envs.models.toroid_wheel` (``tensegrity toroid``'s default
  wheel, radius 1 m, 25 bars, 128 strings of 10⁴ N/m, on a penalty ground with friction,
  rolling at 1 m/s along +y at the start; RK4 at 1 ms projected onto the bar lengths).
* **Action** ``Box(-1, 1, (128,), float32)``: each string's rest length within ±10 % of its
  design value (-1: 10 % shorter, 1: 10 % longer), reached over the control period (20 ms)
  at up to 0.5 m/s.
* **Observation** ``Box(-inf, inf, (380,), float64)``: the 42 node positions relative to
  their centroid (126), the node velocities (126), the 128 rest lengths (relative to their
  design values, minus 1).
* **Reward**: the centroid's progress along +y over the step (m).
* **Termination**: the wheel tipped (its axle, the direction of least spread of its nodes,
  more than ``max_tilt`` = 45° from the ground plane) or a failed physics step (reward
  ``-1``, ``info["error"]``); truncation after 500 steps (10 s).
* **Reset**: the rolling start, turned about the vertical by a random heading of at most
  ``heading_noise`` (0.1 rad) from the seed.
"""

import numpy as np
import gymnasium
from gymnasium import spaces

from ..errors import TensegrityError
from ..simulator import Simulator
from . import models
from .actions import targets


def tilt(nodes):
    """The angle (rad) of the wheel's axle above the ground plane: its axle is the
    direction in which its nodes spread least."""
    _, _, vt = np.linalg.svd(nodes - nodes.mean(axis=0), full_matrices=False)
    return float(np.arcsin(min(1.0, abs(vt[-1][2]))))


class ToroidWheelEnv(gymnasium.Env):
    """The toroid wheel rolling forward (module docs)."""

    metadata = {"render_modes": []}

    def __init__(self, control_period=0.02, max_tilt=np.pi / 4, heading_noise=0.1,
                 scene=None):
        self.sim = Simulator(models.toroid_wheel() if scene is None else scene)
        self.n_steps = max(1, round(control_period / self.sim.dt))
        self.max_tilt, self.heading_noise = float(max_tilt), float(heading_noise)
        self.rest0 = self.sim.reset().rest_lengths.copy()
        a, n = self.sim.n_actuators, self.sim.n_nodes
        self.action_space = spaces.Box(-1.0, 1.0, (a,), np.float32)
        self.observation_space = spaces.Box(-np.inf, np.inf, (6 * n + a,), np.float64)
        self.lo, self.hi = self.sim.min_length, self.sim.max_length
        self._y = 0.0

    def _observe(self, o):
        c = o.nodes.mean(axis=0)
        obs = np.concatenate([(o.nodes - c).ravel(), o.velocities.ravel(),
                              o.rest_lengths / self.rest0 - 1.0])
        return obs, float(c[1])

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        heading = self.np_random.uniform(-self.heading_noise, self.heading_noise)
        o = self.sim.reset(angle=float(heading))
        obs, self._y = self._observe(o)
        return obs, {"tilt": tilt(o.nodes)}

    def step(self, action):
        try:
            o = self.sim.step(targets(action, self.rest0, self.lo, self.hi), self.n_steps)
        except TensegrityError as e:
            obs, _ = self._observe(self.sim.observe())
            return obs, -1.0, True, False, {"error": str(e)}
        obs, y = self._observe(o)
        reward, self._y = y - self._y, y
        angle = tilt(o.nodes)
        info = {"tilt": angle, "t": o.t}
        warnings = self.sim.warnings
        if warnings:  # the run drifted past its limits: its numbers are not to be trusted
            info["warnings"] = warnings
        return obs, float(reward), bool(angle > self.max_tilt), False, info
