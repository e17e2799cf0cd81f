"""Every command from Python against the command line's ``--json`` on the same input: the
same keys, every number equal to 1e-12 (relative, absolute below 1). The only keys left out
are wall-clock timings (``wall_time_s``, conftest.TIMING_KEYS); ``simulate``'s samples
(``t``, ``trajectory`` and the histories the scene records) are compared with the CLI's
``--out`` CSV instead (the CLI writes the samples there; test_simulate_histories.py)."""

import csv
import json

import numpy as np
import pytest

import tensegrity as tg
from conftest import EXAMPLES, assert_same

#: The per-sample histories ``simulate`` adds to the report (the CLI writes them to ``--out``).
HISTORIES = ("velocities", "member_forces", "kinetic_energy", "energy", "contact_nodes",
             "contact_forces")


def pop_samples(py):
    """``t``, ``trajectory``, and the histories taken out of a ``simulate`` result."""
    t, traj = py.pop("t"), py.pop("trajectory")
    for key in HISTORIES:
        py.pop(key, None)
    return t, traj


def test_statics_prism(cli_json):
    assert_same(tg.statics(EXAMPLES / "prism.toml"), cli_json("statics", EXAMPLES / "prism.toml"))


def test_statics_loaded_dbar_with_modes_and_method(cli_json):
    scene = EXAMPLES / "dbar_loaded.toml"
    assert_same(tg.statics(str(scene), method="dense", rank_tol=1e-10),
                cli_json("statics", scene, "--method", "dense", "--rank-tol", "1e-10"))
    tower = EXAMPLES / "tower.toml"
    assert_same(tg.statics(tower, modes=4, mass="consistent"),
                cli_json("statics", tower, "--modes", "4", "--mass", "consistent"))


def test_statics_of_toml_text_and_structure_equal_the_file(cli_json):
    text = (EXAMPLES / "prism.toml").read_text()
    ref = cli_json("statics", EXAMPLES / "prism.toml")
    assert_same(tg.statics(text), ref)
    assert_same(tg.statics(tg.Structure.from_toml(text)), ref)


