"""Plots from Python (matplotlib, optional): the drawn data are the result's arrays."""

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import tensegrity as tg  # noqa: E402
from conftest import EXAMPLES  # noqa: E402


def test_simulate_plots_its_heights_and_energy():
    r = tg.simulate(EXAMPLES / "prism_drop.toml", t_end=0.5, convergence_check=False)
    ax = r.plot()
    lines = ax.get_lines()
    assert len(lines) == 6  # one per node
    np.testing.assert_array_equal(lines[2].get_xdata(), r.t)
    np.testing.assert_array_equal(lines[2].get_ydata(), r.trajectory[:, 2, 2])
    ax = r.plot("energy")
    np.testing.assert_array_equal(ax.get_lines()[1].get_ydata(), r.energy)
    with pytest.raises(KeyError, match="member_forces"):
        r.plot("forces")


def test_roll_plots_its_history():
    r = tg.roll(fidelity="rigid", t_end=1.0)
    ax = r.plot()
    np.testing.assert_array_equal(ax.get_lines()[0].get_ydata(), r.history["axle_s"])
    np.testing.assert_array_equal(ax.get_lines()[1].get_ydata(), r.history["axle_h"])


def test_a_structure_is_drawn_coloured_by_its_prestress():
    s = tg.Structure.from_toml(EXAMPLES / "prism.toml")
    prestress = tg.statics(s)["prestress"]
    ax = s.plot(forces=prestress)
    lines = ax.get_lines()
    assert len(lines) == len(s.bars) + len(s.strings)
    # bars (compression) blue-ish, strings (tension) red-ish
    bar_rgb, string_rgb = lines[0].get_color(), lines[-1].get_color()
    assert bar_rgb[2] > bar_rgb[0] and string_rgb[0] > string_rgb[2]
    with pytest.raises(ValueError, match="expected 12"):
        s.plot(forces=[1.0, 2.0])
