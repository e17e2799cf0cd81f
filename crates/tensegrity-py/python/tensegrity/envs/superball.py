"""``tensegrity/SuperBallRoll-v0``: the SUPERball rolls to a goal on flat ground.

* **Model**: :func:`tensegrity.envs.models.superball` (6 bars of 1.7 m and 3.5 kg, 24
  strings of 2000 N/m pretensioned to 100 N, penalty ground with friction, RK4 at 1 ms
  projected onto the bar lengths).
* **Action** ``Box(-1, 1, (24,), float32)``: each string's target rest length: 0 its
  design rest length (0.99 m), -1 its actuator's min_length (0.5 m), 1 its max_length
  (1.1 m), linear in between; the rest length moves there over the control period
  (``control_period``, default 20 ms = 20 physics steps) at up to 0.5 m/s.
* **Observation** ``Box(-inf, inf, (110,), float64)``: the 12 node positions relative to
  the nodes' centroid (36), the node velocities (36), the 24 rest lengths (24), the goal
  relative to the centroid in the ground plane (2), and the touching nodes as 0/1 (12).
* **Reward**: the decrease of the centroid's ground distance to the goal over the step
  (m), plus 10 on reaching it; ``-10`` if the physics fails (``info["error"]`` says why).
* **Termination**: the centroid within ``goal_radius`` (0.5 m) of the goal, or a failed
  physics step; truncation after 1000 steps (20 s) by the registration's time limit.
* **Reset**: a random heading (a rigid turn about the vertical) and a goal
  ``goal_distance`` (5 m) away in a random direction, both from the seed; the robot then
  settles for ``settle`` seconds (0.5 s) holding its rest lengths.
"""

import numpy as np
import gymnasium
from gymnasium import spaces

from ..errors import TensegrityError
from ..simulator import Simulator
from . import models
from .actions import targets


class SuperBallRollEnv(gymnasium.Env):
    """The SUPERball rolling to a goal (module docs)."""

    metadata = {"render_modes": []}

    def __init__(self, goal_distance=5.0, goal_radius=0.5, control_period=0.02, settle=0.5,
                 scene=None):
        self.sim = Simulator(models.superball() if scene is None else scene)
        self.n_steps = max(1, round(control_period / self.sim.dt))
        self.n_settle = round(settle / self.sim.dt)
        self.goal_distance, self.goal_radius = float(goal_distance), float(goal_radius)
        self.lo, self.hi = self.sim.min_length, self.sim.max_length
        self.rest0 = self.sim.reset().rest_lengths.copy()
        a, n = self.sim.n_actuators, self.sim.n_nodes
        self.action_space = spaces.Box(-1.0, 1.0, (a,), np.float32)
        self.observation_space = spaces.Box(-np.inf, np.inf, (6 * n + a + 2 + n,), np.float64)
        self.goal = np.zeros(2)
        self._distance = 0.0

    def _observe(self, o):
        c = o.nodes.mean(axis=0)
        rel = o.nodes - c
        goal = self.goal - c[:2]
        obs = np.concatenate([rel.ravel(), o.velocities.ravel(), o.rest_lengths, goal,
                              o.touching.astype(np.float64)])
        return obs, float(np.linalg.norm(goal))

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        heading, direction = self.np_random.uniform(0.0, 2.0 * np.pi, size=2)
        self.sim.reset(angle=float(heading))
        o = self.sim.step(None, self.n_settle) if self.n_settle > 0 else self.sim.observe()
        c = o.nodes.mean(axis=0)[:2]
        self.goal = c + self.goal_distance * np.array([np.cos(direction), np.sin(direction)])
        obs, self._distance = self._observe(o)
        return obs, {"distance": self._distance, "goal": self.goal.copy()}

    def step(self, action):
        try:
            o = self.sim.step(targets(action, self.rest0, self.lo, self.hi), self.n_steps)
        except TensegrityError as e:
            obs, _ = self._observe(self.sim.observe())
            return obs, -10.0, True, False, {"error": str(e), "distance": self._distance}
        obs, d = self._observe(o)
        reward = self._distance - d
        self._distance = d
        reached = d < self.goal_radius
        if reached:
            reward += 10.0
        info = {"distance": d, "t": o.t}
        warnings = self.sim.warnings
        if warnings:  # the run drifted past its limits: its numbers are not to be trusted
            info["warnings"] = warnings
        return obs, float(reward), bool(reached), False, info
