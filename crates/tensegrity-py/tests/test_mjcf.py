"""``tensegrity export mjcf``: the exported model loads in MuJoCo (the ``mujoco`` package) and
settles where this project's rigid-bar dynamics comes to rest.

Two scenes of examples/mjcf/: ``prism_pinned.toml``, a prestressed Snelson prism pinned at its
three bottom nodes under gravity (the top sags about 4 cm and twists, so the equilibrium is
neither the drawn geometry nor trivial; one diagonal string stays slack), and ``hinge.toml``,
two bars sharing a node (a class-2 joint: a MuJoCo connect) turned about their pinned ends
by gravity against a string to a pinned node on no bar (a world site), whose equilibrium
angle is also found here by minimising its potential. Our equilibrium is ``tensegrity
simulate`` of the same scene run until at rest; MuJoCo's is the site positions after its own
run comes to rest. MuJoCo's string forces are checked against the law t = k (L − s0) above
the rest length and 0 below (the slack string)."""

import json

import numpy as np
import pytest

from conftest import EXAMPLES

mujoco = pytest.importorskip("mujoco")

SCENE = EXAMPLES / "mjcf" / "prism_pinned.toml"
HINGE = EXAMPLES / "mjcf" / "hinge.toml"
#: The settled positions must agree to this (m): the issue's bound.
TOLERANCE = 1e-3


def export(cli, scene, path):
    code, _, err = cli("export", "mjcf", scene, "--out", path)
    assert code == 0, err
    model = mujoco.MjModel.from_xml_path(str(path))
    return model, mujoco.MjData(model)


@pytest.fixture(scope="module")
def exported(cli, tmp_path_factory):
    """The MuJoCo model of the prism (written by the CLI) and its data."""
    return export(cli, SCENE, tmp_path_factory.mktemp("mjcf") / "prism.xml")


def at_rest(cli, scene):
    """This project's equilibrium: the rigid-bar dynamics run long enough to stop."""
    code, out, err = cli("simulate", scene, "--t-end", "200", "--integrator", "rk45",
                         "--rtol", "1e-10", "--atol", "1e-12", "--no-convergence-check", "--json")
    assert code == 0, err
    report = json.loads(out)
    assert np.abs(report["final_velocities"]).max() < 1e-6, "our run did not come to rest"
    return np.asarray(report["final_nodes"])


@pytest.fixture(scope="module")
def ours(cli):
    return at_rest(cli, SCENE)


def settle(model, data, n_nodes):
    """Steps MuJoCo until no node site moves by more than 1e-10 m in a second (at most
    200 s of its time; a bar's spin about its own axis, which nothing damps, is no motion of
    its nodes); the settled node positions."""
    before = site_positions(model, data, n_nodes)
    while data.time < 200.0:
        mujoco.mj_step(model, data, nstep=round(1.0 / model.opt.timestep))
        now = site_positions(model, data, n_nodes)
        if np.abs(now - before).max() < 1e-10:
            return now
        before = now
    pytest.fail(f"MuJoCo did not settle by t = {data.time}")


@pytest.fixture(scope="module")
def settled(exported):
    """MuJoCo's prism at rest."""
    model, data = exported
    settle(model, data, 6)
    return model, data


def site_positions(model, data, n_nodes=6):
    return np.array([data.site(f"n{i}").xpos for i in range(n_nodes)])


def test_the_model_is_the_scene(cli, tmp_path):
    model, data = export(cli, SCENE, tmp_path / "prism.xml")
    mujoco.mj_forward(model, data)
    start = np.array([
        [1.0, 0.0, 0.0], [-0.5, 0.8660254037844386, 0.0], [-0.5, -0.8660254037844386, 0.0],
        [0.8660254037844387, 0.5, 1.0], [-0.8660254037844387, 0.5, 1.0], [0.0, -1.0, 1.0],
    ])
    assert np.abs(site_positions(model, data) - start).max() < 1e-12
    assert (model.nbody, model.njnt, model.ntendon, model.neq) == (4, 3, 10, 3)
    length = np.linalg.norm(start[4] - start[0])
    for k in range(3):
        body = model.body(f"bar{k}")
        assert body.mass[0] == pytest.approx(1.0, rel=1e-12)
        assert body.inertia[:2] == pytest.approx([length**2 / 12] * 2, rel=1e-12)
    assert model.opt.gravity == pytest.approx([0.0, 0.0, -9.81])


def test_mujoco_settles_at_our_equilibrium(settled, ours):
    model, data = settled
    theirs = site_positions(model, data)
    difference = np.abs(theirs - ours).max()
    print(f"prism settled: largest node difference {difference:.3e} m at t = {data.time:.0f} s")
    assert difference < TOLERANCE
    # the equilibrium is not the drawn geometry: the top sagged and turned by centimetres
    moved = np.linalg.norm(ours[3:] - np.array([
        [0.8660254037844387, 0.5, 1.0], [-0.8660254037844387, 0.5, 1.0], [0.0, -1.0, 1.0]]),
        axis=1)
    assert moved.min() > 0.03
    assert difference < 0.01 * moved.min()


