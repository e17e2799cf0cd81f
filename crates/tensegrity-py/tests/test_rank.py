"""Honest edges from Python: a form-found net with its coordinates rounded to nine
significant digits keeps the self-stress of the exact form, as the command line and
``formfind`` report it; huge counts are input errors, not aborts."""

import numpy as np

import tensegrity as tg
from conftest import EXAMPLES


def _rounded(a, digits):
    return np.array([float("{:.{}e}".format(x, digits - 1)) for x in a.ravel()]).reshape(a.shape)


def test_a_net_rounded_to_nine_digits_keeps_its_self_stress(cli_json, tmp_path):
    topology = EXAMPLES / "formfind" / "cable_net.toml"
    found = tg.formfind(topology=str(topology), analyse=True)
    exact = tg.Structure.from_formfind(topology=str(topology))
    ref = tg.statics(exact)
    assert ref["self_stress_dim"] == found["self_stress_dim"] == 1
    net = exact.replace(nodes=_rounded(exact.nodes, 9))
    assert not np.array_equal(net.nodes, exact.nodes)
    r = tg.statics(net)
    assert r["self_stress_dim"] == 1 and r["prestressable"]
    assert 0.0 < r["input_rounding"] <= 5e-9
    # taken as exact, the rounding's singular value counts
    assert tg.statics(net, input_precision=0.0)["self_stress_dim"] == 0
    # the command line on the same rounded scene agrees
    scene = tmp_path / "net9.toml"
    scene.write_text(net.to_toml())
    assert cli_json("statics", scene)["self_stress_dim"] == 1


def test_a_huge_node_count_is_an_input_error_not_an_abort():
    import pytest
    topology = ("n_nodes = 1000000000000\n[[strings]]\nnodes = [0, 1]\n"
                "force_density = 1.0\n")
    with pytest.raises(tg.InputError, match="n_nodes"):
        tg.formfind(topology=topology)
    # a count past u32 names the keyword and the bound, as on the command line; a huge one
    # within it is refused by its estimate before anything is allocated
    with pytest.raises(tg.InputError, match="sides = 4294967296: must be at most 4294967295"):
        tg.toroid(sides=2 ** 32)
    with pytest.raises(tg.ResourceError, match="sides = 4294967295.*max_memory"):
        tg.toroid(sides=2 ** 32 - 1)
