"""A tensegrity prism from Python: its form found (or built from numpy), its statics, a drop
onto the ground, and a plot of its fall when matplotlib is installed.

    python crates/tensegrity-py/examples/prism_drop.py [--plot prism_drop.png]
"""

import argparse

import numpy as np

import tensegrity as tg


def prism():
    """The Snelson 3-bar prism: form-found when the engine has the form-finding command,
    else from its known equilibrium (the top triangle twisted 30 degrees)."""
    if "formfind" in tg.commands():
        return tg.Structure.from_formfind(builtin="prism:3")
    a = np.radians([0.0, 120.0, 240.0])
    nodes = np.vstack([np.c_[np.cos(a), np.sin(a), np.zeros(3)],
                       np.c_[np.cos(a + np.pi / 6), np.sin(a + np.pi / 6), np.ones(3)]])
    bars = [[0, 4], [1, 5], [2, 3]]
    strings = [[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3], [0, 3], [1, 4], [2, 5]]
    return tg.Structure(nodes, bars, strings)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plot", help="save the figure here instead of showing it")
    args = parser.parse_args()

    shape = prism()
    report = tg.statics(shape)
    q = report["self_stress"][0]
    q = q / q[-1]  # scale: the last vertical string at 1
    print("rank {rank}, self-stress states {self_stress_dim}, prestressable: {prestressable} "
          "(margin {prestress_margin:.4f})".format(**report))
    print("force densities (bars, then strings):", np.round(q, 4))

    # strings 5 % shorter than their length: stiff, prestressed; dropped from 0.5 m
    length = np.linalg.norm(np.diff(shape.nodes[shape.strings], axis=1)[:, 0], axis=1)
    lifted = shape.nodes + [0.0, 0.0, 0.5 - shape.nodes[:, 2].min()]
    scene = shape.replace(
        nodes=lifted, bar_mass=1.0, stiffness=1000.0, rest_length=0.95 * length, damping=2.0,
        gravity=[0, 0, -9.81],
        ground={"point": [0, 0, 0], "normal": [0, 0, 1], "model": "penalty",
                "stiffness": 1e4, "damping": 100.0, "mu_static": 0.8, "mu_kinetic": 0.6},
        simulation={"t_end": 2.0, "integrator": "rk45", "rtol": 1e-8, "atol": 1e-10,
                    "output_interval": 0.01})
    run = tg.simulate(scene)
    t, x = run["t"], run["trajectory"]
    print("simulated {} samples of {} nodes; lowest node at the end {:.4f} m; energy drift {:.2e}"
          .format(len(t), x.shape[1], x[-1, :, 2].min(), run["energy_drift"]))

    try:
        import matplotlib
        if args.plot:
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(matplotlib is not installed: no plot)")
        return
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for i in range(x.shape[1]):
        ax1.plot(t, x[:, i, 2], label="node {}".format(i))
    ax1.set(xlabel="t [s]", ylabel="height [m]", title="the prism dropped on the ground")
    ax1.legend(fontsize=7)
    final = x[-1]
    for members, style in ((scene.bars, "k-"), (scene.strings, "r-")):
        for i, j in members:
            ax2.plot(final[[i, j], 0], final[[i, j], 2], style, lw=2 if style == "k-" else 1)
    ax2.set(xlabel="x [m]", ylabel="z [m]", title="at rest (bars black, strings red)")
    ax2.set_aspect("equal")
    fig.tight_layout()
    if args.plot:
        fig.savefig(args.plot, dpi=100)
        print("wrote", args.plot)
    else:
        plt.show()


if __name__ == "__main__":
    main()