def tendon_jacobian(model, data):
    """d(length)/d(qvel) of each two-site tendon, from the sites' Jacobians."""
    rows = []
    for k in range(model.ntendon):
        adr = model.tendon_adr[k]
        a, b = (int(model.wrap_objid[adr + j]) for j in range(2))
        jac = []
        for site in (a, b):
            jp = np.zeros((3, model.nv))
            mujoco.mj_jacSite(model, data, jp, None, site)
            jac.append(jp)
        u = data.site_xpos[b] - data.site_xpos[a]
        rows.append(u / np.linalg.norm(u) @ (jac[1] - jac[0]))
    return np.array(rows)


def test_mujocos_string_forces_follow_the_tension_only_law(settled, ours):
    model, data = settled
    k, rest = model.tendon_stiffness, model.tendon_lengthspring[:, 1]
    length = data.ten_length
    law = k * np.maximum(length - rest, 0.0)
    # the slack diagonal (string 9) is shorter than its rest length: no force
    assert length[9] < rest[9] - 0.05 and law[9] == 0.0
    assert (law[:9] > 10.0).all()
    # MuJoCo's passive force is exactly Jᵀ(−t) with t from the law (a force in string 9
    # would show: its Jacobian row is not zero)
    J = tendon_jacobian(model, data)
    assert np.abs(J[9]).max() > 0.1
    np.testing.assert_allclose(data.qfrc_spring, -J.T @ law, atol=1e-9 * law.max())
    # the tensions are ours: the same lengths as our equilibrium's strings
    pairs = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5), (0, 5)]
    our_length = np.array([np.linalg.norm(ours[j] - ours[i]) for i, j in pairs])
    np.testing.assert_allclose(length, our_length, atol=1e-6)
    np.testing.assert_allclose(law, k * np.maximum(our_length - rest, 0.0), atol=1e-3)


def test_a_dropped_prism_rests_on_the_ground_plane(cli, tmp_path):
    """examples/prism_drop.toml has a [ground]: its plane and friction go over; the bars'
    capsules land on it and rest there (their radius above it), none falls through."""
    path = tmp_path / "drop.xml"
    code, _, err = cli("export", "mjcf", EXAMPLES / "prism_drop.toml", "--out", path)
    assert code == 0, err
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    assert model.geom("ground").friction[0] == pytest.approx(0.8)
    mujoco.mj_step(model, data, nstep=3000)
    radius = model.geom("bar0").size[0]
    bottom = np.array([data.site(f"n{i}").xpos[2] for i in range(3)])
    assert data.ncon >= 3
    assert np.all(np.abs(bottom - radius) < 0.1 * radius), bottom


def hinge_equilibrium():
    """The hinge's apex at rest, from its one degree of freedom: the angle θ about the line of
    the pinned nodes (x axis) minimising gravity's potential m g z (two 1 kg bars: their
    centres at half the apex's height) plus the string's ½ k (L − s0)₊², golden section."""
    r = np.sqrt(0.5)
    anchor = np.array([0.0, 1.5, 0.0])

    def apex(t):
        return np.array([0.0, r * np.cos(t), r * np.sin(t)])

    def energy(t):
        a = apex(t)
        stretch = max(np.linalg.norm(a - anchor) - 0.5, 0.0)
        return 9.81 * a[2] + 0.5 * 100.0 * stretch**2

    lo, hi = -1.5, 1.0
    for _ in range(200):
        m1, m2 = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
        lo, hi = (lo, m2) if energy(m1) < energy(m2) else (m1, hi)
    return apex(0.5 * (lo + hi))


def test_a_class_2_hinge_settles_at_our_equilibrium_and_the_closed_form(cli, tmp_path):
    model, data = export(cli, HINGE, tmp_path / "hinge.xml")
    assert (model.nbody, model.neq) == (3, 3)  # world + 2 bars; the shared node, 2 pins
    theirs = settle(model, data, 4)
    ours = at_rest(cli, HINGE)
    exact = hinge_equilibrium()
    assert np.abs(ours[1] - exact).max() < 1e-6
    difference = np.abs(theirs - ours).max()
    print(f"hinge settled: largest node difference {difference:.3e} m at t = {data.time:.0f} s")
    assert difference < TOLERANCE
    # the second bar's end at the shared node stays on the first's
    assert np.abs(data.site("n1_bar1").xpos - theirs[1]).max() < 1e-6
    # the apex turned by more than half a metre from where it was drawn
    assert np.linalg.norm(ours[1] - [0.0, 0.5, 0.5]) > 0.5
