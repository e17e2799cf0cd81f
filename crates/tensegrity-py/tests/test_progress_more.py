"""Progress of the other long calls and the sweep's rows as objects (issue 46).

``progress=callback`` on ``tbar_roll`` (simulated seconds over every row's T-bar run, total:
tread counts × t_end), ``tipover`` with ``dynamic`` or ``rolling`` (simulated seconds, total:
the run's end time; paced by the estimate until the run ends, then the last sample's time)
and ``sweep`` (cases written, total: the cases): the callback is called, ``done`` never
decreases, ends at the total (or the run's end time) and the results are the same to the bit
with and without a callback. A bad ``progress`` is a TypeError naming the keyword.

``sweep`` returns a SweepResult: still the dict of numpy columns, with ``rows()``/``row(k)``
giving one object per row whose cells equal the CLI's CSV cells of the same spec, and
``columns`` the names with the units of the CLI's ``# units:`` line."""

import csv
import math
import time
import tomllib

import numpy as np
import pytest

import tensegrity as tg
from conftest import EXAMPLES, ROOT, interrupt_after

SWEEPS = ROOT / "examples" / "sweeps"

#: A short `tbar roll` over two tread counts (rigid model: fractions of a second).
TBAR_ROLL = {"treads": [8, 12], "t_end": 0.3}
#: The same over the default 10 s (rigid model: about a second, reported as it goes).
TBAR_ROLL_LONG = {"treads": [8, 12], "t_end": 10.0}
#: A T-bar roll of about 2 s in a release build (0.2 s for TBAR_ROLL_LONG), to be interrupted.
TBAR_ROLL_INTERRUPTED = {"treads": [8, 12, 16, 24], "t_end": 30.0}
#: A short dynamic tip-over ramp (0.3 s simulated).
DYNAMIC = {"settle": 0.05, "ramp_time": 0.25, "output_dt": 0.01}
#: A short rolling lean run.
ROLLING = {"t_end": 0.05}


def recorder():
    """A progress callback and the list of the ``(done, total)`` it was given."""
    calls = []

    def callback(done, total):
        assert isinstance(done, float) and isinstance(total, float)
        calls.append((done, total))

    return callback, calls


def assert_progress(calls, total, end=None):
    """Called at least once, every total the same, ``done`` non-decreasing within
    [0, total], the last ``done`` the total (``end``: the run's end time, to 1e-12)."""
    assert calls, "no progress reported"
    assert {t for _, t in calls} == {total}, calls
    done = [d for d, _ in calls]
    assert all(b >= a for a, b in zip(done, done[1:])), done
    assert 0.0 <= done[0] and done[-1] <= total * (1 + 1e-12), done
    if end is None:
        assert done[-1] == total, done
    else:
        assert abs(done[-1] - end) <= 1e-12, (done[-1], end)
        assert abs(end - total) <= 1e-12 * max(1.0, total), (end, total)


