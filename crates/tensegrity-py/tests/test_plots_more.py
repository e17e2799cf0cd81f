"""Every result's ``plot()`` (matplotlib, optional): what is drawn is the result's own data,
to the bit: the lines' data are its arrays, a structure's segments its members at its nodes,
each member's colour its force on the diverging map."""

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

import tensegrity as tg  # noqa: E402
from conftest import EXAMPLES  # noqa: E402
from tensegrity import _stubgen  # noqa: E402
from tensegrity.results import wrap  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def assert_structure_drawn(ax, nodes, members, forces):
    """One segment per member (bars, then strings) from node to node, coloured by its force
    on RdBu_r scaled by the largest |force| (Structure.plot's colouring)."""
    lines = ax.get_lines()
    assert len(lines) == len(members)
    forces = np.asarray(forces, dtype=np.float64)[:len(members)]
    scale = np.abs(forces).max()
    cmap = matplotlib.colormaps["RdBu_r"]
    for line, (i, j), f in zip(lines, members, forces):
        np.testing.assert_array_equal(np.array(line.get_data_3d()).T, np.asarray(nodes)[[i, j]])
        assert tuple(line.get_color()) == cmap(0.5 + 0.5 * f / scale)


def tension_and_compression_differ(ax, forces):
    """A compressed member is drawn blue-ish, a tensioned one red-ish."""
    forces = np.asarray(forces)
    lines = ax.get_lines()
    c = lines[int(np.argmin(forces))].get_color()
    t = lines[int(np.argmax(forces))].get_color()
    assert forces.min() < 0 < forces.max()
    assert c[2] > c[0] and t[0] > t[2] and tuple(c) != tuple(t)


# --- structures ---------------------------------------------------------------------------


def test_statics_draws_the_scene_coloured_by_its_prestress():
    path = EXAMPLES / "prism.toml"
    s = tg.Structure.from_toml(path)
    r = tg.statics(path)
    for given in (path, str(path), s):
        ax = r.plot(given)
        assert_structure_drawn(ax, s.nodes, list(s.bars) + list(s.strings), r.prestress)
        tension_and_compression_differ(ax, r.prestress)
        assert ax.get_title() == ""
    assert len(ax.figure.axes) == 2  # the axes and the colour bar


def test_statics_of_a_loaded_scene_is_coloured_by_its_load_forces_and_says_not_prestressable():
    path = EXAMPLES / "column.toml"
    s = tg.Structure.from_toml(path)
    r = tg.statics(path)
    assert r.prestressable is False and "prestress" not in r
    ax = r.plot(s)
    assert_structure_drawn(ax, s.nodes, list(s.bars) + list(s.strings), r.member_force)
    assert "not prestressable" in ax.get_title()


def test_a_report_without_connectivity_plots_the_structure_of_its_own_call():
    # statics, toroid and formfind keep the call's arguments: plot() needs nothing more
    path = EXAMPLES / "prism.toml"
    s = tg.Structure.from_toml(path)
    r = tg.statics(path)
    assert_structure_drawn(r.plot(), s.nodes, list(s.bars) + list(s.strings), r.prestress)
    t = tg.toroid(sides=6)
    wheel = tg.Structure.toroid(sides=6)
    assert_structure_drawn(t.plot(), wheel.nodes, list(wheel.bars) + list(wheel.strings),
                           t.prestress_member_force)
    f = tg.formfind(builtin="prism:3")
    form = tg.Structure.from_formfind(builtin="prism:3")
    assert_structure_drawn(f.plot(), f.nodes, list(form.bars) + list(form.strings),
                           f.member_force)
    # a report rebuilt from a plain dict has no call: then the structure must be given
    bare = wrap("statics", dict(r))
    with pytest.raises(TypeError, match="pass the structure"):
        bare.plot()


def test_a_result_that_keeps_its_call_s_arguments_draws_their_structure():
    path = EXAMPLES / "prism.toml"
    s = tg.Structure.from_toml(path)
    r = wrap("statics", dict(tg.statics(path)), inputs={"scene": str(path), "modes": None})
    assert "_inputs" not in r and set(r) == set(tg.statics(path))
    assert_structure_drawn(r.plot(), s.nodes, list(s.bars) + list(s.strings), r.prestress)
    kw = {"sides": 6, "max_memory": None}
    t = wrap("toroid", dict(tg.toroid(sides=6)), inputs=kw)
    wheel = tg.Structure.toroid(sides=6)
    assert_structure_drawn(t.plot(), wheel.nodes, list(wheel.bars) + list(wheel.strings),
                           t.prestress_member_force)


