"""Shared fixtures: the repository root, its example scenes, and the command line to compare
with (``TENSEGRITY_CLI``, else the workspace's debug or release binary)."""

import builtins
import json
import os
import signal
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "examples"

#: Keys that hold wall-clock time: the only ones left out of a comparison with the CLI.
TIMING_KEYS = {"wall_time_s"}


def cli_path():
    env = os.environ.get("TENSEGRITY_CLI")
    if env:
        return env
    for profile in ("debug", "release"):
        p = ROOT / "target" / profile / "tensegrity"
        if p.exists():
            return str(p)
    return None


@pytest.fixture(scope="session")
def cli():
    """Runs the command line: ``cli(*args)`` → (exit code, stdout, stderr)."""
    path = cli_path()
    if path is None:
        pytest.skip("no tensegrity binary: set TENSEGRITY_CLI or build the workspace")

    def run(*args, cwd=None):
        p = subprocess.run([path, *map(str, args)], capture_output=True, text=True,
                           cwd=cwd or ROOT, timeout=600)
        return p.returncode, p.stdout, p.stderr

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    """The ``--json`` report of a CLI run (which must succeed)."""

    def run(*args):
        code, out, err = cli(*args, "--json")
        assert code == 0, err
        return json.loads(out)

    return run


def assert_same(py, ref, path="", rtol=1e-12):
    """``py`` (the package's result: numpy arrays) equals ``ref`` (the CLI's JSON): the same
    keys, numbers within ``rtol`` relative (absolute below 1)."""
    if isinstance(ref, dict):
        assert isinstance(py, dict), path
        keys = set(ref) - TIMING_KEYS
        assert set(py) - TIMING_KEYS == keys, (path, set(py) ^ set(ref))
        for k in keys:
            assert_same(py[k], ref[k], path + "." + k, rtol)
        return
    if isinstance(ref, list):
        if isinstance(py, np.ndarray):
            want = np.array([np.nan if x is None else x for x in _flat(ref)], dtype=float)
            got = py.astype(float).ravel()
            assert got.shape == want.shape, path
            scale = np.maximum(1.0, np.abs(want))
            ok = (np.abs(got - want) <= rtol * scale) | (np.isnan(got) & np.isnan(want))
            assert ok.all(), (path, got[~ok][:5], want[~ok][:5])
            return
        assert isinstance(py, list) and len(py) == len(ref), path
        for i, (a, b) in enumerate(zip(py, ref)):
            assert_same(a, b, "{}[{}]".format(path, i), rtol)
        return
    if isinstance(ref, float) or (isinstance(ref, int) and not isinstance(ref, bool)):
        assert isinstance(py, (int, float)) and not isinstance(py, bool), path
        assert abs(py - ref) <= rtol * max(1.0, abs(ref)), (path, py, ref)
        return
    assert py == ref, (path, py, ref)


def _flat(v):
    if isinstance(v, list):
        for x in v:
            yield from _flat(x)
    else:
        yield v


@pytest.fixture
def python_handles_sigint():
    """Python's own SIGINT handler (KeyboardInterrupt), as in an interactive session: a
    process started in the background by a non-interactive shell (a CI job) inherits SIGINT
    ignored, and Python then installs no handler."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


def interrupt_after(delay):
    """Sends SIGINT to this process after ``delay`` s; returns a list that receives the time
    it was sent."""
    sent = []

    def fire():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    threading.Timer(delay, fire).start()
    return sent


@pytest.fixture
def without_tqdm(monkeypatch):
    """Imports of tqdm fail, as where it is not installed."""
    real_import = builtins.__import__

    def no_tqdm(name, *args, **kwargs):
        if name.startswith("tqdm"):
            raise ImportError(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_tqdm)