def test_simulate_report_and_trajectory(cli, tmp_path):
    scene = EXAMPLES / "double_pendulum.toml"
    out = tmp_path / "traj.csv"
    code, stdout, err = cli("simulate", scene, "--json", "--out", out, "--t-end", "0.2",
                            "--integrator", "rk45", "--rtol", "1e-9")
    assert code == 0, err
    ref = json.loads(stdout)
    py = tg.simulate(scene, t_end=0.2, integrator="rk45", rtol=1e-9)
    t, traj = pop_samples(py)
    assert_same(py, ref)
    rows = [r for r in csv.reader(open(out)) if r and not r[0].startswith("#")]
    table = np.array(rows[1:], dtype=float)
    n = traj.shape[1]
    assert traj.shape == (len(table), n, 3)
    np.testing.assert_allclose(t, table[:, 0], rtol=1e-15, atol=0)
    np.testing.assert_allclose(traj.reshape(len(t), 3 * n), table[:, 1:1 + 3 * n],
                               rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(traj[-1], np.array(ref["final_nodes"]), rtol=1e-12, atol=1e-12)


def test_simulate_without_trajectory_is_the_plain_report(cli_json):
    scene = EXAMPLES / "prism_drop.toml"
    ref = cli_json("simulate", scene, "--t-end", "0.3")
    py = tg.simulate(scene, t_end=0.3, trajectory=False)
    assert_same(py, ref)


def test_simulate_of_an_elastic_scene_is_the_clis(cli, tmp_path):
    # TsgFEM's T-bar as elastic members (`[simulation] bars = "elastic"`): the same run,
    # report and samples as the command line
    scene = EXAMPLES / "anchors" / "tsgfem_tbar_elastic.toml"
    out = tmp_path / "traj.csv"
    code, stdout, err = cli("simulate", scene, "--json", "--out", out)
    assert code == 0, err
    ref = json.loads(stdout)
    py = tg.simulate(scene)
    t, traj = pop_samples(py)
    assert_same(py, ref)
    assert ref["bar_length_drift"] == 0.0 and ref["valid"]
    rows = [r for r in csv.reader(open(out)) if r and not r[0].startswith("#")]
    table = np.array(rows[1:], dtype=float)
    np.testing.assert_allclose(t, table[:, 0], rtol=1e-15, atol=0)
    np.testing.assert_allclose(traj[-1], np.array(ref["final_nodes"]), rtol=1e-12, atol=1e-12)


def test_toroid(cli_json):
    assert_same(tg.toroid(), cli_json("toroid"))
    assert_same(tg.toroid(sides=12, stabilize="inner,outer"),
                cli_json("toroid", "--sides", "12", "--stabilize", "inner,outer"))


def test_toroid_angles_and_flags(cli_json):
    assert_same(tg.toroid(prism_only=True, rim_window=True),
                cli_json("toroid", "--prism-only", "--rim-window"))


def roll(**kw):
    """``tg.roll`` without its ``history`` (the CLI writes it to ``--out``; compared in
    test_roll_history_is_the_clis_csv)."""
    out = tg.roll(**kw)
    out.pop("history")
    return out


def test_roll_rigid_and_full(cli_json):
    assert_same(roll(fidelity="rigid", t_end=1.0, incline="40deg"),
                cli_json("roll", "--fidelity", "rigid", "--t-end", "1", "--incline", "40deg"))
    assert_same(roll(fidelity="full", t_end=0.3),
                cli_json("roll", "--fidelity", "full", "--t-end", "0.3"))


def test_roll_history_is_the_clis_csv(cli, tmp_path):
    out = tmp_path / "history.csv"
    code, stdout, err = cli("roll", "--fidelity", "full", "--t-end", "0.3", "--out", out,
                            "--json")
    assert code == 0, err
    py = tg.roll(fidelity="full", t_end=0.3)
    rows = [r for r in csv.reader(open(out)) if r and not r[0].startswith("#")]
    header, table = rows[0], np.array(rows[1:], dtype=float)
    assert [h.split(" [")[0] for h in header] == list(py["history"])
    for k, name in enumerate(py["history"]):
        np.testing.assert_allclose(py["history"][name], table[:, k], rtol=1e-12, atol=1e-12)
    # a history that means what it says: 1 ms samples, energy zero at the start, the axle
    # going downhill
    h = py["history"]
    assert len(h["t"]) == 301 and np.allclose(np.diff(h["t"]), 1e-3, rtol=0, atol=1e-12)
    assert h["energy_J"][0] == 0.0 and h["axle_s"][-1] > h["axle_s"][0]


def test_roll_full_under_imex_ark(cli_json):
    py = roll(fidelity="full", t_end=0.3, integrator="imex-ark", incline="30deg", mu=1.2)
    assert_same(py, cli_json("roll", "--fidelity", "full", "--t-end", "0.3",
                             "--integrator", "imex-ark", "--incline", "30deg", "--mu", "1.2"))
    # its own default step (wheel_rolling::defaults::IMEX_ARK_ROLL_DT), not the split's
    assert py["integrator"] == "imex-ark" and py["dt"] == 2.5e-4
    assert py["valid"] and py["energy_balance_error"] < 2e-3


def test_tipover_three_modes(cli_json):
    assert_same(tg.tipover(sides=16, sigma=0.5), cli_json("tipover", "--sides", "16", "--sigma", "0.5"))
    # less their `history` (the CLI's --out; test_tipover_tbar_histories.py compares it)
    assert_same(_less(tg.tipover(dynamic=True), "history"), cli_json("tipover", "--dynamic"))
    assert_same(_less(tg.tipover(rolling=True, t_end=1.0), "history"),
                cli_json("tipover", "--rolling", "--t-end", "1"))


def _less(result, *keys):
    """``result`` without ``keys`` (what a function adds to the CLI's --json)."""
    return {k: v for k, v in result.items() if k not in keys}


def test_michell(cli_json):
    args = dict(complexity=3, cylindrical=0.25, beta="pi/6", phi="22.5deg", azimuth=-0.5)
    assert_same(tg.michell(**args),
                cli_json("michell", "--complexity", "3", "--cylindrical", "0.25", "--beta",
                         "pi/6", "--phi", "22.5deg", "--azimuth", "-0.5"))
    assert_same(tg.michell(complexity=4, planar=True, beta=np.pi / 6, phi=np.pi / 8,
                           method="global"),
                cli_json("michell", "--complexity", "4", "--planar", "--beta", "pi/6",
                         "--phi", "pi/8", "--method", "global"))


def test_michell_optimize(cli_json):
    assert_same(tg.michell_optimize(planar=True, radius_ratio=0.25, complexity=4),
                cli_json("michell", "optimize", "--planar", "--radius-ratio", "0.25",
                         "--complexity", "4"))
    assert_same(tg.michell_optimize(spherical="pi/24", radius_ratio=0.3, joint_mass=0.01),
                cli_json("michell", "optimize", "--spherical", "pi/24", "--radius-ratio",
                         "0.3", "--joint-mass", "0.01"))


def test_michell_table(cli, tmp_path):
    # the CLI writes this table as CSV (no --json): compared row by row
    out = tmp_path / "table.csv"
    code, _, err = cli("michell-table", "--max-complexity", "4", "--out", out)
    assert code == 0, err
    rows = list(csv.DictReader(open(out)))
    py = tg.michell_table(max_complexity=4)
    assert set(py) == {"rows"} and len(py["rows"]) == len(rows)
    for a, b in zip(py["rows"], rows):
        assert set(a) == set(b)
        for k in a:
            assert abs(float(a[k]) - float(b[k])) <= 1e-12 * max(1.0, abs(float(b[k]))), k


def test_tbar(cli_json):
    assert_same(tg.tbar(beta="pi/6", phi="pi/8", cylindrical=0.25),
                cli_json("tbar", "--beta", "pi/6", "--phi", "pi/8", "--cylindrical", "0.25"))
    assert_same(tg.tbar(beta="pi/6", phi="pi/8", spherical="pi/24", wheel=True),
                cli_json("tbar", "--beta", "pi/6", "--phi", "pi/8", "--spherical", "pi/24",
                         "--wheel"))


def test_tbar_roll(cli_json):
    assert_same(_less(tg.tbar_roll(treads=[4, 8], t_end=0.5), "table", "history"),
                cli_json("tbar", "roll", "--treads", "4,8", "--t-end", "0.5"))


@pytest.mark.skipif("formfind" not in tg.commands(), reason="no formfind command in this engine")
def test_formfind(cli_json, cli, tmp_path):
    assert_same(tg.formfind(builtin="prism:3"), cli_json("formfind", "--builtin", "prism:3"))
    assert_same(tg.formfind(builtin="tower:3", n=2, method="adaptive", prestress=50.0),
                cli_json("formfind", "--builtin", "tower:3", "--n", "2", "--method", "adaptive",
                         "--prestress", "50"))
    # the found structure is the scene `formfind --out` writes
    out = tmp_path / "prism.toml"
    code, _, err = cli("formfind", "--builtin", "octahedron", "--out", out)
    assert code == 0, err
    s = tg.Structure.from_formfind(builtin="octahedron")
    assert s.to_toml() == out.read_text()
    assert tg.statics(s)["self_stress_dim"] >= 1


@pytest.mark.skipif("formfind" not in tg.commands(), reason="no formfind command in this engine")
def test_formfind_analyse(cli_json):
    # the statics of the form with `analyse` only (`--analyse`); the form itself the same bits
    plain = tg.formfind(builtin="grid:3")
    analysed = tg.formfind(builtin="grid:3", analyse=True)
    assert_same(analysed, cli_json("formfind", "--builtin", "grid:3", "--analyse"))
    for key in ("self_stress_dim", "prestressable", "prestress_stable"):
        assert plain[key] is None, key
    assert analysed["prestressable"] and analysed["prestress_stable"]
    assert analysed["self_stress_dim"] > 0
    for key in ("nodes", "force_density", "member_force", "rest_length"):
        assert np.array_equal(np.asarray(plain[key]), np.asarray(analysed[key])), key


def test_sweep_against_the_cli(cli, tmp_path):
    spec = {"study": "tipover", "axes": {"sigma": [0.3, 0.6],
                                         "epsilon": {"from": 0.25, "to": 0.75, "step": 0.25}}}
    path = tmp_path / "spec.toml"
    path.write_text(
        'study = "tipover"\n[axes]\nsigma = [0.3, 0.6]\n'
        'epsilon = { from = 0.25, to = 0.75, step = 0.25 }\n')
    out = tmp_path / "rows.csv"
    code, _, err = cli("sweep", path, "--out", out, "--quiet", "--threads", "2")
    assert code == 0, err
    ref = tg.read_rows(out)
    for got in (tg.sweep(spec, threads=1), tg.sweep(path, threads=2),
                tg.sweep(path.read_text())):
        assert list(got) == list(ref)
        for k in ref:
            if ref[k].dtype.kind in "fi":
                np.testing.assert_allclose(got[k], ref[k], rtol=1e-12, atol=0)
            else:
                assert (got[k] == ref[k]).all()
    assert len(ref["case"]) == 6 and ref["sigma"].tolist() == [0.3] * 3 + [0.6] * 3


def test_sweep_out_file_is_the_clis(cli, tmp_path):
    path = tmp_path / "spec.toml"
    path.write_text('study = "toroid"\n[axes]\nsides = [6, 8]\n')
    a, b = tmp_path / "cli.csv", tmp_path / "py.csv"
    code, _, err = cli("sweep", path, "--out", a, "--quiet")
    assert code == 0, err
    tg.sweep(path, out=b, threads=2)
    assert a.read_text() == b.read_text()


def test_solve_is_the_cli_s_load_path(cli_json):
    """The two-bar truss through both limit points: the Python dict equals the CLI's JSON,
    and its first limit point is the closed form's λ* = 1.2058608 (examples/von_mises.toml)."""
    scene = EXAMPLES / "von_mises.toml"
    py = tg.solve(scene, target=2.0)
    assert_same(py, cli_json("solve", scene, "--target", "2"))
    assert py["limit_points"] == 2
    assert abs(py["first_limit_load_factor"] - 1.2058607502775498) < 1e-9
    assert py["path"]["points"][-1]["stability"] == "stable"
