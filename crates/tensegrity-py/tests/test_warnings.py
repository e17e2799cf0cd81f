"""Warnings cross as data: each one a dict with its ``kind`` (a stable name), its ``message``
(the text the command line prints) and its numbers, equal to the command line's JSON."""

import tensegrity as tg
from conftest import EXAMPLES, assert_same


def test_a_drift_warning_is_a_dict_with_its_numbers(cli_json):
    scene = EXAMPLES / "prism_drop.toml"
    py = tg.simulate(scene, integrator="rk4", dt=0.01, trajectory=False)
    warnings = py["warnings"]
    assert warnings, py
    w = warnings[0]
    assert isinstance(w, dict)
    assert w["kind"] == "drift"
    assert w["invariant"] == "bar_length"
    # the warning's own numbers say why it was raised
    assert w["value"] > w["limit"] > 0.0
    assert "above the limit" in w["message"]
    assert {x["kind"] for x in warnings[1:]} == {"not_converged"}
    # not converged: the error extrapolated from the companion run exceeds the tolerance
    assert all(x["estimated_error"] > x["tolerance"] for x in warnings[1:])
    ref = cli_json("simulate", scene, "--integrator", "rk4", "--dt", "0.01")
    assert_same(py, ref)


def test_a_chaotic_quantity_carries_its_interval_as_the_cli_does(cli_json):
    """The hops of a full 3 s run on 50° are chaotic: each such quantity is a single draw with
    the 95 % interval of another run from its three draws (run, half step, twin), a list of two
    numbers that holds the run's own value (one of the draws), as in the CLI's JSON."""
    py = tg.roll(fidelity="full", t_end=3.0)
    chaotic = [q for q in py["convergence"]["quantities"] if q["status"] == "chaotic"]
    assert len(chaotic) >= 3, py["convergence"]
    for q in chaotic:
        lo, hi = q["interval"]
        assert lo <= q["value"] <= hi and lo < hi, q
        assert not q["converged"]
    assert py["valid"], py["warnings"]
    ref = cli_json("roll", "--fidelity", "full", "--t-end", "3")
    assert_same(py["convergence"], ref["convergence"])
