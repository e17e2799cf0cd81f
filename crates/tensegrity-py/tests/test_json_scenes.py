"""JSON scenes from Python: a scene written as JSON by the command line reads back as the same
Structure and gives the same statics as its TOML."""

import numpy as np

import tensegrity as t
from conftest import EXAMPLES


def test_a_json_scene_is_the_toml_scene(cli, tmp_path):
    out = tmp_path / "prism.json"
    code, _, err = cli("export", "json", EXAMPLES / "prism.toml", "--out", out)
    assert code == 0, err
    a, b = t.Structure.from_toml(EXAMPLES / "prism.toml"), t.Structure.from_toml(out)
    np.testing.assert_array_equal(a.nodes, b.nodes)
    np.testing.assert_array_equal(a.strings, b.strings)
    np.testing.assert_array_equal(a.rest_length, b.rest_length)
    from_text = t.Structure.from_toml(out.read_text())
    np.testing.assert_array_equal(from_text.bars, a.bars)
    ra, rb = t.statics(EXAMPLES / "prism.toml"), t.statics(out)
    np.testing.assert_array_equal(ra["self_stress"], rb["self_stress"])
    assert ra["rank"] == rb["rank"]


def test_a_bad_json_scene_names_the_key():
    try:
        t.Structure.from_toml('{"nodes": [[0, 0, 0], [1, 0, 0]], "bars": [{"nodes": [0, 1], "colour": 1}]}')
    except t.InputError as e:
        assert "colour" in str(e)
    else:
        raise AssertionError("an unknown key was accepted")
