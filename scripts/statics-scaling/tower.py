"""The free tower of N Snelson prisms as a scene (examples/tower200.toml continued): rings of 3
nodes twisted pi/6 a level, per stage 3 bars, 3 vertical and 3 ring strings (9 N + 3 members).

    python3 scripts/statics-scaling/tower.py N > towerN.toml

Used by scripts/statics-scaling/run.sh and scripts/peers-side-by-side/side_by_side.py."""
import math
import sys


def tower_toml(n):
    """The scene's TOML text for a tower of `n` prisms."""
    out = ["nodes = ["]
    for i in range(n + 1):
        for j in range(3):
            a = 2 * math.pi * j / 3 + i * math.pi / 6
            out.append(f"  [{math.cos(a)!r}, {math.sin(a)!r}, {float(i)!r}],")
    out.append("]")
    for i in range(n):
        for j in range(3):
            out.append(f"[[bars]]\nnodes = [{3*i+j}, {3*(i+1)+(j+1)%3}]\nmass = 0.5")
    for i in range(n + 1):
        for j in range(3):
            if i < n:
                out.append(f"[[strings]]\nnodes = [{3*i+j}, {3*(i+1)+j}]\nstiffness = 2000.0")
            out.append(f"[[strings]]\nnodes = [{3*i+j}, {3*i+(j+1)%3}]\nstiffness = 2000.0")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    sys.stdout.write(tower_toml(int(sys.argv[1])))
