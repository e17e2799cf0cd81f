"""The action mapping the environments share: a normalised action in [-1, 1] per actuator
onto its target rest length, 0 the design rest length ``rest0``, -1 the actuator's
``min_length``, 1 its ``max_length``, linear in between."""

import numpy as np


def targets(action, rest0, lo, hi):
    """The target rest lengths (m) of ``action`` (clipped to [-1, 1])."""
    a = np.clip(np.asarray(action, dtype=np.float64), -1.0, 1.0)
    return np.where(a < 0.0, rest0 + a * (rest0 - lo), rest0 + a * (hi - rest0))
