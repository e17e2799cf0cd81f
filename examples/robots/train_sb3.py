"""Training a policy for the SUPERball environment with Stable-Baselines3 (PPO): an example,
not run in CI (it takes hours on a laptop; `pip install stable-baselines3 gymnasium`).

    python examples/robots/train_sb3.py --timesteps 2000000 --envs 8 --out superball_ppo

Eight environments step in their own processes (all cores); the policy is saved to --out and
evaluated for five episodes (mean distance to the goal at the end, and how many reached it).
"""

import argparse

import gymnasium
import numpy as np

import tensegrity.envs  # noqa: F401  (registers the ids)

ID = "tensegrity/SuperBallRoll-v0"


def main():
    from stable_baselines3 import PPO
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.vec_env import SubprocVecEnv

    p = argparse.ArgumentParser()
    p.add_argument("--timesteps", type=int, default=2_000_000)
    p.add_argument("--envs", type=int, default=8)
    p.add_argument("--out", default="superball_ppo")
    a = p.parse_args()
    venv = make_vec_env(ID, n_envs=a.envs, seed=0, vec_env_cls=SubprocVecEnv)
    model = PPO("MlpPolicy", venv, n_steps=512, batch_size=2048, gamma=0.995,
                learning_rate=3e-4, verbose=1, seed=0)
    model.learn(total_timesteps=a.timesteps)
    model.save(a.out)
    env = gymnasium.make(ID)
    reached, final = 0, []
    for episode in range(5):
        obs, info = env.reset(seed=1000 + episode)
        done = False
        while not done:
            action, _ = model.predict(obs, deterministic=True)
            obs, _, term, trunc, info = env.step(action)
            done = term or trunc
        reached += bool(term and "error" not in info)
        final.append(info["distance"])
    print(f"reached the goal in {reached}/5 episodes; final distances {np.round(final, 2)}")


if __name__ == "__main__":
    main()
