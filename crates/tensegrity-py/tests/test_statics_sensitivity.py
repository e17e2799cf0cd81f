"""The statics' sensitivities in Python (issue 47, items 3 and 6):
:func:`tensegrity.margin_sensitivity` against central differences of the margin on a bar
held by strings to pinned anchors, and what it says of the Snelson prism (margin 1/√3, a
self-stress that lives on its special geometry); :func:`tensegrity.stiffness_sensitivity`
against the closed forms of a bar on a pinned base (λ = a = E A / l, f = √(a/m) / 2π)."""

import math
from pathlib import Path

import numpy as np
import pytest

import tensegrity
from tensegrity import margin_sensitivity, stiffness_sensitivity

ROOT = Path(__file__).resolve().parents[3]

# a bar held at each end by three strings to pinned anchors towards its middle: seven
# members on six free dofs, one self-stress
NODES = np.array([
    [0.0, 0.0, 0.0], [1.0, 0.1, 0.0],
    [0.4, 1.0, 0.2], [0.45, -0.9, 0.5], [0.35, 0.1, -1.0],
    [0.6, 1.1, -0.3], [0.55, -1.0, -0.4], [0.65, 0.2, 0.9],
])


def held_bar(nodes):
    rows = ", ".join("[{!r}, {!r}, {!r}]".format(*map(float, x)) for x in nodes)
    text = "nodes = [{}]\n[[bars]]\nnodes = [0, 1]\n".format(rows)
    for i, a in [(0, 2), (0, 3), (0, 4), (1, 5), (1, 6), (1, 7)]:
        text += "[[strings]]\nnodes = [{}, {}]\n".format(i, a)
    for a in range(2, 8):
        text += "[[supports]]\nnode = {}\n".format(a)
    return text


def test_the_margin_gradient_matches_central_differences():
    m = margin_sensitivity(held_bar(NODES))
    assert m.smoothness == "differentiable" and m.detail == {}
    assert 0.0 < m.margin < 1.0 and m.nodes.shape == (8, 3)
    assert m.prestress_level == 0.0 and not m.axial_stiffnesses.any()
    assert m.at_margin and m.at_bound
    h = 1e-5

    def margin_at(i, axis, step):
        x = NODES.copy()
        x[i, axis] += step
        return margin_sensitivity(held_bar(x)).margin

    largest = np.abs(m.nodes).max()
    for i in range(8):
        for axis in range(3):
            d1 = (margin_at(i, axis, h) - margin_at(i, axis, -h)) / (2 * h)
            d2 = (margin_at(i, axis, h / 2) - margin_at(i, axis, -h / 2)) / h
            fd = (4 * d2 - d1) / 3
            assert abs(fd - m.nodes[i, axis]) < 1e-6 * largest, (i, axis, fd, m.nodes[i, axis])


def test_the_prism_margin_lives_on_its_special_geometry():
    m = margin_sensitivity(ROOT / "examples" / "prism.toml")
    # bars at |q| = 1, the ring strings at the margin 1/√3 (the prism's self-stress)
    assert m.margin == pytest.approx(1 / math.sqrt(3), abs=1e-9)
    assert m.smoothness == "special_geometry" and m.nodes is None
    assert m.detail["mechanisms"] == 1 and m.detail["coupling"] > 1e-2
    assert np.abs(m.stress).max() == pytest.approx(1.0, abs=1e-12)
    # its lowest frequencies skip the six rigid-body motions (ω² of round-off), as the
    # statics report's do
    s = stiffness_sensitivity(ROOT / "examples" / "prism.toml", modes=2)
    report = tensegrity.statics(str(ROOT / "examples" / "prism.toml"), modes=2)
    assert [f.value for f in s.frequencies] == pytest.approx(report["natural_frequencies_hz"],
                                                            rel=1e-9)
    # its rest lengths realise its self-stress: the state is balanced, no warning
    assert s.equilibrium_residual < 1e-9 and s.warnings == []
    # a ring string shortened by 1 cm realises none: the derivatives come with a warning
    text = (ROOT / "examples" / "prism.toml").read_text()
    first = text.index("rest_length = ")
    end = text.index("\n", first)
    value = float(text[first + len("rest_length = "):end])
    off = text[:first] + "rest_length = {!r}".format(value - 0.01) + text[end:]
    s = stiffness_sensitivity(off)
    assert s.equilibrium_residual > 1e-3 and len(s.warnings) == 1
    assert "out of equilibrium" in s.warnings[0]


BAR = """
nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
[materials.steel]
density = 7800.0
youngs_modulus = 200e9
yield_strength = 500e6
[[bars]]
nodes = [0, 1]
mass = 2.0
material = "steel"
radius = 0.001
[[supports]]
node = 0
[[supports]]
node = 1
directions = ["y", "z"]
"""


def test_the_stiffness_sensitivities_match_a_closed_form():
    s = stiffness_sensitivity(BAR, modes=1)
    a = 200e9 * math.pi * 0.001 ** 2 / 1.0
    assert s.axial_stiffnesses == pytest.approx([a], rel=1e-12)
    assert s.force_densities == pytest.approx([0.0], abs=1e-12)
    lam = s.smallest_eigenvalue
    # K = a on the one free dof: λ = a, dλ/da = 1, dλ/dq = 0 (the motion is along the bar)
    assert lam.value == pytest.approx(a, rel=1e-12) and lam.multiplicity == 1
    assert lam.axial_stiffnesses == pytest.approx([1.0], rel=1e-12)
    assert lam.force_densities == pytest.approx([0.0], abs=1e-12)
    assert lam.nodes.shape == (2, 3) and lam.prestress_level == 0.0
    # half the bar's 2 kg at the free end: f = √(a / 1 kg) / 2π, df/da = f / (2a)
    (f,) = s.frequencies
    expected = math.sqrt(a) / (2 * math.pi)
    assert f.value == pytest.approx(expected, rel=1e-12)
    assert f.axial_stiffnesses == pytest.approx([expected / (2 * a)], rel=1e-10)
    assert stiffness_sensitivity(BAR).frequencies == []


def test_bad_input_is_refused_by_name():
    with pytest.raises(tensegrity.InputError, match="scene"):
        margin_sensitivity("nodes = [[0.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 7]\n")
    massless = BAR.replace("mass = 2.0\n", "")
    with pytest.raises(tensegrity.TensegrityError, match="node 1"):
        stiffness_sensitivity(massless, modes=1)
