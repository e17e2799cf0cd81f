"""Clustered strings in a ``Structure``: given as arguments, read from a scene file and
written back (exact round trip), crossing as data; bad clusters are named."""

import numpy as np
import pytest

import tensegrity as tg


def pulley(**kwargs):
    """A string from an anchor (node 0) over a pulley (node 1) down to a hanging node 2."""
    args = dict(clusters=[[0, 1, 2]], cluster_stiffness=[1e4], cluster_rest_length=[1.9],
                supports=[0, 1], loads={2: (0.0, 0.0, -10.0)})
    args.update(kwargs)
    return tg.Structure([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 0.0, 0.0]], **args)


def test_a_cluster_round_trips_through_data_and_toml():
    s = pulley(cluster_damping=[2.0], cluster_friction=[[0.3]], cluster_material=["uhmwpe"])
    assert s.n_clusters == 1 and s.n_strings == 0
    data = s._arrays()
    assert data["clusters"] == [[0, 1, 2]] and data["cluster_friction"] == [[0.3]]
    back = tg.Structure.from_toml(s.to_toml())
    assert back == s
    assert back.clusters == [[0, 1, 2]]
    assert back.cluster_rest_length == [1.9] and back.cluster_damping == [2.0]
    assert s != pulley()


@pytest.mark.parametrize("kwargs,says", [
    ({"clusters": [[0, 1]]}, "cluster 0: passes through 2 node(s)"),
    ({"clusters": [[0, 1, 7]]}, "cluster 0"),
    ({"cluster_friction": [[0.1, 0.2]]}, "cluster 0: 2 friction coefficient(s) for 1 inner"),
    ({"cluster_stiffness": [-1.0]}, "cluster 0: stiffness must be positive and finite"),
    ({"cluster_stiffness": [1.0, 2.0]}, "cluster_stiffness: expected one entry per cluster"),
    ({"clusters": [[0, 1, 1]]}, "cluster 0: segment 1 (nodes 1 and 1) has zero length"),
])
def test_bad_clusters_are_named(kwargs, says):
    with pytest.raises(tg.InputError) as e:
        pulley(**kwargs)
    assert says in str(e.value)


def test_the_equilibrium_matrix_clusters_the_segments_columns():
    """A's cluster column is Σ_i (L_c / l_i) times its segments' columns (built here from
    C_c and the nodes): A_seg diag(L_c / l) Sᵀ, CTSFEM's clustering; the clustered prism's
    counts are the hand count (10 columns, rank 9: one self-stress)."""
    s = tg.Structure.from_toml(__import__("conftest").EXAMPLES / "clustered_prism.toml")
    x = np.asarray(s.nodes, dtype=float)
    cc, S, A = s.C_c, s.clustering_matrix, s.equilibrium_matrix
    assert S.shape == (1, cc.shape[0]) and np.all(S == 1.0)
    seg = cc @ x                                   # segment vectors, segments × 3
    lengths = np.linalg.norm(seg, axis=1)
    full = np.zeros((3 * len(x), cc.shape[0]))
    for i in range(cc.shape[0]):
        a, b = int(np.argmin(cc[i])), int(np.argmax(cc[i]))
        full[3 * a:3 * a + 3, i] -= seg[i]
        full[3 * b:3 * b + 3, i] += seg[i]
    rows = [3 * n + d for n, d in s.free_dofs]
    ours = full[rows] @ np.diag(lengths.sum() / lengths) @ S.T
    assert np.abs(A[:, -1:] - ours).max() < 1e-14 * np.abs(ours).max()
    assert A.shape[1] == s.n_bars + s.n_strings + 1 == 10
    assert np.linalg.matrix_rank(A) == 9


@pytest.mark.parametrize("example,command,flags,keywords", [
    ("clustered_prism.toml", "statics", (), {}),
    ("pulley_load.toml", "solve", (), {}),
    ("atwood.toml", "simulate", ("--no-convergence-check",),
     {"convergence_check": False, "trajectory": False}),
])
def test_a_clustered_structure_reports_as_its_file(cli_json, example, command, flags,
                                                   keywords):
    from conftest import EXAMPLES, assert_same
    path = EXAMPLES / example
    s = tg.Structure.from_toml(path)
    assert s.n_clusters == 1
    assert_same(getattr(tg, command)(s, **keywords), cli_json(command, path, *flags),
                rtol=1e-9)


def test_the_atwood_machine_falls_as_the_closed_form():
    s = tg.Structure.from_toml(__import__("conftest").EXAMPLES / "atwood.toml")
    r = tg.simulate(s, convergence_check=False, trajectory=False)
    m1, m2, g = 3.0, 1.0, 9.81
    drop = 0.5 * (m1 - m2) * g / (m1 + m2) * r["t_end"] ** 2
    assert abs(r["final_nodes"][1][2] - (-1.0 - drop)) < 1e-9
    assert abs(r["final_nodes"][2][2] - (-1.5 + drop)) < 1e-9


def test_a_cluster_rest_length_change_reels_along_the_load_path(cli_json, tmp_path):
    """``cluster_rest_length_change`` drives the whole rest length along ``solve``'s path
    (EA kept): the 10 kg weight over the pulley keeps its tension W and rises by
    0.1 (1 + W/EA) at λ = 1, as the CLI on the written scene says."""
    w, ea = 98.1, 1e4 * 1.99019
    s = tg.Structure([[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, -1.0]],
                     clusters=[[0, 1, 2]], cluster_stiffness=[1e4],
                     cluster_rest_length=[1.99019], cluster_rest_length_change=[-0.1],
                     supports=[0, 1], masses={2: 10.0}, gravity=(0.0, 0.0, -9.81))
    r = tg.solve(s)
    last = r["path"]["points"][-1]
    assert last["lambda"] == 1.0
    assert abs(last["tensions"][0] - w) < 1e-9 * w
    assert abs(last["displacements"][2][2] - 0.1 * (1.0 + w / ea)) < 1e-12
    path = tmp_path / "reel.toml"
    path.write_text(s.to_toml())
    assert "rest_length_change = -0.1" in path.read_text()
    from conftest import assert_same
    assert_same(r, cli_json("solve", path), rtol=1e-12)
