"""``simulate`` returns every history the scene records — positions, velocities, member
forces, energies, contact forces per sample — equal to the command line's ``--out`` CSV of
the same run (written with 17 significant digits: to 1e-12)."""

import numpy as np

import tensegrity as t
from conftest import EXAMPLES


def csv_columns(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, comments="#", ndmin=2)
    return {name.split(" [")[0]: data[:, i] for i, name in enumerate(header)}


def test_every_recorded_history_equals_the_csv(cli, tmp_path):
    record = ["nodes", "velocities", "member_forces", "energy", "contact_forces"]
    s = t.Structure.from_toml(EXAMPLES / "prism_drop.toml")
    sim = dict(s.tables["simulation"], record=record, t_end=0.4)
    scene = tmp_path / "drop.toml"
    scene.write_text(s.replace(simulation=sim).to_toml())
    out = tmp_path / "drop.csv"
    code, _, err = cli("simulate", scene, "--out", out, "--no-convergence-check")
    assert code == 0, err
    c = csv_columns(out)
    r = t.simulate(scene, convergence_check=False)
    n, members = len(s.nodes), len(s.bars) + len(s.strings)
    assert r["trajectory"].shape == (len(c["t"]), n, 3)
    np.testing.assert_allclose(r["t"], c["t"], rtol=0, atol=1e-12)
    for i in range(n):
        for a, axis in enumerate("xyz"):
            np.testing.assert_allclose(r["trajectory"][:, i, a], c[f"n{i}_{axis}"], rtol=1e-12,
                                       atol=1e-12)
            np.testing.assert_allclose(r["velocities"][:, i, a], c[f"v{i}_{axis}"], rtol=1e-12,
                                       atol=1e-12)
    assert r["member_forces"].shape == (len(c["t"]), members)
    names = [f"bar{k}" for k in range(len(s.bars))] + [f"string{k}" for k in range(len(s.strings))]
    for k, name in enumerate(names):
        np.testing.assert_allclose(r["member_forces"][:, k], c[f"{name}_force"], rtol=1e-12,
                                   atol=1e-9)
    np.testing.assert_allclose(r["kinetic_energy"], c["kinetic_energy"], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(r["energy"], c["total_energy"], rtol=1e-12, atol=1e-12)
    for j, node in enumerate(r["contact_nodes"]):
        for a, axis in enumerate("xyz"):
            np.testing.assert_allclose(r["contact_forces"][:, j, a], c[f"c{node}_{axis}"],
                                       rtol=1e-12, atol=1e-9)
    # the histories mean what they say: the prism falls freely from 0.5 m (no contact,
    # v_z = -g t) and lands after sqrt(2 · 0.5 / g) = 0.32 s, its feet then pushing up by
    # more than its weight as it stops
    weight, g = 3 * 1.0 * 9.81, 9.81
    falling = r["t"] < 0.3
    assert not r["contact_forces"][falling].any()
    np.testing.assert_allclose(r["velocities"][falling, :, 2].mean(axis=1), -g * r["t"][falling],
                               rtol=0, atol=1e-8)
    assert r["contact_forces"][:, :, 2].sum(axis=1).max() > weight
    # and the strings stay in tension, the bars in compression
    assert (r["member_forces"][:, :3] <= 0).all() and (r["member_forces"][:, 3:] >= 0).all()


def test_positions_only_without_a_record_list():
    s = t.Structure.from_toml(EXAMPLES / "prism.toml")
    r = t.simulate(s, t_end=0.01, convergence_check=False)
    assert "velocities" not in r and "member_forces" not in r and "energy" not in r
    assert r["trajectory"].shape[1:] == (6, 3)
