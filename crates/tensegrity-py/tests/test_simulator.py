"""The stepped simulation: the same trajectory as ``simulate`` of the same actuation table,
closed forms (free fall, the prestress), actuator limits, exact restores, and bad actions
named."""

import numpy as np
import pytest

import tensegrity as t
from conftest import EXAMPLES

G = 9.81


def prism(**changes):
    """The prestressed prism of examples/prism.toml on the ground of prism_drop.toml."""
    return t.Structure.from_toml(EXAMPLES / "prism_drop.toml").replace(**changes)


def test_steps_reproduce_simulate_of_the_same_actuation_table():
    s = prism()
    dt, n, periods = 1e-3, 40, 6
    r0 = np.asarray(s.rest_length)
    # strings 0 and 4 pulled in, string 7 let out, period by period
    targets = [r0[[0, 4, 7]] * np.array([1 - 0.015 * p, 1 - 0.01 * p, 1 + 0.01 * p])
               for p in range(periods + 1)]
    times = [(p * n) * dt for p in range(periods + 1)]
    table = [{"string": j, "times": times, "rest_lengths": [float(v[i]) for v in targets]}
             for i, j in enumerate((0, 4, 7))]
    ref = t.simulate(s.replace(actuation=table), integrator="rk4", dt=dt, t_end=times[-1],
                     output_interval=n * dt, convergence_check=False)
    sim = t.Simulator(s.replace(actuators=[{"strings": [0, 4, 7]}]), integrator="rk4",
                      dt=dt)
    obs = [sim.reset()]
    for p in range(1, periods + 1):
        obs.append(sim.step(targets[p], n_steps=n))
    assert np.allclose(ref["t"], [o.t for o in obs], rtol=0, atol=1e-15)
    for o, x in zip(obs, ref["trajectory"]):
        assert np.abs(o.nodes - x).max() <= 1e-12
    np.testing.assert_array_equal(obs[-1].rest_lengths, targets[-1])
    # the prism moved: the comparison is not between resting states
    assert np.abs(obs[-1].nodes - obs[0].nodes).max() > 1e-3


def test_free_fall_and_prestress_in_the_observation():
    # no ground: the prism falls freely keeping its prestressed shape
    s = prism(ground=None)
    sim = t.Simulator(s, integrator="rk4", dt=1e-3)
    o0 = sim.reset()
    o = sim.step(None, n_steps=300)
    T = 0.3
    drop = o0.nodes[:, 2].mean() - o.nodes[:, 2].mean()
    assert abs(drop - G * T * T / 2) < 1e-12
    assert np.abs(o.velocities[:, 2] + G * T).max() < 1e-12
    # the strings carry k (l − l0), the bars the matching compression
    lengths = np.linalg.norm(o.nodes[s.strings[:, 1]] - o.nodes[s.strings[:, 0]], axis=1)
    expected = np.asarray(s.stiffness) * (lengths - np.asarray(s.rest_length))
    assert np.abs(o.member_forces[3:] - expected).max() < 1e-9 * expected.max()
    assert (o.member_forces[:3] < 0).all()
    assert not o.touching.any() and not o.contact_forces.any()
    # energy: kinetic ½ M v², total conserved (no actuation, no ground; damping idle)
    assert abs(o.kinetic_energy - 0.5 * 3.0 * (G * T) ** 2) < 1e-9
    assert abs(o.energy - o0.energy) < 1e-9 * abs(o0.energy)
    assert sim.warnings == []


def test_actuator_limits_from_the_scene():
    s = prism(actuators=[{"string": 2, "min_length": 1.6, "max_rate": 0.1}])
    sim = t.Simulator(s, integrator="rk4", dt=1e-3)
    assert sim.n_actuators == 1
    assert sim.actuators[0] == t.Actuator("string", 2, 1.6, np.inf, 0.1)
    r0 = sim.reset().rest_lengths[0]
    o = sim.step([0.0], duration=0.1)            # 100 ticks at 0.1 m/s
    assert abs(o.rest_lengths[0] - (r0 - 0.01)) < 1e-12
    o = sim.step([-5.0], n_steps=1500, mode="rate")  # at the rate limit, to min_length
    assert abs(o.rest_lengths[0] - 1.6) < 1e-12


def test_a_saved_state_and_a_seeded_reset_repeat_the_run():
    sim = t.Simulator(prism(), integrator="rk4", dt=1e-3)
    sim.reset(seed=7)
    sim.step(np.asarray(sim.observe().rest_lengths) * 0.97, n_steps=80)
    state = sim.get_state()
    a = sim.step(None, n_steps=120).nodes.copy()
    sim.reset(state)
    b = sim.step(None, n_steps=120).nodes
    np.testing.assert_array_equal(a, b)
    assert state.t == pytest.approx(0.08, abs=1e-15)
    first = sim.reset(seed=7).nodes.copy()
    np.testing.assert_array_equal(first, sim.reset(seed=7).nodes)
    turned = sim.reset(angle=0.5).nodes
    # a turn about the vertical keeps heights and the distances to the centroid
    assert np.abs(np.sort(turned[:, 2]) - np.sort(prism().nodes[:, 2])).max() < 1e-12


def test_bad_actions_are_named():
    sim = t.Simulator(prism(), integrator="rk4", dt=1e-3)
    sim.reset()
    with pytest.raises(t.InputError, match="expected 9 entries, got 2"):
        sim.step([1.0, 2.0])
    with pytest.raises(t.InputError, match="actuator 3"):
        sim.step([1.7, 1.7, 1.7, np.nan, 1.7, 1.7, 1.7, 1.7, 1.7])
    with pytest.raises(ValueError, match="mode"):
        sim.step(np.ones(9), mode="torque")
    with pytest.raises(ValueError, match="n_steps = 0"):
        sim.step(None, n_steps=0)
    with pytest.raises(ValueError, match="not a whole number of ticks"):
        sim.step(None, duration=0.0015)
    assert sim.t == 0.0
    with pytest.raises(t.InputError, match="actuators 0: string 40 does not exist"):
        t.Simulator(prism(actuators=[{"string": 40}]))
    with pytest.raises(t.InputError, match="elastic"):
        t.Simulator(prism(simulation={"t_end": 1.0, "bars": "elastic"}))
