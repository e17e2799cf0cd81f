"""The Gymnasium environments: the environment checker, determinism, a vectorised
environment, the action mapping, and a scripted controller (no learning) that rolls the
SUPERball more than a body length toward its goal."""

import itertools

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")
from gymnasium.utils.env_checker import check_env  # noqa: E402

import tensegrity as t  # noqa: E402
import tensegrity.envs  # noqa: E402,F401
from tensegrity.envs import models  # noqa: E402
from conftest import EXAMPLES  # noqa: E402

IDS = ["tensegrity/SuperBallRoll-v0", "tensegrity/ToroidWheel-v0"]


@pytest.mark.parametrize("env_id", IDS)
def test_the_environment_checker_passes(env_id):
    env = gymnasium.make(env_id)
    check_env(env.unwrapped, skip_render_check=True)
    obs, _ = env.reset(seed=3)
    assert env.observation_space.contains(obs)
    obs2, _ = env.reset(seed=3)
    np.testing.assert_array_equal(obs, obs2)


def test_the_superball_scene_is_the_example_and_the_layout():
    s = models.superball()
    # the example file is this model's TOML (to the last bits, which numpy's trigonometry
    # and BLAS may set differently on another CPU)
    ex = t.Structure.from_toml(EXAMPLES / "robots" / "superball.toml")
    np.testing.assert_allclose(ex.nodes, s.nodes, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(ex.strings, s.strings)
    # the expanded octahedron: bars 1.7 m, 24 strings sqrt(6)/4 of a bar, 4 per node
    bars = np.linalg.norm(s.nodes[s.bars[:, 1]] - s.nodes[s.bars[:, 0]], axis=1)
    strings = np.linalg.norm(s.nodes[s.strings[:, 1]] - s.nodes[s.strings[:, 0]], axis=1)
    assert np.abs(bars - 1.7).max() < 1e-12
    assert len(strings) == 24 and np.abs(strings - 1.7 * np.sqrt(6) / 4).max() < 1e-12
    assert np.bincount(s.strings.ravel()).tolist() == [4] * 12
    # resting on a string triangle at z = 0
    assert sorted(np.flatnonzero(s.nodes[:, 2] < 1e-12).tolist()) == [0, 4, 8]
    # its one self-stress: bar : string force densities -3/2 : 1
    r = t.statics(s.replace(gravity=None, ground=None, simulation=None, actuators=None))
    assert r["self_stress_dim"] == 1 and r["prestress_stable"]
    q = r["self_stress"][0]
    assert np.abs(q[:6] / q[6:].mean() + 1.5).max() < 1e-9
    assert np.abs(q[6:] / q[6] - 1.0).max() < 1e-9


def test_a_vectorised_environment_steps_every_copy():
    envs = gymnasium.make_vec(IDS[0], num_envs=2, vectorization_mode="sync")
    obs, _ = envs.reset(seed=[1, 2])
    assert obs.shape == (2, 110)
    assert not np.array_equal(obs[0], obs[1])  # their own headings and goals
    obs, reward, term, trunc, info = envs.step(np.zeros((2, 24), np.float32))
    assert obs.shape == (2, 110) and reward.shape == (2,)
    envs.close()


def test_a_zero_action_holds_the_design_rest_lengths():
    env = gymnasium.make(IDS[0]).unwrapped
    obs, _ = env.reset(seed=0)
    rest = obs[72:96]
    assert np.abs(rest - env.rest0).max() == 0.0
    obs, _, _, _, info = env.step(-np.ones(24, np.float32))
    # 20 ms at 0.5 m/s toward 0.5 m: 0.01 m shorter
    assert np.abs(obs[72:96] - (env.rest0 - 0.01)).max() < 1e-12
    assert "warnings" not in info  # the projected RK4 run keeps its bar lengths


def test_a_scripted_controller_rolls_the_superball_a_body_length():
    """Greedy: from the current state, try pulling in every string and every pair of strings
    for 0.6 s (then 0.6 s back to the design) on copies of the state, and do the one that
    moves the centroid furthest toward the goal."""
    sim = t.Simulator(models.superball())
    o = sim.reset()
    o = sim.step(None, 1000)
    r0 = o.rest_lengths.copy()
    goal = np.array([1.0, 0.0])
    start = o.nodes.mean(axis=0)[:2]

    def progress(o):
        return float((o.nodes.mean(axis=0)[:2] - start) @ goal)

    moves = [(i,) for i in range(24)] + list(itertools.combinations(range(24), 2))
    for _ in range(4):
        state, base = sim.get_state(), progress(sim.observe())
        gains = []
        for m in moves:
            sim.set_state(state)
            a = r0.copy()
            a[list(m)] = 0.5
            sim.step(a, 600, observe=False)
            gains.append(progress(sim.step(r0, 600)) - base)
        best = moves[int(np.argmax(gains))]
        sim.set_state(state)
        a = r0.copy()
        a[list(best)] = 0.5
        sim.step(a, 600, observe=False)
        o = sim.step(r0, 600)
    assert progress(o) > 1.7, progress(o)
    assert sim.warnings == []
