"""Gymnasium environments of tensegrity robots (``pip install gymnasium``), stepped by
:class:`tensegrity.Simulator`.

Registered ids (``gymnasium.make(id)`` after ``import tensegrity.envs``):

* ``tensegrity/SuperBallRoll-v0`` (:class:`~tensegrity.envs.superball.SuperBallRollEnv`):
  the 6-bar SUPERball rolls to a goal on flat ground with its 24 string actuators;
* ``tensegrity/ToroidWheel-v0`` (:class:`~tensegrity.envs.wheel.ToroidWheelEnv`): the
  thesis's toroid wheel keeps rolling forward without tipping over, steering with its 128
  strings.

Both are deterministic given the seed of ``reset``; vectorise them with
``gymnasium.make_vec(id, num_envs=n, vectorization_mode="async")`` (one process per
environment: all cores) or ``"sync"``.
"""

import gymnasium

from .superball import SuperBallRollEnv
from .wheel import ToroidWheelEnv

__all__ = ["SuperBallRollEnv", "ToroidWheelEnv"]

for _id, _entry, _steps in (
        ("tensegrity/SuperBallRoll-v0", "tensegrity.envs.superball:SuperBallRollEnv", 1000),
        ("tensegrity/ToroidWheel-v0", "tensegrity.envs.wheel:ToroidWheelEnv", 500)):
    if _id not in gymnasium.registry:
        gymnasium.register(id=_id, entry_point=_entry, max_episode_steps=_steps)
