"""Ctrl-C: a real SIGINT sent to the process during a ~10-second computation returns control
within 0.5 s (the issue's requirement: the engine runs with the GIL released and the caller
checks for signals every 50 ms, then gives a stopping command 0.3 s), raising
``tensegrity.Interrupted`` — a ``KeyboardInterrupt`` — with the results so far, as the
command line keeps them; the next call runs normally (the stop flag is cleared)."""

import signal
import time

import numpy as np
import pytest

import tensegrity as tg
from conftest import EXAMPLES, interrupt_after

pytestmark = [
    pytest.mark.skipif(not hasattr(signal, "pthread_kill"), reason="POSIX signals"),
    # Python's own SIGINT handler, which a CI job's background process lacks (conftest)
    pytest.mark.usefixtures("python_handles_sigint"),
]

#: The limit the issue sets on the time from Ctrl-C to control back in Python.
LIMIT_S = 0.5


def long_simulation(**kwargs):
    # about 10 s on one core: 3.5 million RK4 steps of the dropped prism
    return tg.simulate(EXAMPLES / "prism_drop.toml", t_end=35.0, integrator="rk4", dt=1e-5,
                       max_work=1e6, **kwargs)


def test_simulation_stops_within_half_a_second_with_the_samples_so_far():
    sent = interrupt_after(1.0)
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt) as e:
        long_simulation()
    back = time.monotonic()
    assert sent, "the computation ended before the signal"
    assert back - sent[0] < LIMIT_S, back - sent[0]
    assert back - start < 5.0
    assert isinstance(e.value, tg.Interrupted)
    partial = e.value.partial
    t, x = partial["t"], partial["trajectory"]
    assert 0 < len(t) < 3501 and x.shape == (len(t), 6, 3)  # the scene samples every 10 ms
    assert np.all(np.diff(t) > 0) and t[-1] < 35.0
    # the flag is cleared: the next call runs to its end
    r = tg.simulate(EXAMPLES / "prism_drop.toml", t_end=0.05)
    assert r["t"][-1] == pytest.approx(0.05)


def test_sweep_stops_with_the_rows_so_far_kept_in_its_file(tmp_path):
    # RK4 at 1e-4 s: the sweep must outlast the interrupt at 1 s (the default IMEX runs it in
    # about that time)
    spec = {"study": "roll", "fixed": {"fidelity": "full", "t_end": 0.5, "integrator": "rk4"},
            "axes": {"sides": list(range(6, 16))}}
    out = tmp_path / "rows.csv"
    sent = interrupt_after(1.0)
    with pytest.raises(tg.Interrupted) as e:
        tg.sweep(spec, threads=1, out=out)
    back = time.monotonic()
    assert sent and back - sent[0] < LIMIT_S, back - sent[0]
    rows = e.value.partial
    assert 0 < len(rows["case"]) < 10
    assert rows["case"].tolist() == list(range(len(rows["case"])))
    # the case in progress ends on its thread, then the sweep writes its trailer, as the
    # command line's does (`# incomplete: … run the sweep again with resume`)
    deadline = time.monotonic() + 30
    while "# incomplete" not in out.read_text() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert "# incomplete" in out.read_text()
    # resume finishes the file, as `tensegrity sweep --resume` does
    done = tg.sweep(spec, threads=2, out=out, resume=True)
    assert done["case"].tolist() == list(range(10))


def test_a_command_that_cannot_stop_early_still_returns_control():
    # the dynamic tip-over run does not poll the stop flag: control comes back at once, the
    # run's result is dropped
    sent = interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        tg.tipover(dynamic=True)  # about 3 s
    back = time.monotonic()
    assert sent and back - sent[0] < LIMIT_S
    assert tg.toroid(sides=6)["rank"] > 0
