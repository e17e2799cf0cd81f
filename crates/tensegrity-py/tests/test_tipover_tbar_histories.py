"""The histories and studies of ``tipover`` and ``tbar`` from Python equal the command line's
files of the same run: ``tipover --dynamic/--rolling --out`` (the history), ``tipover --grid``
(the friction map), ``tbar roll --out`` (one row per number of treads), and the ``--json`` of
``tbar --loop-study`` and ``tbar --mass-sweep`` (the command line writes no CSV for those);
each result's scalar fields equal the CLI's ``--json``. Bad keywords raise InputError naming
the keyword. Every run is short (a few hundredths of a second of simulated time)."""

import csv
import json

import numpy as np
import pytest

import tensegrity
from conftest import assert_same
from tensegrity.errors import InputError

#: A short dynamic tip-over run: keywords and the same flags.
DYNAMIC = {"settle": 0.05, "ramp_time": 0.1, "output_dt": 0.01}
DYNAMIC_FLAGS = ["--settle", "0.05", "--ramp-time", "0.1", "--output-dt", "0.01"]
#: A short rolling lean run.
ROLLING = {"t_end": 0.05}
ROLLING_FLAGS = ["--t-end", "0.05"]
#: A short `tbar roll` over two tread counts.
TBAR_ROLL = {"treads": [8, 12], "t_end": 0.3}
TBAR_ROLL_FLAGS = ["--treads", "8,12", "--t-end", "0.3"]
#: One T-bar tread.
TBAR = {"beta": "30deg", "phi": "22.5deg", "cylindrical": 0.25}
TBAR_FLAGS = ["--beta", "30deg", "--phi", "22.5deg", "--cylindrical", "0.25"]


def cell(text):
    """A CSV cell as the package types it: a number, a flag, NaN for an empty cell, or text."""
    if text == "":
        return np.nan
    if text in ("true", "false"):
        return text == "true"
    try:
        return float(text)
    except ValueError:
        return text


