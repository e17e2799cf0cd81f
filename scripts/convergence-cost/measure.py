#!/usr/bin/env python3
"""The convergence check's cost against the bare run (issue 48, item 3).

Runs each command with and without `--no-convergence-check`, `--repeat` times each,
alternating, and prints a markdown table of the best CPU time (user + system of the child)
and the best wall time of each, the check's extra over the bare run, and the companion and
cost the run's JSON states. Usage: measure.py BINARY [--repeat N].
"""
import json
import resource
import subprocess
import sys
import time

COMMANDS = [
    ["tbar", "roll", "--t-end", "2"],
    ["simulate", "examples/prism_drop.toml", "--integrator", "imex-ark"],
    ["simulate", "examples/anchors/motes_dbar.toml"],
    ["simulate", "examples/prism_drop.toml"],
    ["roll", "--fidelity", "rigid"],
    ["roll", "--fidelity", "full", "--t-end", "2", "--dt", "3.125e-5"],
    ["roll", "--fidelity", "full", "--t-end", "2", "--dt", "6.25e-5"],
    ["roll", "--fidelity", "full", "--t-end", "2", "--dt", "1.25e-4"],
    ["roll", "--fidelity", "full", "--t-end", "2"],
    ["roll"],
    ["tipover", "--dynamic"],
]


def timed(argv):
    """CPU seconds (user + system) and wall seconds of one run of argv."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall, done


def convergence(binary, args):
    """The companion, cost and refinement the run's JSON states."""
    out = subprocess.run([binary, *args, "--json"], stdout=subprocess.PIPE, check=True)
    report = json.loads(out.stdout)
    found = []

    def walk(node):
        if isinstance(node, dict):
            if isinstance(node.get("convergence"), dict):
                found.append(node["convergence"])
            for value in node.values():
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)

    # (`tbar roll` has one per row and wheel: the largest cost)
    walk(report)
    if not found:
        return None, None, ""
    c = max(found, key=lambda c: c.get("cost") or 0.0)
    return c.get("companion"), c.get("cost"), c.get("refinement", "")


def main():
    binary = sys.argv[1]
    repeat = int(sys.argv[sys.argv.index("--repeat") + 1]) if "--repeat" in sys.argv else 5
    print("| command | CPU with check | CPU bare | extra CPU | wall with | wall bare | extra wall | stated cost | companion |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---|")
    for args in COMMANDS:
        best = {True: [1e9, 1e9], False: [1e9, 1e9]}
        for _ in range(repeat):
            for check in (True, False):
                argv = [binary, *args] + ([] if check else ["--no-convergence-check"])
                cpu, wall, done = timed(argv)
                if done.returncode not in (0,):
                    print(f"{' '.join(args)}: exit {done.returncode}", file=sys.stderr)
                best[check][0] = min(best[check][0], cpu)
                best[check][1] = min(best[check][1], wall)
        (cw, ww), (cb, wb) = best[True], best[False]
        companion, cost, label = convergence(binary, args)
        print(
            f"| `{' '.join(args)}` | {cw:.3f} s | {cb:.3f} s | **{(cw - cb) / cb:.2f}×** "
            f"| {ww:.3f} s | {wb:.3f} s | {(ww - wb) / wb:.2f}× | {cost} | {companion}: {label[:60]} |"
        )
        sys.stdout.flush()


if __name__ == "__main__":
    main()
