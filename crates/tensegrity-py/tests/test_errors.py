"""Bad input raises ``InputError`` (a ``ValueError``) naming the item in Python's words (the
keyword, never a command-line flag), with the command line's reason; failures of the
computation and refused estimates raise ``RuntimeError``s."""

import math

import numpy as np
import pytest

import tensegrity as tg
from conftest import EXAMPLES

PRISM_NODES = np.array([
    [1.0, 0.0, 0.0], [-0.5, 0.8660254037844387, 0.0], [-0.5, -0.8660254037844384, 0.0],
    [0.8660254037844386, 0.5, 1.0], [-0.8660254037844385, 0.5, 1.0], [0.0, -1.0, 1.0]])
BARS = [[0, 4], [1, 5], [2, 3]]
STRINGS = [[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3], [0, 3], [1, 4], [2, 5]]


def message(cli, *args):
    code, _, err = cli(*args)
    assert code == 2, err
    line = err.strip().splitlines()[0]
    assert line.startswith("error: "), err
    return line[len("error: "):]


def test_negative_stiffness_names_the_string():
    stiffness = np.full(9, 100.0)
    stiffness[4] = -5.0
    with pytest.raises(ValueError) as e:
        tg.Structure(PRISM_NODES, BARS, STRINGS, stiffness=stiffness)
    assert isinstance(e.value, tg.InputError)
    assert "string 4" in str(e.value) and "stiffness" in str(e.value) and "-5" in str(e.value)


def test_out_of_range_index_names_the_member():
    with pytest.raises(ValueError, match=r"bar 1: node index 9 is out of range"):
        tg.Structure(PRISM_NODES, [[0, 4], [1, 9], [2, 3]], STRINGS)
    with pytest.raises(ValueError, match=r"string 2: node index -1 is out of range"):
        tg.Structure(PRISM_NODES, BARS, [[0, 1], [1, 2], [2, -1]])


def test_nan_coordinate_names_the_node():
    nodes = PRISM_NODES.copy()
    nodes[3, 1] = math.nan
    with pytest.raises(ValueError) as e:
        tg.Structure(nodes, BARS, STRINGS)
    assert "node 3" in str(e.value) and "not finite" in str(e.value), str(e.value)


def test_scene_errors_are_the_clis(cli, tmp_path):
    bad = (EXAMPLES / "prism.toml").read_text().replace("stiffness = 1000.0", "stiffness = -1.0", 1)
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    with pytest.raises(ValueError) as e:
        tg.statics(path)
    assert str(e.value) == message(cli, "statics", path)
    assert "string 0" in str(e.value) and "line" in str(e.value)
    with pytest.raises(ValueError) as e:
        tg.statics(tmp_path / "missing.toml")
    assert str(e.value) == message(cli, "statics", tmp_path / "missing.toml")


@pytest.mark.parametrize("call, args", [
    (lambda: tg.toroid(sides=1), ["toroid", "--sides", "1"]),
    (lambda: tg.toroid(sides=2.5), ["toroid", "--sides", "2.5"]),
    (lambda: tg.roll(t_end=-1), ["roll", "--t-end", "-1"]),
    (lambda: tg.roll(incline="fortydeg"), ["roll", "--incline", "fortydeg"]),
    (lambda: tg.roll(dt=2e-3), ["roll", "--dt", "2e-3"]),
    (lambda: tg.michell(complexity=3, planar=True, beta=1, phi=1, r0=float("nan")),
     ["michell", "--complexity", "3", "--planar", "--beta", "1", "--phi", "1", "--r0", "nan"]),
    (lambda: tg.tipover(dynamic=True, incline=0.3),
     ["tipover", "--dynamic", "--incline", "0.3"]),
    (lambda: tg.simulate(EXAMPLES / "prism.toml", dt=-1),
     ["simulate", EXAMPLES / "prism.toml", "--dt", "-1"]),
    (lambda: tg.simulate(EXAMPLES / "prism.toml"), ["simulate", EXAMPLES / "prism.toml"]),
    (lambda: tg.michell_optimize(planar=True, radius_ratio=4),
     ["michell", "optimize", "--planar", "--radius-ratio", "4"]),
    (lambda: tg.tbar(beta="pi/6", phi="pi/8"), ["tbar", "--beta", "pi/6", "--phi", "pi/8"]),
    (lambda: tg.statics(EXAMPLES / "prism.toml", method="qr"),
     ["statics", EXAMPLES / "prism.toml", "--method", "qr"]),
])
def test_keyword_errors_name_the_keyword_with_the_clis_reason(cli, call, args):
    with pytest.raises(ValueError) as e:
        call()
    got = str(e.value)
    assert "--" not in got, got
    want = message(cli, *args)
    if want.startswith("invalid value '"):
        # a choice the CLI's parser (clap) refuses itself, before the engine sees it: Python
        # has the engine's message, naming the keyword and the choices
        assert got.startswith('method = "qr": expected one of'), got
        return
    usage = "invalid value for --"
    if want.startswith(usage):
        # the CLI's usage prefix names the flag; Python names the keyword, whose value it
        # passes typed (2.5, not "2.5"): the reason after `keyword = value: ` is the same
        want = want.split(": ", 1)[1]
        keyword = want.split(" = ", 1)[0]
        assert e.value.parameter == keyword
        assert got.startswith(keyword + " = "), got
        assert got.split(": ", 1)[1] == want.split(": ", 1)[1]
    else:
        assert got == want