def read_csv(path):
    """The CSV's columns, by header name, each a list of typed cells."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header, body = rows[0], rows[1:]
    return {name: [cell(r[j]) for r in body] for j, name in enumerate(header)}


def assert_column(py, ref, name):
    """A numpy column equals the CLI's cells (numbers to 1e-12 relative, flags, NaN for an
    empty cell)."""
    py = np.asarray(py)
    assert py.shape == (len(ref),), name
    if py.dtype == bool:
        assert py.tolist() == ref, name
        return
    ref = np.array(ref, dtype=np.float64)
    np.testing.assert_allclose(py.astype(np.float64), ref, rtol=1e-12, atol=1e-300,
                               equal_nan=True, err_msg=name)


def run_cli(cli, *args):
    code, out, err = cli(*args)
    assert code == 0, err
    return json.loads(out)


def without(result, *keys):
    return {k: v for k, v in result.items() if k not in keys}


@pytest.mark.parametrize("mode, kwargs, flags, columns", [
    ("dynamic", DYNAMIC, DYNAMIC_FLAGS, ["t", "force", "lean", "near_normal", "far_normal"]),
    ("rolling", ROLLING, ROLLING_FLAGS, ["t", "lean", "downhill", "across"]),
])
def test_tipover_history_is_the_cli_out_file(cli, tmp_path, mode, kwargs, flags, columns):
    out = tmp_path / "history.csv"
    ref = run_cli(cli, "tipover", f"--{mode}", *flags, "--out", out, "--json")
    r = tensegrity.tipover(**{mode: True}, **kwargs)
    assert type(r).__name__ == "TipoverResult"
    assert list(r.history) == columns
    table = read_csv(out)
    assert list(table) == columns
    assert len(r.history["t"]) > 3
    for name in columns:
        assert_column(r.history[name], table[name], name)
    # the scalar fields (and the convergence object) are the CLI's --json
    assert_same(without(r, "history"), ref)
    assert "convergence" in r and r.convergence is not None


def test_tipover_grid_is_the_cli_grid_file(cli, tmp_path):
    out = tmp_path / "grid.csv"
    code, _, err = cli("tipover", "--grid", out, "--grid-points", "6", "--eps-max", "0.8")
    assert code == 0, err
    r = tensegrity.tipover(grid=True, grid_points=6, eps_max=0.8)
    g = r.grid
    assert g["sigma"].shape == (6,) and g["epsilon"].shape == (6,)
    assert g["normalized_friction"].shape == (6, 6)
    table = read_csv(out)
    # the CSV's rows: σ outer, ε inner
    sigma, eps = np.meshgrid(g["sigma"], g["epsilon"], indexing="ij")
    assert_column(sigma.ravel(), table["sigma"], "sigma")
    assert_column(eps.ravel(), table["epsilon"], "epsilon")
    assert_column(g["normalized_friction"].ravel(), table["normalized_friction"],
                  "normalized_friction")
    assert r.grid_points == 6 and r.eps_max == 0.8
    # the axes are the grid's: σ = i/(n+1), ε = eps_max j/n
    np.testing.assert_allclose(g["sigma"], np.arange(1, 7) / 7, rtol=1e-15)
    np.testing.assert_allclose(g["epsilon"], 0.8 * np.arange(1, 7) / 6, rtol=1e-15)


def test_tbar_roll_table_is_the_cli_out_file_and_its_report_the_json(cli, tmp_path):
    out = tmp_path / "rows.csv"
    ref = run_cli(cli, "tbar", "roll", *TBAR_ROLL_FLAGS, "--out", out, "--json")
    r = tensegrity.tbar_roll(**TBAR_ROLL)
    table = read_csv(out)
    assert list(r.table) == list(table)
    for name in table:
        assert_column(r.table[name], table[name], name)
    # observing the first row's run changed nothing: the report is the CLI's
    assert_same(without(r, "table", "history"), ref)
    # each row carries its convergence object
    assert r.rows[0]["tbar"]["convergence"]["converged"] in (True, False)
    h = r.history
    assert list(h) == list(tensegrity._native.ROLL_HISTORY_COLUMNS)
    # every 1 ms sample of [0, t_end]
    assert len(h["t"]) == 301
    np.testing.assert_allclose(h["t"], np.arange(301) * 1e-3, atol=1e-12)
    # the wheel moves down the slope
    assert h["axle_s"][-1] > h["axle_s"][0]


def test_tbar_loop_study_is_the_cli_json(cli):
    ref = run_cli(cli, "tbar", *TBAR_FLAGS, "--loop-study", "--json")
    r = tensegrity.tbar(**TBAR, loop_study=True)
    assert type(r).__name__ == "TbarResult"
    assert_same(r.rows, ref)
    assert len(r.loop_study["structure"]) == len(ref)
    for name in ("rank", "self_stress_dim", "mechanisms", "contacts"):
        assert r.loop_study[name].tolist() == [row[name] for row in ref], name
    for name in ("in_plane", "out_of_plane", "internal", "prestress_margin"):
        assert_column(r.loop_study[name], [row[name] for row in ref], name)
    assert r.loop_study["stance"].tolist() == [row["stance"] for row in ref]


def test_tbar_mass_sweep_is_the_cli_json(cli):
    ref = run_cli(cli, "tbar", *TBAR_FLAGS, "--mass-sweep", "--sweep-complexities", "1,2",
                  "--sweep-deltas", "0.1,0.5", "--json")
    r = tensegrity.tbar(**TBAR, mass_sweep=True, sweep_complexities=[1, 2],
                        sweep_deltas=[0.1, 0.5])
    assert_same(r.rows, ref)
    m = r.mass_sweep
    assert m["complexity"].tolist() == [row["complexity"] for row in ref]
    nan = float("nan")
    for name in ("mass_kg", "michell_mass_kg", "mass_ratio", "yield_mass_kg"):
        want = [row["mass"][name] if row["mass"] else nan for row in ref]
        assert_column(m["mass." + name], want, name)
    assert_column(m["min_prestress"], [row["min_prestress"] if row["min_prestress"] is not None
                                       else nan for row in ref], "min_prestress")
    assert "mass" not in m
    assert m["note"].tolist() == [row["note"] or "" for row in ref]


@pytest.mark.parametrize("call, parameter", [
    (lambda: tensegrity.tipover(grid=True, grid_points=1), "grid_points"),
    (lambda: tensegrity.tipover(grid=True, grid_points=2.5), "grid_points"),
    (lambda: tensegrity.tipover(grid=True, eps_max=float("nan")), "eps_max"),
    (lambda: tensegrity.tipover(grid=True, eps_max=-1.0), "eps_max"),
    (lambda: tensegrity.tipover(grid=True, sides=8), "sides"),
    (lambda: tensegrity.tipover(grid_points=4), "grid_points"),
    (lambda: tensegrity.tipover(dynamic=True, settle=-1.0), "settle"),
    (lambda: tensegrity.tbar(**TBAR, mass_sweep=True, sweep_complexities=[0]),
     "sweep_complexities"),
    (lambda: tensegrity.tbar(**TBAR, mass_sweep=True, sweep_deltas=[float("inf")]),
     "sweep_deltas"),
    (lambda: tensegrity.tbar(**TBAR, sweep_deltas=[0.1]), "sweep_deltas"),
    (lambda: tensegrity.tbar(beta="30deg", phi=-1.0, cylindrical=0.25, loop_study=True), "phi"),
    (lambda: tensegrity.tbar_roll(treads=[2], t_end=0.1), "treads"),
])
def test_bad_keywords_are_named(call, parameter):
    with pytest.raises(InputError) as e:
        call()
    assert e.value.parameter == parameter


def test_modes_that_exclude_each_other_are_refused():
    with pytest.raises(TypeError):
        tensegrity.tipover(grid=True, dynamic=True)
    with pytest.raises(TypeError):
        tensegrity.tbar(**TBAR, loop_study=True, mass_sweep=True)


def test_extra_fields_are_documented():
    from tensegrity import results
    for name, field in [("tipover", "history"), ("tipover", "grid"), ("tbar_roll", "table"),
                        ("tbar_roll", "history"), ("tbar", "loop_study"),
                        ("tbar", "mass_sweep")]:
        fields = [f for f, _, _ in results.EXTRA_FIELDS[name]]
        assert field in fields, (name, field)
        assert field in results.result_class(name).__doc__
