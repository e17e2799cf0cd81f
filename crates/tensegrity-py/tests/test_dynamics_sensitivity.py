"""Sensitivities of the dynamics and system identification in Python (issue 47, items 4 to
6): :func:`tensegrity.trajectory_sensitivity` against central differences of whole runs (a
bar hung from two anchors by two strings, swinging under gravity: every kind of parameter)
and :func:`tensegrity.identify` recovering the two strings' stiffnesses and dampings from the
scene's own motion; the bar-length drift of the unprojected steps, small at 1 ms and reported
with a warning at 20 ms; bad input refused."""

import numpy as np
import pytest

import tensegrity
from tensegrity import identify, trajectory_sensitivity

SCENE = """
nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [-0.3, 0.2, 1.0], [1.2, -0.1, 1.1]]
velocities = [[0.0, 0.3, 0.1], [0.0, 0.3, 0.1], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
[[bars]]
nodes = [0, 1]
mass = {mass}
[[strings]]
nodes = [0, 2]
stiffness = {k0}
rest_length = 0.8
damping = {c0}
[[strings]]
nodes = [1, 3]
stiffness = 500.0
rest_length = 0.9
damping = 1.5
[[supports]]
node = 2
[[supports]]
node = 3
[gravity]
acceleration = [0.0, 0.0, -9.81]
"""

BASE = {"mass": 2.0, "k0": 800.0, "c0": 1.0}


def scene(**moved):
    values = dict(BASE)
    values.update(moved)
    return SCENE.format(**{k: repr(float(v)) for k, v in values.items()})


def final(text):
    return trajectory_sensitivity(text, [], dt=1e-3, t_end=0.3).nodes[-1]


@pytest.mark.parametrize("key,parameter", [("k0", ("stiffness", 0)), ("c0", ("damping", 0)),
                                           ("mass", ("mass", 0))])
def test_sensitivities_match_central_differences(key, parameter):
    s = trajectory_sensitivity(scene(), [parameter], dt=1e-3, t_end=0.3)
    assert s.nodes.shape == (301, 4, 3) and s.sensitivities.shape == (301, 1, 4, 3)
    h = 1e-4 * BASE[key]
    fd = (final(scene(**{key: BASE[key] + h})) - final(scene(**{key: BASE[key] - h}))) / (2 * h)
    exact = s.sensitivities[-1, 0]
    assert np.abs(exact - fd).max() <= 1e-6 * np.abs(fd).max(), (exact, fd)
    # the anchors do not move
    assert np.all(exact[2:] == 0.0)
    # 1 ms steps keep the bar's length inside simulate's limit of 1e-6
    assert s.bar_length_drift < 1e-6 and s.warnings == []


def test_a_coarse_step_reports_its_bar_length_drift():
    s = trajectory_sensitivity(scene(), [("stiffness", 0)], dt=2e-2, t_end=0.4)
    length = np.linalg.norm(s.nodes[:, 1] - s.nodes[:, 0], axis=1)
    sampled = np.abs(length - length[0]).max() / length[0]
    assert s.bar_length_drift >= sampled > 1e-6
    assert len(s.warnings) == 1 and "bar lengths drifted" in s.warnings[0]


def test_the_initial_velocity_moves_the_whole_bar():
    s = trajectory_sensitivity(scene(), [("initial_velocity", 0, 1)], dt=1e-3, t_end=0.2)
    # at the start a velocity moves nothing; then the bar drifts along y by about t
    assert np.all(s.sensitivities[0] == 0.0)
    assert 0.0 < s.sensitivities[-1, 0, 0, 1] < 0.2


def test_identify_recovers_the_stiffnesses_and_dampings():
    truth = trajectory_sensitivity(scene(), [], dt=1e-3, t_end=0.4, every=4)
    start = scene(k0=700.0, c0=1.3)
    params = [("stiffness", 0), ("damping", 0), ("stiffness", 1), ("damping", 1)]
    id = identify(start.replace("stiffness = 500.0", "stiffness = 560.0"), params,
                  truth.nodes[:, :2], dt=1e-3, every=4, observed=[0, 1])
    assert id.converged and id.rms < 1e-9 < id.rms_start
    assert id.bar_length_drift < 1e-6 and id.warnings == []
    assert np.allclose(id.values, [800.0, 1.0, 500.0, 1.5], rtol=1e-6)


def test_bad_parameters_are_refused():
    with pytest.raises(tensegrity.TensegrityError, match="spring"):
        trajectory_sensitivity(scene(), [("spring", 0)], dt=1e-3, t_end=0.01)
    with pytest.raises(tensegrity.TensegrityError, match="string 7"):
        trajectory_sensitivity(scene(), [("stiffness", 7)], dt=1e-3, t_end=0.01)
    with pytest.raises(ValueError, match="shape"):
        identify(scene(), [("stiffness", 0)], np.zeros((5, 3)), dt=1e-3)
