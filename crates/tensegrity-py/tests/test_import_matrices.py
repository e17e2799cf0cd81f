"""``Structure.from_matrices``: MOTES's D-bar from its matrices is the anchor scene
(examples/anchors/motes_dbar.toml): the same statics and the same trajectory as the CLI on
the anchor file, and bad matrices are refused naming the row."""

import numpy as np
import pytest

import tensegrity as tg


def dbar():
    N = np.array([[-1.0, 0.0, 1.0, 0.0], [0.0, -1.0, 0.0, 1.0], [0.0, 0.0, 0.0, 0.0]])
    C_b = np.zeros((4, 4))
    for k, (i, j) in enumerate([(3, 0), (0, 1), (1, 2), (2, 3)]):
        C_b[k, i], C_b[k, j] = -1.0, 1.0
    C_s = np.zeros((2, 4))
    for k, (i, j) in enumerate([(1, 3), (0, 2)]):
        C_s[k, i], C_s[k, j] = -1.0, 1.0
    return tg.Structure.from_matrices(N, C_b, C_s, bar_mass=[1.0] * 4, stiffness=[100.0] * 2,
                                      rest_length=[1.0, 0.5], pinned=[0])


def test_the_dbar_from_its_matrices_is_the_anchor(cli_json):
    from conftest import EXAMPLES
    s = dbar()
    assert (s.n_nodes, s.n_bars, s.n_strings) == (4, 4, 2)
    anchor = EXAMPLES / "anchors" / "motes_dbar.toml"
    ours = tg.statics(s)
    theirs = cli_json("statics", anchor)
    for key in ("rank", "mechanisms", "self_stress_dim", "prestress"):
        assert np.array_equal(np.asarray(ours[key]), np.asarray(theirs[key])), key
    r = tg.simulate(s, t_end=5.0, dt=1e-3, integrator="rk4", convergence_check=False,
                    trajectory=False)
    cli = cli_json("simulate", anchor, "--no-convergence-check")
    assert np.array_equal(np.asarray(r["final_nodes"]), np.asarray(cli["final_nodes"]))


@pytest.mark.parametrize("C_b,says", [
    ([[-1, 1, 0, 0], [0, 1, 1, 0]], "C_b: row 2 (member 1): 1 at node 2"),
    ([[-1, 1, 0]], "C_b: row 1 (member 0): 3 column(s) for 4 node(s)"),
])
def test_bad_matrices_are_named(C_b, says):
    N = np.eye(3, 4)
    with pytest.raises(tg.InputError) as e:
        tg.Structure.from_matrices(N, C_b)
    assert says in str(e.value)
