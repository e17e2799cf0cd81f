"""Exact derivatives of a force density form in Python (issue 47, items 1 and 6):
:class:`tensegrity.FormSensitivity` against the closed form of a node held by four strings,
x = (sum q_k x_k + p) / sum q, and the adjoint against the forward mode on the built-in grid;
bad input refused."""

import numpy as np
import pytest

import tensegrity
from tensegrity import FormSensitivity

ANCHORS = np.array([[0.0, 0.0, 1.0], [3.0, 0.5, 0.0], [1.0, 2.5, 0.5], [-0.5, 1.0, 2.0]])
Q = np.array([1.0, 2.0, 3.0, 4.0])
P = np.array([0.3, -0.2, -2.0])

STAR = "n_nodes = 5\n" + "".join(
    "[[strings]]\nnodes = [{}, 4]\nforce_density = {}\n".format(k, Q[k]) for k in range(4)
) + "".join(
    "[[fixed]]\nnode = {}\nposition = [{}, {}, {}]\n".format(k, *ANCHORS[k]) for k in range(4)
) + "[[loads]]\nnode = 4\nforce = [{}, {}, {}]\n".format(*P)


@pytest.fixture()
def star(tmp_path):
    path = tmp_path / "star.toml"
    path.write_text(STAR)
    return FormSensitivity(path)


def test_the_form_and_its_derivatives_have_their_closed_forms(star):
    total = Q.sum()
    x = (Q @ ANCHORS + P) / total
    form = star.form()
    assert np.allclose(form.nodes[4], x, atol=1e-14)
    assert np.allclose(form.nodes[:4], ANCHORS)
    assert np.allclose(form.lengths, np.linalg.norm(ANCHORS - x, axis=1), atol=1e-14)
    assert np.allclose(form.forces, Q * form.lengths, atol=1e-13)
    # each support holds its string against the free node: r_k = q_k (x_k - x)
    assert np.allclose(form.reactions, Q[:, None] * (ANCHORS - x), atol=1e-13)
    # dx/dq_k = (x_k - x) / sum q, dx/dp = I / sum q, dx/dx_k = q_k I / sum q
    for k in range(4):
        d = star.forward("force_density", k)
        assert np.allclose(d.nodes[4], (ANCHORS[k] - x) / total, atol=1e-14)
        assert np.allclose(d.nodes[:4], 0.0)
    d = star.forward("load", 4, 2)
    assert np.allclose(d.nodes[4], [0.0, 0.0, 1.0 / total], atol=1e-15)
    d = star.forward("fixed", 1, 0)
    assert np.allclose(d.nodes[4], [Q[1] / total, 0.0, 0.0], atol=1e-15)
    assert np.allclose(d.nodes[1], [1.0, 0.0, 0.0])


def test_the_adjoint_of_the_height_is_the_closed_form(star):
    total = Q.sum()
    x = (Q @ ANCHORS + P) / total
    dnodes = np.zeros((5, 3))
    dnodes[4, 2] = 1.0
    g = star.adjoint(dnodes)
    assert np.allclose(g.force_densities, (ANCHORS[:, 2] - x[2]) / total, atol=1e-14)
    assert np.allclose(g.loads[4], [0.0, 0.0, 1.0 / total], atol=1e-15)
    assert np.allclose(g.fixed[:, 2], Q / total, atol=1e-15)
    # a Python objective: f = the sum of the string forces, df/dq = L at fixed nodes
    f, grad = star.gradient(lambda form: (form.forces.sum(),
                                          _forces_dnodes(form, star.force_densities),
                                          form.lengths))
    assert np.isclose(f, (Q * np.linalg.norm(ANCHORS - x, axis=1)).sum())
    forward = [star.forward("force_density", k).forces.sum() for k in range(4)]
    assert np.allclose(grad.force_densities, forward, rtol=1e-12, atol=1e-14)


def _forces_dnodes(form, q):
    """d(sum q_k L_k)/dx for the star: q_k e_k at node 4 (e_k from node k to node 4)."""
    d = np.zeros_like(form.nodes)
    for k in range(4):
        e = (form.nodes[4] - form.nodes[k]) / form.lengths[k]
        d[4] += q[k] * e
        d[k] -= q[k] * e
    return d


def test_the_adjoint_equals_the_forward_mode_on_the_grid():
    s = FormSensitivity(builtin="grid:2")
    rng = np.random.default_rng(3)
    w = rng.normal(size=(s.n_nodes, 3))
    g = s.adjoint(w)
    for k in range(0, s.n_members, 7):
        d = s.forward("force_density", k)
        assert np.isclose(g.force_densities[k], (w * d.nodes).sum(), rtol=1e-10, atol=1e-13)


def test_bad_input_is_refused():
    with pytest.raises(tensegrity.InputError, match="fixed"):
        FormSensitivity(builtin="prism:3")
    s = FormSensitivity(builtin="grid:2")
    with pytest.raises(ValueError, match="kind"):
        s.forward("stiffness", 0)
    with pytest.raises(tensegrity.InputError, match="force_density"):
        s.forward("force_density", 10_000)
    with pytest.raises(ValueError, match="shape"):
        s.adjoint(np.zeros((2, 3)))


LINE = """nodes = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.1, 0.0, 0.0]]
[[strings]]
nodes = [0, 2]
length = 0.8
stiffness = 100.0
[[strings]]
nodes = [2, 1]
length = 0.6
stiffness = 100.0
[[fixed]]
node = 0
position = [-1.0, 0.0, 0.0]
[[fixed]]
node = 1
position = [1.0, 0.0, 0.0]
"""


def test_a_relaxed_form_and_its_derivatives_have_their_closed_forms(tmp_path):
    """A node on two strings (rest lengths a = 0.8, b = 0.6, equal stiffness) between anchors
    2 m apart: equal tensions put it at x = -1 + 2a/(a + b), so dx/da = 2b/(a + b)^2 and
    dx/db = -2a/(a + b)^2; the tension EA (L_a - a)/a; stiffening the first string pulls
    the node towards its anchor, dx/dEA_a = -(L_a/a - 1) / (EA (1/a + 1/b))."""
    (tmp_path / "line.toml").write_text(LINE)
    s = tensegrity.RelaxedSensitivity(tmp_path / "line.toml")
    a, b = 0.8, 0.6
    form = s.form()
    assert np.isclose(form.nodes[2, 0], -1.0 + 2 * a / (a + b), atol=1e-9)
    la = 2 * a / (a + b)
    assert np.allclose(form.tensions, 100.0 * (la - a) / a, rtol=1e-9)
    da = s.forward("rest_length", 0)
    assert np.isclose(da.nodes[2, 0], 2 * b / (a + b) ** 2, rtol=1e-8)
    db = s.forward("rest_length", 1)
    assert np.isclose(db.nodes[2, 0], -2 * a / (a + b) ** 2, rtol=1e-8)
    dk = s.forward("stiffness", 0)
    dx_dk = -(la / a - 1.0) / (100.0 * (1.0 / a + 1.0 / b))
    assert np.isclose(dk.nodes[2, 0], dx_dk, rtol=1e-8)
    # the adjoint of f = x_2 gives the same two derivatives
    w = np.zeros((3, 3))
    w[2, 0] = 1.0
    g = s.adjoint(w)
    assert np.allclose(g.rest_lengths, [da.nodes[2, 0], db.nodes[2, 0]], rtol=1e-10)
    assert np.allclose(g.stiffnesses, [dx_dk, s.forward("stiffness", 1).nodes[2, 0]],
                       rtol=1e-10)
    with pytest.raises(ValueError, match="kind"):
        s.forward("force_density", 0)
