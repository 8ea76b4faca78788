#!/usr/bin/env python3
"""Writes scenes/valley.obj: a rough rock valley for scenes/valley.toml.

A triangulated surface (Wavefront OBJ, Y up, scene coordinates in metres) on a 2 m grid over
X in [-12, 36], Z in [-18, 18]: 24 x 18 cells, two triangles each, 864 triangles.

* Level (Y = 0) for X <= 4 m, where the monolith starts: its contacts at (-6, 5), (4, 5) and
  (4, -5) are on the ground.
* Beyond X = 4 m the floor rises at 20 degrees towards +X (as the paper's plane 1), and the
  valley's sides rise at 25 degrees beyond |Z| = 10 m.
* From X = 8 m on, every grid point is moved up or down by up to 0.15 m by a fixed
  pseudo-random hash: a rough surface with small ridges and hollows.

Standard library only; the same file every time. Run from the repository root:
    python3 scenes/make_valley.py
"""

import math
import os

X0, Z0, STEP, NX, NZ = -12.0, -18.0, 2.0, 24, 18
ROUGH = 0.15


def noise(i, j):
    """A fixed pseudo-random number in [-1, 1] for grid point (i, j)."""
    h = (i * 73856093) ^ (j * 19349663) ^ 0x5BD1E995
    h = (h * 2654435761) % (1 << 32)
    return (h / float(1 << 32)) * 2.0 - 1.0


def height(i, j):
    x, z = X0 + i * STEP, Z0 + j * STEP
    y = math.tan(math.radians(20.0)) * max(0.0, x - 4.0)
    y += math.tan(math.radians(25.0)) * max(0.0, abs(z) - 10.0) * (1.0 if x > 4.0 else 0.0)
    if x >= 8.0:
        y += ROUGH * noise(i, j)
    return x, y, z


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.join(here, "valley.obj")
    lines = [
        "# valley.obj: a rough rock valley, written by scenes/make_valley.py (do not edit).",
        "# Y up, scene coordinates (m). %d triangles." % (2 * NX * NZ),
    ]
    for i in range(NX + 1):
        for j in range(NZ + 1):
            lines.append("v %.9f %.9f %.9f" % height(i, j))

    def vid(i, j):
        return i * (NZ + 1) + j + 1

    for i in range(NX):
        for j in range(NZ):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            lines.append("f %d %d %d" % (a, b, c))
            lines.append("f %d %d %d" % (a, c, d))
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, path)
    print("wrote", path)


if __name__ == "__main__":
    main()
