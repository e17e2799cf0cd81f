"""A ``Structure`` crosses to the engine as data (the dict of its arrays and tables, read as a
scene given as data), never as scene TOML: its reports equal the command line's on the same
scene file, with ``to_toml`` and the native TOML functions out of reach; errors of the data
name the item and no line."""

import numpy as np
import pytest

import tensegrity as tg
from tensegrity import _native
from conftest import EXAMPLES, assert_same

from test_structure import dropped, snelson


@pytest.fixture
def no_toml(monkeypatch):
    """Every way to scene TOML text raises: the structure's export and import and the native
    writer and reader."""

    def refuse(*args, **kwargs):
        raise AssertionError("scene TOML on the call path")

    monkeypatch.setattr(tg.Structure, "to_toml", refuse)
    monkeypatch.setattr(tg.Structure, "from_toml", classmethod(refuse))
    for name in ("structure_toml", "structure_read", "toml_text"):
        monkeypatch.setattr(_native, name, refuse)


def scene_file(structure, tmp_path, name="scene.toml"):
    """The structure's scene file (written before TOML is put out of reach)."""
    path = tmp_path / name
    path.write_text(structure.to_toml())
    return path


def test_statics_and_simulate_of_a_structure_need_no_toml(cli_json, tmp_path, monkeypatch,
                                                          request):
    loaded = snelson(supports={0: "xyz", 1: "xyz", 2: "xyz"}, loads={3: [0.0, 0.0, -10.0]},
                     stiffness=1000.0, bar_mass=1.0, bar_radius=0.01, bar_material="steel")
    falling = dropped(t_end=0.1)
    paths = scene_file(loaded, tmp_path, "loaded.toml"), scene_file(falling, tmp_path, "drop.toml")
    refs = (cli_json("statics", paths[0], "--modes", "2", "--least-squares"),
            cli_json("simulate", paths[1], "--no-convergence-check"))
    request.getfixturevalue("no_toml")
    with pytest.raises(AssertionError, match="scene TOML"):
        loaded.to_toml()
    # the structure is made, validated and run without TOML
    again = loaded.replace(stiffness=1000.0)
    assert again == loaded
    assert_same(tg.statics(again, modes=2, least_squares=True), refs[0])
    assert_same(tg.simulate(falling, trajectory=False, convergence_check=False), refs[1])
    r = tg.simulate(falling, convergence_check=False)
    assert r["trajectory"].shape == (len(r["t"]), 6, 3)
    # its matrices and topologies need none either
    assert loaded.equilibrium_matrix.shape == (18 - 9, 12)
    t = tg.Structure.toroid(sides=6)
    assert tg.statics(t)["rank"] == tg.toroid(sides=6)["rank"]


def test_a_structure_crosses_as_the_dict_of_its_arrays(cli_json):
    prism = tg.Structure.from_toml(EXAMPLES / "prism.toml")
    data = prism._arrays()
    assert {"nodes", "bars", "strings", "stiffness", "rest_length", "materials"} <= set(data)
    assert data["bars"] == [[0, 4], [1, 5], [2, 3]]
    assert data["materials"]["steel_rod"]["density"] == 7862.0
    ref = cli_json("statics", EXAMPLES / "prism.toml")
    assert_same(tg.statics(prism), ref)
    # the same dict, given as the scene, is the same scene
    assert_same(tg.statics(dict(data)), ref)


def test_the_structure_of_a_scene_file_reports_as_the_file(cli, cli_json):
    for name, args in (("tower.toml", ("--modes", "3")), ("dbar_loaded.toml", ())):
        s = tg.Structure.from_toml(EXAMPLES / name)
        kwargs = {"modes": 3} if args else {}
        assert_same(tg.statics(s, **kwargs), cli_json("statics", EXAMPLES / name, *args))
    scene = EXAMPLES / "prism_drop.toml"
    s = tg.Structure.from_toml(scene)
    assert "ground" in s.tables
    assert_same(tg.simulate(s, t_end=0.3, trajectory=False),
                cli_json("simulate", scene, "--t-end", "0.3"))


def test_errors_of_the_data_name_the_item_without_a_line():
    with pytest.raises(tg.InputError) as e:
        dropped().replace(ground={"stiffness": 1e4, "mu_static": 0.2, "mu_kinetic": 0.5,
                                  "point": [0.0, 0.0, -0.5]})
    assert "ground: mu_kinetic (0.5) exceeds mu_static (0.2)" in str(e.value)
    assert "line" not in str(e.value)
    with pytest.raises(tg.InputError) as e:
        snelson(supports={7: "xyz"})
    assert "support 0: node index 7 is out of range" in str(e.value)
    assert "line" not in str(e.value)
    with pytest.raises(tg.InputError) as e:
        snelson(ground={"stiffnes": 1e4})
    assert "unknown field `stiffnes`" in str(e.value)
    with pytest.raises(tg.InputError) as e:
        tg.statics({"nodes": [[0, 0, 0], [1, 0, 0]], "bars": [[0, -1]]})
    assert "bar 0: node index -1 is out of range" in str(e.value)


def test_equal_structures_compare_by_their_data():
    s = snelson(stiffness=100.0, bar_material="steel")
    back = tg.Structure.from_toml(s.to_toml())
    # the built-in material is written out in full, and the structures are still equal
    assert "steel" in back.materials and not s.materials
    assert back == s
    assert s != snelson(stiffness=200.0, bar_material="steel")
    k = np.full(9, 100.0)
    k[4] = np.nan
    partly = snelson(stiffness=k)
    assert partly._arrays()["stiffness"][4] is None
    assert tg.Structure.from_toml(partly.to_toml()) == partly
