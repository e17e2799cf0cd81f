"""The keys a scene file holds beside its structure cross as data too: supports along any
direction, on springs and with a prescribed displacement, elastic bars' rest lengths, a bar's
``elastic``, strings' masses, point masses, rest-length changes. A ``Structure`` read from
each bundled example of them reports as the command line on the file (no TOML on the way),
round-trips through scene TOML, and a structure given by these arguments has the closed
form of the inclined roller."""

import numpy as np
import pytest

import tensegrity as tg
from conftest import EXAMPLES, assert_same

from test_structure_data import no_toml  # noqa: F401 (a fixture)


CASES = [
    # (example, command, CLI flags, Python keywords)
    ("inclined_roller.toml", "statics", (), {}),
    ("prescribed_displacement.toml", "statics", (), {}),
    ("solve_drivers.toml", "solve", (), {}),
    ("mixed_bars.toml", "simulate", ("--no-convergence-check", "--t-end", "0.05"),
     {"convergence_check": False, "trajectory": False, "t_end": 0.05}),
    ("anchors/tsgfem_tbar_elastic.toml", "simulate",
     ("--no-convergence-check", "--t-end", "0.05"),
     {"convergence_check": False, "trajectory": False, "t_end": 0.05}),
]


@pytest.mark.parametrize("example,command,flags,keywords", CASES)
def test_a_structure_read_from_a_file_reports_as_the_file(cli_json, request, example,
                                                          command, flags, keywords):
    path = EXAMPLES / example
    ref = cli_json(command, path, *flags)
    s = tg.Structure.from_toml(path)
    assert tg.Structure.from_toml(s.to_toml()) == s
    request.getfixturevalue("no_toml")
    got = getattr(tg, command)(s, **keywords)
    assert_same(got, ref, rtol=1e-9)


def roller(**kwargs):
    """examples/inclined_roller.toml given as arguments: a bar from a pin to a node on a 30°
    incline, 1 kN down on it."""
    s, c = np.sin(np.radians(30.0)), np.cos(np.radians(30.0))
    args = dict(bar_material="soft", bar_radius=0.01,
                materials={"soft": (1000.0, 1e7, 1e6)}, supports={0: "xyz"},
                support_along={1: [[-s, 0.0, c], [0.0, 1.0, 0.0]]}, loads={1: (0, 0, -1000.0)})
    args.update(kwargs)
    return tg.Structure([[0, 0, 0], [2.0, 0, 0]], [[0, 1]], **args)


def test_supports_along_and_on_springs_given_as_arguments():
    r = tg.statics(roller())
    # the incline pushes along its normal with P / cos 30°, the bar carries -P tan 30°
    assert abs(r["reactions"][1]["along"][0] - 1000.0 / np.cos(np.radians(30.0))) < 1e-9
    assert abs(r["member_force"][0] + 1000.0 * np.tan(np.radians(30.0))) < 1e-9
    # on a spring of 1e4 N/m along its normal the node sinks by the reaction over k
    sprung = roller(support_stiffness={1: 1e4})
    assert sprung != roller()
    assert tg.Structure.from_toml(sprung.to_toml()) == sprung
    with pytest.raises(tg.InputError, match="support_stiffness of node 0"):
        roller(supports={}, support_stiffness={0: 1e4})


def test_point_and_string_masses_and_rigid_bars_cross_and_are_checked():
    t = tg.Structure.from_toml(EXAMPLES / "anchors/tsgfem_tbar_elastic.toml")
    assert np.allclose(t.string_mass, 2.2666666666666666)
    assert t.bar_rest_length[0] == 2.000139266823317
    heavier = t.replace(masses={0: 1.0})
    assert heavier.masses == {0: 1.0} and heavier != t
    with pytest.raises(tg.InputError, match="point mass 0: node 9"):
        t.replace(masses={9: 1.0})
    m = tg.Structure.from_toml(EXAMPLES / "mixed_bars.toml")
    assert m.bar_elastic == [True, False, False]
    with pytest.raises(tg.InputError, match="bar_elastic"):
        m.replace(bar_elastic=[True])
