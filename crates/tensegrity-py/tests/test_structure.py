"""The structure model from numpy: a Snelson prism built from arrays has the closed-form
self-stress, falls as a trajectory of shape (samples, nodes, 3), round-trips through scene
TOML, and has the connectivity and equilibrium matrices of its definition."""

import numpy as np
import pytest

import tensegrity as tg
from conftest import EXAMPLES

SQ3 = np.sqrt(3.0)


def snelson(height=1.0, **kwargs):
    """The Snelson 3-bar prism of unit radius: bottom node i at 120i deg, top node i at
    120i + 30 deg (the equilibrium twist pi/2 - pi/3), bars bottom i -> top i+1, strings the
    two triangles and the verticals bottom i -> top i."""
    a = np.radians(120.0 * np.arange(3))
    bottom = np.c_[np.cos(a), np.sin(a), np.zeros(3)]
    top = np.c_[np.cos(a + np.pi / 6), np.sin(a + np.pi / 6), np.full(3, height)]
    nodes = np.vstack([bottom, top])
    bars = np.array([[0, 4], [1, 5], [2, 3]])
    strings = np.array([[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3], [0, 3], [1, 4], [2, 5]])
    return tg.Structure(nodes, bars, strings, **kwargs)


def closed_form_self_stress():
    """Equilibrium of node 0 (1, 0, 0): ring strings to (-1/2, ±√3/2, 0) pull
    q_r (-3, 0, 0), the vertical string to (√3/2, 1/2, 1) q_v (√3/2 - 1, 1/2, 1), the bar to
    (-√3/2, 1/2, 1) q_b (-√3/2 - 1, 1/2, 1). z: q_v + q_b = 0; x: -3 q_r + √3 q_v = 0. So
    q_ring : q_vertical : q_bar = 1 : √3 : -√3 (bars first, then strings in order)."""
    q = np.array([-SQ3] * 3 + [1.0] * 6 + [SQ3] * 3)
    return q / np.linalg.norm(q)


def test_statics_of_the_numpy_prism_is_the_closed_form_self_stress():
    r = tg.statics(snelson())
    assert r["self_stress_dim"] == 1 and r["prestressable"]
    s = r["self_stress"]
    assert s.shape == (1, 12)
    q = closed_form_self_stress()
    s = s[0] * np.sign(s[0] @ q)
    np.testing.assert_allclose(s, q, atol=1e-12)
    # the max-margin prestress with max|q| = 1: bars -1, verticals 1, rings 1/√3
    np.testing.assert_allclose(r["prestress"], q / np.abs(q).max(), atol=1e-9)
    assert r["prestress_margin"] == pytest.approx(1 / SQ3, abs=1e-9)
    assert r["rank"] == 11 and r["internal_mechanisms"] == 1


def test_the_closed_form_holds_at_any_height():
    # the force densities of the twisted prism do not depend on its height
    r = tg.statics(snelson(height=2.5))
    s = r["self_stress"][0]
    q = closed_form_self_stress()
    np.testing.assert_allclose(s * np.sign(s @ q), q, atol=1e-12)


def dropped(t_end=0.2, interval=0.01):
    length = np.array([np.sqrt(3.0)] * 6 + [np.sqrt(2 - SQ3 + 1)] * 3)
    return snelson(
        bar_mass=1.0, stiffness=1000.0, rest_length=0.95 * length, damping=2.0,
        gravity=[0, 0, -9.81],
        ground={"point": [0.0, 0.0, -0.5], "normal": [0.0, 0.0, 1.0], "model": "penalty",
                "stiffness": 1e4, "damping": 100.0},
        simulation={"t_end": t_end, "integrator": "rk45", "rtol": 1e-8, "atol": 1e-10,
                    "output_interval": interval})


def test_simulate_returns_the_trajectory_as_samples_by_nodes_by_3():
    r = tg.simulate(dropped())
    t, x = r["t"], r["trajectory"]
    assert x.shape == (len(t), 6, 3) and len(t) == 21
    np.testing.assert_allclose(t, np.linspace(0, 0.2, 21), atol=1e-12)
    np.testing.assert_allclose(x[0], snelson().nodes, atol=1e-15)
    np.testing.assert_allclose(x[-1], r["final_nodes"], atol=1e-12)
    # before the ground (0.5 m below) is reached the prism falls freely: its centre by g t²/2
    centre = x.mean(axis=1)[:, 2] - x[0].mean(axis=0)[2]
    early = t <= 0.1
    np.testing.assert_allclose(centre[early], -0.5 * 9.81 * t[early] ** 2, atol=1e-6)


def test_toml_round_trip_is_exact():
    s = dropped()
    back = tg.Structure.from_toml(s.to_toml())
    assert back == s and back.to_toml() == s.to_toml()
    np.testing.assert_array_equal(back.nodes, s.nodes)
    np.testing.assert_array_equal(back.rest_length, s.rest_length)
    assert back.tables["ground"]["model"] == "penalty"
    f = tg.Structure.from_toml(EXAMPLES / "prism.toml")
    assert (f.n_nodes, f.n_bars, f.n_strings) == (6, 3, 9)
    assert f.bar_material == ["steel_rod"] * 3 and "steel_rod" in f.materials
    assert tg.Structure.from_toml(f.to_toml()) == f


def test_connectivity_and_equilibrium_matrices():
    s = snelson(supports={0: "xyz", 1: "z"})
    cb, cs = s.C_b, s.C_s
    assert cb.shape == (3, 6) and cs.shape == (9, 6)
    for c, members in ((cb, s.bars), (cs, s.strings)):
        for k, (i, j) in enumerate(members):
            row = np.zeros(6)
            row[i], row[j] = -1.0, 1.0
            np.testing.assert_array_equal(c[k], row)
    # column k of A: -(n_j - n_i) at node i, +(n_j - n_i) at node j (free dofs only)
    c = np.vstack([cb, cs])
    a_full = np.einsum("kn,kd->ndk", c, c @ s.nodes).reshape(18, 12)
    free = [3 * n + d for n, d in s.free_dofs]
    assert len(free) == 18 - 4
    np.testing.assert_allclose(s.equilibrium_matrix, a_full[free], atol=1e-15)
    row, col, val, shape = s.sparse("equilibrium_matrix")
    dense = np.zeros(shape)
    dense[row, col] = val
    np.testing.assert_array_equal(dense, s.equilibrium_matrix)
    assert len(val) == np.count_nonzero(s.equilibrium_matrix)
    r, c2, v, sh = s.sparse("C_b")
    assert sh == (3, 6) and sorted(v.tolist()) == [-1.0] * 3 + [1.0] * 3


def test_topologies_as_structures():
    t = tg.Structure.toroid(sides=6)
    report = tg.toroid(sides=6)
    assert (t.n_nodes, t.n_bars, t.n_strings) == (report["nodes"], report["bars"], report["strings"])
    assert tg.statics(t)["rank"] == report["rank"]
    m = tg.Structure.michell(complexity=2, planar=True, beta="pi/6", phi="pi/8")
    assert m.n_bars == len(tg.michell(complexity=2, planar=True, beta="pi/6", phi="pi/8")["members"])
    b = tg.Structure.tbar(beta="pi/6", phi="pi/8", cylindrical=0.25)
    assert b.n_nodes > 0 and b.n_bars > 0


def test_replace_makes_a_changed_copy():
    s = snelson(stiffness=100.0)
    t = s.replace(stiffness=200.0)
    assert t.stiffness[0] == 200.0 and s.stiffness[0] == 100.0
    with pytest.raises(ValueError):
        s.nodes[0, 0] = 5.0  # read-only arrays
