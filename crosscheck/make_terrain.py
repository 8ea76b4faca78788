#!/usr/bin/env python3
"""Writes triangulated grounds (Wavefront OBJ, Y up, scene coordinates in metres) for the
whole-body scenes of scenes/body/ and drake_body.py.

Kinds (each a height field on a grid of X and Z lines, two triangles a cell):

* rough: a surveyed-style rough rock surface: 2 m cells over X in [-24, 40], Z in [-20, 20];
  the mean surface dips downstream (towards +X) at --dip degrees (default 2), and every cell's
  slope differs from it by a few degrees: each grid point is moved up or down by a seeded,
  smoothed random amount (one pass of a 3 x 3 average over uniform numbers, scaled so that the
  cells' slopes are within about --slope degrees, default 4, of the mean dip).
* bump: level ground with a ridge of two faces rising at --ridge-deg (default 8) over
  --half-width m (default 1) each side of the crest line X = --at (default -1, the middle of the
  default frame's footprint, x' from -6 to 4), the crest parallel to Z: the ground of a bump under
  the middle of a base. Grid lines every 2 m plus the crest and the ridge's feet.
* step: level ground Y = 0 up to X = --at (default 1), then a riser down to Y = -(--drop)
  (default 0.3 m) over --run m (default 0.05: a riser of 80.5 degrees), level beyond: a face
  0.3 m lower beyond X. (A ground of [[foundation.plane]] faces is the highest of them, a convex
  function of (X, Z); a step down is not convex, so it has to be a surface.)

Standard library only; the same file for the same arguments. From the repository root:
    python3 crosscheck/make_terrain.py rough --seed 7 --out scenes/body/rough.obj
    python3 crosscheck/make_terrain.py bump --out scenes/body/bump.obj
    python3 crosscheck/make_terrain.py step --out scenes/body/step.obj
"""

import argparse
import math
import os
import random

X0, X1, Z0, Z1, STEP = -24.0, 40.0, -20.0, 20.0, 2.0


def lines(a, b, step, extra=()):
    n = int(round((b - a) / step))
    xs = {round(a + k * step, 9) for k in range(n + 1)}
    xs.update(round(x, 9) for x in extra if a < x < b)
    return sorted(xs)


def rough(a):
    xs, zs = lines(X0, X1, STEP), lines(Z0, Z1, STEP)
    rng = random.Random(a.seed)
    u = [[rng.uniform(-1.0, 1.0) for _ in zs] for _ in xs]
    # One pass of a 3 x 3 average: neighbouring points move together, as on surveyed rock.
    s = [[0.0] * len(zs) for _ in xs]
    for i in range(len(xs)):
        for j in range(len(zs)):
            near = [u[k][m] for k in range(max(0, i - 1), min(len(xs), i + 2))
                    for m in range(max(0, j - 1), min(len(zs), j + 2))]
            s[i][j] = sum(near) / len(near)
    # Scale so that the steepest difference between neighbours is STEP * tan(slope).
    diff = max(max(abs(s[i + 1][j] - s[i][j]) for i in range(len(xs) - 1) for j in range(len(zs))),
               max(abs(s[i][j + 1] - s[i][j]) for i in range(len(xs)) for j in range(len(zs) - 1)))
    amp = STEP * math.tan(math.radians(a.slope)) / diff
    dip = math.tan(math.radians(a.dip))
    h = [[-dip * x + amp * s[i][j] for j, _ in enumerate(zs)] for i, x in enumerate(xs)]
    return xs, zs, h, (f"rough rock: mean dip {a.dip} deg downstream, cells within about "
                       f"{a.slope} deg of it, seed {a.seed}")


def bump(a):
    w, t = a.half_width, math.tan(math.radians(a.ridge_deg))
    xs = lines(X0, X1, STEP, (a.at - w, a.at, a.at + w))
    zs = lines(Z0, Z1, STEP)
    h = [[t * max(0.0, w - abs(x - a.at)) for _ in zs] for x in xs]
    return xs, zs, h, (f"level with a ridge of {a.ridge_deg} deg faces, crest X = {a.at} m, "
                       f"{t * w:.4f} m high, {2 * w} m wide")


def step(a):
    xs = lines(X0, X1, STEP, (a.at, a.at + a.run))
    zs = lines(Z0, Z1, STEP)
    h = [[0.0 if x <= a.at + 1e-12 else -a.drop for _ in zs] for x in xs]
    return xs, zs, h, (f"level, a step {a.drop} m down at X = {a.at} m over {a.run} m, "
                       f"level beyond")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("kind", choices=["rough", "bump", "step"])
    ap.add_argument("--out", required=True)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--dip", type=float, default=2.0, help="rough: mean dip downstream, deg")
    ap.add_argument("--slope", type=float, default=4.0, help="rough: cells' slopes about it, deg")
    ap.add_argument("--ridge-deg", type=float, default=8.0, help="bump: the ridge's faces, deg")
    ap.add_argument("--half-width", type=float, default=1.0, help="bump: crest to foot, m")
    ap.add_argument("--at", type=float, default=None,
                    help="bump: crest X (default -1); step: edge X (default 1)")
    ap.add_argument("--drop", type=float, default=0.3, help="step: height, m")
    ap.add_argument("--run", type=float, default=0.05, help="step: the riser's run, m")
    a = ap.parse_args()
    if a.at is None:
        a.at = -1.0 if a.kind == "bump" else 1.0
    xs, zs, h, what = {"rough": rough, "bump": bump, "step": step}[a.kind](a)
    out = [f"# {os.path.basename(a.out)}: {what}.",
           f"# Written by crosscheck/make_terrain.py {a.kind} (do not edit). Y up, scene "
           f"coordinates (m); {2 * (len(xs) - 1) * (len(zs) - 1)} triangles."]
    for i, x in enumerate(xs):
        for j, z in enumerate(zs):
            out.append("v %.9f %.9f %.9f" % (x, h[i][j], z))

    def vid(i, j):
        return i * len(zs) + j + 1

    for i in range(len(xs) - 1):
        for j in range(len(zs) - 1):
            p, q, r, s = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            # Counter-clockwise seen from above (+Y): normals up.
            out.append("f %d %d %d" % (p, s, r))
            out.append("f %d %d %d" % (p, r, q))
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(out) + "\n")
    os.replace(tmp, a.out)
    print("wrote", a.out, "-", what)


if __name__ == "__main__":
    main()
