"""Progress from Python: ``progress=callback`` is called with (simulated seconds, end time),
increasing, ending at the end time; an exception it raises stops the run; ``progress=True``
without tqdm prints lines on stderr."""

import pytest

import tensegrity as tg
from conftest import EXAMPLES


def test_simulate_and_roll_report_their_progress():
    for run, t_end in ((lambda cb: tg.simulate(EXAMPLES / "prism_drop.toml", t_end=2.0,
                                               integrator="rk4", dt=1e-4,
                                               convergence_check=False, progress=cb), 2.0),
                       (lambda cb: tg.roll(fidelity="full", t_end=0.5, progress=cb), 0.5)):
        calls = []
        run(lambda done, total: calls.append((done, total)))
        assert calls, "no progress reported"
        assert all(total == t_end for _, total in calls)
        done = [d for d, _ in calls]
        assert done == sorted(done) and done[-1] == pytest.approx(t_end, abs=1e-9)


def test_an_exception_in_the_callback_stops_the_run():
    class Enough(Exception):
        pass

    def stop(done, total):
        raise Enough(done)

    with pytest.raises(Enough):
        tg.simulate(EXAMPLES / "prism_drop.toml", t_end=50.0, integrator="rk4", dt=1e-4,
                    convergence_check=False, progress=stop)


def test_progress_true_prints_lines_without_tqdm(capsys, without_tqdm):
    tg.simulate(EXAMPLES / "prism_drop.toml", t_end=0.2, convergence_check=False,
                progress=True)
    err = capsys.readouterr().err
    assert "simulate: 100 % (0.2 of 0.2 s simulated)" in err
