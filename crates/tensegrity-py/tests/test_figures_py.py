"""The project's figures and the command line's exports, written from Python by the same Rust
code in-process: ``tensegrity.figure`` equals ``tensegrity figures --only N`` (SVG byte for
byte with its data CSV, PNG of the same pixel size and bytes, PDF of the same page), and
``export_mjcf``/``export_json``/``export_schema`` equal ``tensegrity export …`` byte for
byte. Bad arguments raise InputError naming the argument."""

import json
import struct

import pytest

import tensegrity
from conftest import EXAMPLES
from tensegrity.errors import InputError

#: Cheap figures: a planar D-bar, a Michell spiral, the T-bar tread.
CHEAP = ["2.2", "4.1", "5.1"]


def cli_figure(cli, tmp_path, number, *flags, ext="svg"):
    out = tmp_path / "cli"
    code, _, err = cli("figures", "--out", out, "--only", number, "--quiet", *flags)
    assert code == 0, err
    stem = "fig_" + number.replace(".", "_")
    return out / f"{stem}.{ext}", out / f"{stem}.csv"


def png_size(path):
    """(width, height) of a PNG from its IHDR chunk."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


@pytest.mark.parametrize("number", CHEAP)
def test_svg_and_its_data_equal_the_cli(cli, tmp_path, number):
    svg, csv = cli_figure(cli, tmp_path, number)
    mine = tmp_path / "mine.svg"
    assert tensegrity.figure(number, mine) == str(mine)
    assert mine.read_bytes() == svg.read_bytes()
    assert (tmp_path / "mine.csv").read_bytes() == csv.read_bytes()


def test_svg_with_a_size_equals_the_cli(cli, tmp_path):
    svg, _ = cli_figure(cli, tmp_path, "5.1", "--size", "6x4in")
    mine = tmp_path / "sized.svg"
    tensegrity.figure("fig_5_1", mine, size="6x4in", data=False)
    assert mine.read_bytes() == svg.read_bytes()
    assert not (tmp_path / "sized.csv").exists()


def test_png_has_the_cli_size(cli, tmp_path):
    png, _ = cli_figure(cli, tmp_path, "5.1", "--png", "--dpi", "48", ext="png")
    mine = tmp_path / "mine.png"
    tensegrity.figure("5.1", mine, dpi=48)
    assert png_size(mine) == png_size(png)
    assert mine.stat().st_size == png.stat().st_size
    assert mine.read_bytes() == png.read_bytes()


def test_pdf_is_the_cli_page(cli, tmp_path):
    pdf, _ = cli_figure(cli, tmp_path, "2.2", "--pdf", ext="pdf")
    mine = tmp_path / "mine.pdf"
    tensegrity.figure("2.2", mine)
    data = mine.read_bytes()
    assert data.startswith(b"%PDF")
    ref = pdf.read_bytes()
    # the same page (its MediaBox), whatever the creation stamps
    box = lambda b: b[b.index(b"/MediaBox"):][:60]  # noqa: E731
    assert box(data) == box(ref)


def test_figure_catalogue_lists_the_cli_figures():
    f = tensegrity.figures()
    assert "3.10" in f and "5.2" in f
    assert all(isinstance(d, str) and d for d in f.values())


@pytest.mark.parametrize("kwargs, parameter", [
    ({"name": "9.99"}, "name"),
    ({"name": 3.1}, "name"),
    ({"size": "6 by 4"}, "size"),
    ({"dpi": 5}, "dpi"),
    ({"dpi": float("nan")}, "dpi"),
    ({"path": "figure.txt"}, "path"),
])
def test_bad_figure_arguments_are_named(tmp_path, kwargs, parameter):
    args = {"name": "5.1", "path": tmp_path / "f.svg"}
    args.update(kwargs)
    if parameter == "path":
        args["path"] = tmp_path / args["path"]
    with pytest.raises(InputError) as e:
        tensegrity.figure(**args)
    assert e.value.parameter == parameter
    assert not (tmp_path / "f.svg").exists()


SCENE = EXAMPLES / "mjcf" / "prism_pinned.toml"


def test_mjcf_equals_the_cli(cli, tmp_path):
    out = tmp_path / "cli.xml"
    code, _, err = cli("export", "mjcf", SCENE, "--out", out, "--timestep", "0.002",
                       "--ground-height", "-0.5")
    assert code == 0, err
    mine = tmp_path / "mine.xml"
    text = tensegrity.export_mjcf(str(SCENE), mine, timestep=0.002, ground_height=-0.5)
    assert mine.read_bytes() == out.read_bytes()
    assert text == out.read_text(encoding="utf-8")
    # a Structure of the same scene gives the same model but for the source's name
    s = tensegrity.Structure.from_toml(SCENE)
    same = tensegrity.export_mjcf(s, timestep=0.002, ground_height=-0.5, source=str(SCENE))
    assert same.count("<body") == text.count("<body")


def test_json_and_schema_equal_the_cli(cli, tmp_path):
    code, out, err = cli("export", "json", SCENE)
    assert code == 0, err
    assert tensegrity.export_json(SCENE) == out
    code, out, err = cli("export", "schema")
    assert code == 0, err
    path = tmp_path / "schema.json"
    schema = tensegrity.export_schema(path)
    assert path.read_text(encoding="utf-8") == out
    assert schema == json.loads(out)


def test_bad_exports_are_named(tmp_path):
    with pytest.raises(InputError) as e:
        tensegrity.export_mjcf(SCENE, timestep=-1.0)
    assert e.value.parameter == "timestep"
    with pytest.raises(InputError) as e:
        tensegrity.export_mjcf(42)
    assert e.value.parameter == "scene"
    with pytest.raises(InputError):
        tensegrity.export_json(tmp_path / "missing.toml")
