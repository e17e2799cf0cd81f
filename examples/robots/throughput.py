"""Throughput of the SUPERball environment (tensegrity/SuperBallRoll-v0): environment steps
and physics steps (1 ms RK4, projected) per second, single-threaded and through a vectorised
environment on every core. A measurement, not a test.

    python examples/robots/throughput.py [--seconds S] [--envs N]

Prints one JSON line per configuration (the machine's core count, the environment steps
taken, the wall time, the rates). Random actions from a seeded generator; episodes that end
are reset by the vectorised environment's autoreset.
"""

import argparse
import json
import os
import time

import gymnasium
import numpy as np

import tensegrity.envs  # noqa: F401  (registers the ids)

ID = "tensegrity/SuperBallRoll-v0"


def single(seconds):
    env = gymnasium.make(ID)
    rng = np.random.default_rng(0)
    env.reset(seed=0)
    physics = env.unwrapped.n_steps
    n, t0 = 0, time.perf_counter()
    while time.perf_counter() - t0 < seconds:
        _, _, term, trunc, _ = env.step(rng.uniform(-1, 1, 24).astype(np.float32))
        n += 1
        if term or trunc:
            env.reset()
    wall = time.perf_counter() - t0
    return {"mode": "single", "envs": 1, "env_steps": n, "wall_s": wall,
            "env_steps_per_s": n / wall, "physics_steps_per_s": n * physics / wall}


def vectorised(seconds, num_envs, mode):
    envs = gymnasium.make_vec(ID, num_envs=num_envs, vectorization_mode=mode)
    rng = np.random.default_rng(0)
    envs.reset(seed=list(range(num_envs)))
    physics = 20
    n, t0 = 0, time.perf_counter()
    while time.perf_counter() - t0 < seconds:
        envs.step(rng.uniform(-1, 1, (num_envs, 24)).astype(np.float32))
        n += num_envs
    wall = time.perf_counter() - t0
    envs.close()
    return {"mode": mode, "envs": num_envs, "env_steps": n, "wall_s": wall,
            "env_steps_per_s": n / wall, "physics_steps_per_s": n * physics / wall}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--seconds", type=float, default=5.0)
    p.add_argument("--envs", type=int, default=os.cpu_count())
    a = p.parse_args()
    cores = os.cpu_count()
    for row in (single(a.seconds), vectorised(a.seconds, a.envs, "async")):
        row["cores"] = cores
        print(json.dumps(row))


if __name__ == "__main__":
    main()
