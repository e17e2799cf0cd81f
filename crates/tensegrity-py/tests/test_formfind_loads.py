"""Loads in form-finding from Python (issue 43, item 4): a topology with ``[[loads]]`` reaches
the force density method through the same ``formfind`` request as the command line, and its
``loads``, ``reactions`` and ``equilibrium_residual`` cross unchanged; the structure it
synthesises carries the loads and the supports (the scene ``formfind --out`` writes)."""

import numpy as np
import pytest

import tensegrity as tg
from conftest import EXAMPLES, assert_same

NET = EXAMPLES / "formfind" / "loaded_net.toml"


@pytest.mark.skipif("formfind" not in tg.commands(), reason="no formfind command in this engine")
def test_the_loaded_net_crosses_with_its_reactions(cli_json, cli, tmp_path):
    r = tg.formfind(topology=str(NET))
    assert_same(r, cli_json("formfind", NET))
    reactions = np.array([np.asarray(x["force"], dtype=float) for x in r["reactions"]])
    loads = np.array([np.asarray(x["force"], dtype=float) for x in r["loads"]])
    assert reactions.shape == (12, 3) and loads.shape == (9, 3)
    # Σ r + Σ p = 0: the twelve held nodes carry the nine 1 N loads
    total = reactions.sum(axis=0) + loads.sum(axis=0)
    assert np.abs(total).max() < 1e-12
    assert abs(reactions[:, 2].sum() - 9.0) < 1e-12
    assert r["equilibrium_residual"] < 1e-14
    # the structure is the loaded scene `--out` writes: supports and loads kept
    out = tmp_path / "net.toml"
    code, _, err = cli("formfind", NET, "--out", out)
    assert code == 0, err
    s = tg.Structure.from_formfind(topology=str(NET))
    assert s.to_toml() == out.read_text()
    assert out.read_text().count("[[loads]]") == 9
    assert out.read_text().count("[[supports]]") == 12


@pytest.mark.skipif("formfind" not in tg.commands(), reason="no formfind command in this engine")
def test_loads_on_a_free_standing_topology_are_refused_by_name():
    text = ("[[bars]]\nnodes = [0, 1]\nforce_density = -1.0\n"
            "[[strings]]\nnodes = [1, 2]\nforce_density = 1.0\n"
            "[[strings]]\nnodes = [2, 0]\nforce_density = 1.0\n"
            "[[loads]]\nnode = 2\nforce = [0.0, 0.0, -1.0]\n")
    with pytest.raises(tg.InputError, match="loads: 1 load"):
        tg.formfind(topology=text)