def test_a_bad_value_names_its_keyword():
    with pytest.raises(tg.InputError) as e:
        tg.roll(t_end=-1)
    assert e.value.parameter == "t_end"


def test_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError):
        tg.toroid(sidez=8)


def test_refused_estimate_is_a_resource_error_naming_the_keyword(cli):
    with pytest.raises(RuntimeError) as e:
        tg.roll(fidelity="full", max_work=0.001)
    assert isinstance(e.value, tg.ResourceError)
    got = str(e.value)
    assert "--" not in got, got
    assert "raise the limit with `max_work` (e.g. max_work=" in got, got
    # the estimate itself is the command line's
    cli_text = message(cli, "roll", "--fidelity", "full", "--max-work", "0.001")
    assert got.split("; raise the limit")[0] == cli_text.split("; raise the limit")[0]


def test_a_failed_computation_has_the_clis_message(cli, tmp_path):
    s = tg.Structure([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1]], [[1, 2]],
                     supports=[0], loads={2: [0, 0, -1.0]})
    path = tmp_path / "mechanism.toml"
    path.write_text(s.to_toml())
    with pytest.raises(tg.ComputationError) as e:
        tg.statics(path)
    code, _, err = cli("statics", path)
    assert code == 1
    assert "error: " + str(e.value) == err.strip().splitlines()[-1]


def test_a_failed_computation_is_a_runtime_error():
    # a load on a mechanism the structure cannot carry (without least_squares)
    s = tg.Structure([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1]], [[1, 2]],
                     supports=[0], loads={2: [0, 0, -1.0]})
    with pytest.raises(RuntimeError) as e:
        tg.statics(s)
    assert isinstance(e.value, tg.ComputationError) and not isinstance(e.value, ValueError)


def test_numpy_values_cross_as_their_numbers_and_other_objects_are_refused_by_name():
    # a numpy integer is the integer (the same report), an object the engine cannot read is
    # an input error naming its keyword
    assert tg.toroid(sides=np.int64(12))["mass_kg"] == tg.toroid(sides=12)["mass_kg"]
    with pytest.raises(tg.InputError) as e:
        tg.toroid(sides=object())
    assert e.value.parameter == "sides"
    assert "cannot be passed" in str(e.value) and "--" not in str(e.value)


def test_a_full_model_setting_under_the_rigid_model_is_refused_by_name(cli):
    # given at another value or at its default: the rigid model ignores it either way, so it
    # is refused before any work, as on the command line
    for name, value in [("integrator", "imex-ark"), ("contact", "stick"), ("ground_stiffness", 1e5)]:
        with pytest.raises(ValueError) as e:
            tg.roll(fidelity="rigid", t_end=0.1, **{name: value})
        assert isinstance(e.value, tg.InputError)
        assert name in str(e.value) and "only the full model reads it" in str(e.value), str(e.value)
    # the same refusal as the command line's (which spells the flags)
    with pytest.raises(ValueError) as e:
        tg.roll(fidelity="rigid", t_end=0.1, integrator="imex-ark")
    cli_message = message(cli, "roll", "--fidelity", "rigid", "--t-end", "0.1",
                          "--integrator", "imex-ark")
    assert 'integrator = "imex-ark": only the full model reads it' in str(e.value)
    assert 'integrator = "imex-ark": only the full model reads it' in cli_message
    # what the rigid model reads is taken
    assert tg.roll(fidelity="rigid", t_end=0.1, mu=1.0)["mu"] == 1.0