def assert_identical(a, b, path="", skip=("wall_time_s",)):
    """Two results the same to the bit (NaN equal to NaN), wall-clock times left out."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), path
        for k in a:
            if k not in skip:
                assert_identical(a[k], b[k], f"{path}.{k}", skip)
    elif isinstance(a, (list, tuple)):
        assert isinstance(b, (list, tuple)) and len(a) == len(b), path
        for k, (x, y) in enumerate(zip(a, b)):
            assert_identical(x, y, f"{path}[{k}]", skip)
    elif isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray) and a.dtype == b.dtype and a.shape == b.shape, path
        if a.dtype.kind == "f":
            assert np.array_equal(a.view(np.uint64), b.view(np.uint64)), path
        else:
            assert np.array_equal(a, b), path
    elif isinstance(a, float):
        assert isinstance(b, float), path
        assert a == b or (math.isnan(a) and math.isnan(b)), (path, a, b)
    else:
        assert a == b, (path, a, b)


# --- tbar_roll ----------------------------------------------------------------------------


def test_tbar_roll_reports_simulated_seconds_over_every_row():
    for kwargs in (TBAR_ROLL, TBAR_ROLL_LONG):
        callback, calls = recorder()
        start = time.monotonic()
        with_cb = tg.tbar_roll(progress=callback, **kwargs)
        elapsed = time.monotonic() - start
        t_end = kwargs["t_end"]
        total = len(kwargs["treads"]) * t_end
        assert_progress(calls, total)
        without = tg.tbar_roll(**kwargs)
        assert_identical(dict(with_cb), dict(without))
        assert [r["treads"] for r in with_cb["rows"]] == kwargs["treads"]
    # the long run is counted as it goes (calls at most every 50 ms): a run that took a few
    # ticks reports a time inside the rows, not only their ends
    done = [d for d, _ in calls]
    assert all(0 <= d <= total for d in done), done
    if elapsed > 0.5:
        assert any(0 < d < total and d % t_end != 0 for d in done), (elapsed, done)


def test_tbar_roll_with_a_callback_is_the_cli_table(cli, tmp_path):
    """The rows run one tread count at a time under a callback are the CLI's rows."""
    out = tmp_path / "rows.csv"
    code, _, err = cli("tbar", "roll", "--treads", "8,12", "--t-end", "0.3", "--out", out)
    assert code == 0, err
    with open(out, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    header, body = rows[0], rows[1:]
    table = tg.tbar_roll(progress=lambda d, t: None, **TBAR_ROLL)["table"]
    for j, name in enumerate(header):
        for k, r in enumerate(body):
            x = table[name][k]
            assert_cell(x.item() if isinstance(x, np.generic) else x, r[j], f"{name}[{k}]")


# --- tipover --------------------------------------------------------------------------------


@pytest.mark.parametrize("mode, kwargs, t_end", [
    ("dynamic", DYNAMIC, DYNAMIC["settle"] + DYNAMIC["ramp_time"]),
    ("rolling", ROLLING, ROLLING["t_end"]),
])
def test_tipover_timed_runs_report_their_simulated_time(mode, kwargs, t_end):
    callback, calls = recorder()
    with_cb = tg.tipover(**{mode: True}, progress=callback, **kwargs)
    end = float(with_cb["history"]["t"][-1])
    assert_progress(calls, t_end, end=end)
    # while the run goes on, done stays below 99 % of the end time (paced by the estimate)
    assert all(d <= 0.99 * t_end for d, _ in calls[:-1])
    without = tg.tipover(**{mode: True}, **kwargs)
    assert_identical(dict(with_cb), dict(without))


def test_tipover_progress_is_for_the_timed_runs_only():
    with pytest.raises(TypeError, match="progress"):
        tg.tipover(progress=lambda d, t: None)
    with pytest.raises(TypeError, match="progress"):
        tg.tipover(grid=True, grid_points=2, progress=True)
    # None and False are no progress, as for every call
    assert tg.tipover(progress=None)["rho"] == tg.tipover(progress=False)["rho"]


# --- sweep ----------------------------------------------------------------------------------


def small_spec(name, axes, fixed=None):
    """The example spec ``name`` of examples/sweeps with its ``axes`` (and ``fixed``) cut."""
    spec = tomllib.loads((SWEEPS / name).read_text())
    spec["axes"] = axes
    if fixed is not None:
        spec["fixed"] = fixed
    return spec


TOROID = small_spec("toroid_n_small.toml",
                    {"stabilize": ["spokes,inner", "inner,outer"], "sides": [6, 8, 12]})
ROLL = small_spec("roll_n_slope.toml",
                  {"sides": [6, 8], "incline": ["10deg", "30deg"], "outer_tread": [0.4]},
                  {"fidelity": "rigid", "t_end": 0.5})


def test_sweep_reports_the_cases_written():
    callback, calls = recorder()
    with_cb = tg.sweep(TOROID, threads=2, progress=callback)
    assert_progress(calls, 6.0)
    assert all(float(d).is_integer() for d, _ in calls)
    without = tg.sweep(TOROID, threads=1)
    assert_identical(with_cb.to_dict(), without.to_dict())


def test_sweep_resumed_counts_the_rows_already_in_the_file(tmp_path):
    out = tmp_path / "rows.csv"
    tg.sweep(TOROID, out=out)
    callback, calls = recorder()
    tg.sweep(TOROID, out=out, resume=True, progress=callback)
    # nothing left to run: the start (6 of 6) is the only report
    assert_progress(calls, 6.0)


def test_sweep_progress_true_prints_lines_without_tqdm(capsys, without_tqdm):
    tg.sweep(TOROID, threads=1, progress=True)
    assert "sweep: 100 % (6 of 6 cases)" in capsys.readouterr().err


@pytest.mark.parametrize("call", [
    lambda p: tg.sweep(TOROID, progress=p),
    lambda p: tg.tbar_roll(progress=p, **TBAR_ROLL),
    lambda p: tg.tipover(dynamic=True, progress=p, **DYNAMIC),
    lambda p: tg.simulate(EXAMPLES / "prism_drop.toml", t_end=0.01, progress=p),
    lambda p: tg.roll(t_end=0.01, progress=p),
])
@pytest.mark.parametrize("bad", [1, "yes", 0.5, [True]])
def test_a_bad_progress_is_a_type_error_naming_the_keyword(call, bad):
    with pytest.raises(TypeError, match=r"progress = "):
        call(bad)


def test_an_exception_in_the_sweep_callback_stops_it(tmp_path):
    class Enough(Exception):
        pass

    def stop(done, total):
        raise Enough(done)

    spec = small_spec("roll_n_slope.toml", {"sides": [6, 7, 8, 9]},
                      {"fidelity": "full", "t_end": 0.2})
    with pytest.raises(Enough):
        tg.sweep(spec, threads=1, out=tmp_path / "rows.csv", progress=stop)
    # the stop flag is cleared: the next call runs
    assert len(tg.sweep(TOROID, threads=1)["case"]) == 6


# --- sweep rows as objects ------------------------------------------------------------------


def assert_cell(value, text, where):
    """A row's Python scalar equals the CSV cell ``text`` (numbers to 1e-12 relative, an
    empty cell NaN or "")."""
    if isinstance(value, bool):
        assert text == ("true" if value else "false"), (where, value, text)
        return
    if text == "":
        assert value == "" or (isinstance(value, float) and math.isnan(value)), (where, value)
        return
    try:
        x = float(text)
    except ValueError:
        assert isinstance(value, str) and value == text, (where, value, text)
        return
    assert isinstance(value, (int, float)) and not isinstance(value, bool), (where, value)
    if text.lstrip("-").isdigit():
        assert value == int(text), (where, value, text)
    assert abs(value - x) <= 1e-12 * max(1.0, abs(x)), (where, value, text)


@pytest.mark.parametrize("spec", [TOROID, ROLL], ids=["toroid_n_small", "roll_n_slope"])
def test_sweep_rows_are_the_cli_csv_cells(cli, tmp_path, spec):
    path = tmp_path / "spec.toml"
    path.write_text(tg._native.toml_text(spec))
    out = tmp_path / "cli.csv"
    code, _, err = cli("sweep", path, "--out", out, "--units", "--quiet", "--threads", "2")
    assert code == 0, err
    with open(out, newline="", encoding="utf-8") as f:
        lines = list(f)
    units = next(csv.reader([lines[0][len("# units:"):].strip()]))
    rows = list(csv.reader(line for line in lines if not line.startswith("#")))
    header, body = rows[0], rows[1:]

    r = tg.sweep(path, threads=2)
    assert isinstance(r, tg.SweepResult) and isinstance(r, tg.Result)
    # the dict of columns as before, and its plain dict
    assert list(r) == header and type(r.to_dict()) is dict and list(r.to_dict()) == header
    assert r["case"].tolist() == list(range(len(body)))
    # the columns with the CLI's units line
    assert [name for name, _ in r.columns] == header
    assert [u or "-" for _, u in r.columns] == units
    assert any(u is not None for _, u in r.columns)
    # one object per row, its cells the CSV's
    objs = r.rows()
    assert len(objs) == len(body)
    for k, (obj, cells) in enumerate(zip(objs, body)):
        assert isinstance(obj, tg.SweepRow) and list(obj) == header
        for name, text in zip(header, cells):
            assert_cell(obj[name], text, f"row {k} {name}")
            assert type(obj[name]) in (int, float, str), (name, type(obj[name]))
        assert obj.case == k and obj["status"] == obj.status
    assert_identical(r.row(-1), objs[-1])
    assert_identical(r.row(0), objs[0])
    with pytest.raises(IndexError):
        r.row(len(body))
    # the file read back has the same rows and units
    back = tg.read_rows(out)
    assert back.columns == r.columns
    assert_identical(back.rows(), objs)


# --- Ctrl-C with a callback -----------------------------------------------------------------


@pytest.mark.skipif(not hasattr(__import__("signal"), "pthread_kill"), reason="POSIX signals")
def test_ctrl_c_still_stops_a_sweep_and_a_tbar_roll_with_a_callback(python_handles_sigint,
                                                                       tmp_path):
    spec = small_spec("roll_n_slope.toml", {"sides": list(range(6, 16))},
                      {"fidelity": "full", "t_end": 0.5, "integrator": "rk4"})
    callback, calls = recorder()
    sent = interrupt_after(1.0)
    with pytest.raises(tg.Interrupted) as e:
        tg.sweep(spec, threads=1, out=tmp_path / "rows.csv", progress=callback)
    back = time.monotonic()
    assert sent and back - sent[0] < 0.5, back - sent[0]
    rows = e.value.partial
    assert isinstance(rows, tg.SweepResult) and 0 < len(rows["case"]) < 10
    # what was reported never passed what was written
    assert all(d <= len(rows["case"]) for d, _ in calls)

    sent = interrupt_after(0.3)
    with pytest.raises(KeyboardInterrupt):
        tg.tbar_roll(progress=lambda d, t: None, **TBAR_ROLL_INTERRUPTED)
    back = time.monotonic()
    assert sent and back - sent[0] < 0.5, back - sent[0]
    # the next call runs
    assert len(tg.sweep(TOROID, threads=1, progress=lambda d, t: None)["case"]) == 6