def test_toroid_draws_the_wheel_coloured_by_its_prestress():
    r = tg.toroid(sides=6)
    wheel = tg.Structure.toroid(sides=6)
    members = list(wheel.bars) + list(wheel.strings)
    assert len(members) == len(r.prestress_member_force) == r.bars + r.strings
    ax = r.plot(wheel)
    assert_structure_drawn(ax, wheel.nodes, members, r.prestress_member_force)
    tension_and_compression_differ(ax, r.prestress_member_force)


def test_formfind_draws_the_form_found_at_its_nodes():
    r = tg.formfind(builtin="prism:3")
    s = tg.Structure.from_formfind(builtin="prism:3")
    members = list(s.bars) + list(s.strings)
    assert len(members) == r.bar_count + r.string_count
    ax = r.plot(s)
    assert_structure_drawn(ax, r.nodes, members, r.member_force)
    tension_and_compression_differ(ax, r.member_force)
    assert np.array_equal(np.sign(r.member_force), np.sign(r.force_density))
    kept = wrap("formfind", dict(r), inputs={"builtin": "prism:3", "analyse": None})
    assert_structure_drawn(kept.plot(), r.nodes, members, r.member_force)


def test_tbar_draws_its_tread_coloured_by_its_prestress():
    r = tg.tbar(beta="pi/6", phi="pi/8", spherical="pi/24", wheel=True)
    members = r.bar_nodes.tolist() + r.string_nodes.tolist()
    assert len(members) == r.bars + r.strings == len(r.prestress_force)
    ax = r.plot()
    assert_structure_drawn(ax, r.node_coordinates, members, r.prestress_force)
    tension_and_compression_differ(ax, r.prestress_force)
    with pytest.raises(ValueError, match="no structure"):
        tg.tbar(beta="pi/6", phi="pi/8", cylindrical=0.25, loop_study=True).plot()


def test_michell_draws_its_truss_by_tension_and_compression():
    r = tg.michell(complexity=3, cylindrical=0.25, beta="pi/6", phi="22.5deg")
    at = {tuple(n["index"]): k for k, n in enumerate(r.nodes)}
    bars = [m for m in r.members if m["kind"] == "bar"]
    others = [m for m in r.members if m["kind"] != "bar"]
    members = [[at[tuple(m["parent"])], at[tuple(m["child"])]] for m in bars + others]
    forces = [m["force"] for m in bars + others]
    ax = r.plot()
    assert len(ax.get_lines()) == len(r.members) == 30
    assert_structure_drawn(ax, [n["position"] for n in r.nodes], members, forces)
    tension_and_compression_differ(ax, forces)
    assert all(line.get_linewidth() == 2.5 for line in ax.get_lines()[:len(bars)])
    assert all(line.get_linewidth() == 1.0 for line in ax.get_lines()[len(bars):])


# --- histories, maps and paths ---------------------------------------------------------


def test_tbar_roll_plots_its_history_as_roll_does():
    r = tg.tbar_roll(treads=[4], t_end=0.5)
    ax = r.plot()
    h = r.history
    lines = ax.get_lines()
    np.testing.assert_array_equal(lines[0].get_xdata(), h["t"])
    np.testing.assert_array_equal(lines[0].get_ydata(), h["axle_s"])
    np.testing.assert_array_equal(lines[1].get_ydata(), h["axle_h"])
    right = ax.figure.axes[1].get_lines()
    np.testing.assert_array_equal(right[0].get_ydata(), h["normal_N"])
    np.testing.assert_array_equal(right[1].get_ydata(), h["tangential_N"])


def test_tipover_dynamic_plots_the_lean_and_the_forces():
    r = tg.tipover(dynamic=True)
    h = r.history
    ax = r.plot()
    (lean,) = ax.get_lines()
    np.testing.assert_array_equal(lean.get_xdata(), h["t"])
    np.testing.assert_array_equal(lean.get_ydata(), h["lean"])
    right = ax.figure.axes[1].get_lines()
    assert [line.get_ydata().tolist() for line in right] == [
        h[c].tolist() for c in ("force", "near_normal", "far_normal")]
    assert ax.get_ylabel() == "rad" and ax.figure.axes[1].get_ylabel() == "N"


def test_tipover_rolling_plots_the_lean_and_the_hub_s_travel():
    r = tg.tipover(rolling=True, t_end=1.0)
    h = r.history
    ax = r.plot()
    np.testing.assert_array_equal(ax.get_lines()[0].get_ydata(), h["lean"])
    right = ax.figure.axes[1].get_lines()
    np.testing.assert_array_equal(right[0].get_ydata(), h["downhill"])
    np.testing.assert_array_equal(right[1].get_ydata(), h["across"])
    assert ax.figure.axes[1].get_ylabel() == "m"


def test_tipover_grid_is_drawn_as_its_map_over_sigma_and_epsilon():
    r = tg.tipover(grid=True, grid_points=5)
    g = r.grid
    ax = r.plot()
    (mesh,) = ax.collections
    drawn = np.asarray(mesh.get_array()).reshape(5, 5)  # rows ε, columns σ
    np.testing.assert_array_equal(drawn, g["normalized_friction"].T)
    x0, x1 = ax.get_xlim()
    assert x0 < g["sigma"][0] and g["sigma"][-1] < x1
    with pytest.raises(ValueError, match="nothing to plot"):
        tg.tipover(sides=16, sigma=0.5).plot()


def test_solve_plots_its_load_path_with_the_limit_points():
    r = tg.solve(EXAMPLES / "von_mises.toml", target=2.0)
    points = r.path["points"]
    ax = r.plot()
    path, limits = ax.get_lines()
    np.testing.assert_array_equal(path.get_xdata(), [p["max_displacement"] for p in points])
    np.testing.assert_array_equal(path.get_ydata(), [p["lambda"] for p in points])
    assert len(path.get_xdata()) == r.points
    events = r.path["events"]
    assert limits.get_label() == "limit point" and len(events) == r.limit_points == 2
    np.testing.assert_array_equal(limits.get_ydata(), [e["lambda"] for e in events])
    assert limits.get_ydata()[0] == r.first_limit_load_factor
    assert ax.get_title() == ""


def test_sweep_plots_one_line_per_group_with_the_csv_s_values(tmp_path):
    spec = {"study": "tipover", "axes": {"sigma": [0.3, 0.6],
                                         "epsilon": {"from": 0.25, "to": 0.75, "step": 0.25}}}
    out = tmp_path / "rows.csv"
    r = tg.sweep(spec, threads=1, out=out)
    ax = r.plot("epsilon", "critical_lateral_force", group="sigma")
    lines = ax.get_lines()
    assert [line.get_label() for line in lines] == ["sigma = 0.3", "sigma = 0.6"]
    assert ax.get_xlabel() == "epsilon" and ax.get_ylabel() == "critical_lateral_force [N]"
    back = tg.read_rows(out)
    for line, k in zip(lines, (slice(0, 3), slice(3, 6))):
        np.testing.assert_array_equal(line.get_xdata(), back["epsilon"][k])
        np.testing.assert_array_equal(line.get_ydata(), back["critical_lateral_force"][k])
    (one,) = r.plot("case", "mass_kg").get_lines()
    np.testing.assert_array_equal(one.get_ydata(), r.mass_kg)
    with pytest.raises(KeyError, match="nope"):
        r.plot("sigma", "nope")


def test_every_plot_is_in_the_stubs():
    text = _stubgen.stubs()
    for name in ("Statics", "Simulate", "Toroid", "Roll", "Tipover", "Michell", "Tbar",
                 "TbarRoll", "Formfind", "Solve"):
        cls = getattr(tg.results, name + "Result")
        assert callable(cls.plot), name
        block = text.split(f"class {name}Result(Result):")[1].split("\nclass ")[0]
        assert "    def plot(self" in block, name
    block = text.split("class SweepResult(Result):")[1].split("\nclass ")[0]
    assert "def plot(self, x: str, y: str" in block

