#!/usr/bin/env python3
"""Compares two paths written by drake_body.py (or drake_route.py, or slideroute's route.csv:
any CSV with t_s, x_m, y_m, z_m, theta_deg) at their common times: the travel of each (the
horizontal path length of the written point), the largest distance between the two points and
the largest yaw difference, absolute and as a share of the first path's travel. Standard library
only.

    python3 crosscheck/compare_paths.py a.csv b.csv [--cols x_m,y_m,z_m] [--cols-a x_m,y_m,z_m]
        [--until T] [--spread plus.csv minus.csv]

--cols names the point in b (and --spread's files), --cols-a in a if it differs: slideroute's
route.csv writes the base point under the CM as x_m, y_m, z_m, drake_body.py as bx_m, by_m, bz_m.
--spread: two more runs of b (e.g. Drake with mu + 0.001 and mu - 0.001); the comparison then
ends where they first part by 1 % of a's travel (its 3-D path length until their end) or
0.5°, as tests/integration/drake_crosscheck.rs's follows_drake does.
"""
import argparse
import csv
import math


def read(path, cols):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = {}
    for r in rows:
        t = round(float(r["t_s"]), 6)
        out[t] = ([float(r[c]) for c in cols], float(r["theta_deg"]),
                  {k: r[k] for k in r})
    return out


def travel(path, until):
    ts = sorted(t for t in path if t <= until + 1e-9)
    return sum(math.hypot(path[b][0][0] - path[a][0][0], path[b][0][2] - path[a][0][2])
               for a, b in zip(ts, ts[1:]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--cols", default="x_m,y_m,z_m",
                    help="the point compared (e.g. bx_m,by_m,bz_m: the base point under the CM)")
    ap.add_argument("--cols-a", help="the point compared in a, if not --cols")
    ap.add_argument("--until", type=float, default=float("inf"))
    ap.add_argument("--spread", nargs=2, metavar=("PLUS", "MINUS"),
                    help="end where these two runs of b part by 1 %% of a's travel or 0.5°")
    a = ap.parse_args()
    cols = a.cols.split(",")
    pa, pb = read(a.a, (a.cols_a or a.cols).split(",")), read(a.b, cols)
    if a.spread:
        plus, minus = read(a.spread[0], cols), read(a.spread[1], cols)
        ts = sorted(t for t in plus if t in minus and t <= a.until + 1e-9)
        mine = sorted(t for t in pa if t <= ts[-1] + 1e-9)
        scale = sum(math.dist(pa[x][0], pa[y][0]) for x, y in zip(mine, mine[1:]))
        apart = next((t for t in ts
                      if math.dist(plus[t][0], minus[t][0]) > 0.01 * scale
                      or abs((plus[t][1] - minus[t][1] + 180) % 360 - 180) > 0.5), None)
        print(f"{a.spread[0]} and {a.spread[1]} part by 1 % of {scale:.4f} m or 0.5° at "
              + (f"{apart:.3f} s" if apart is not None else f"no time until {ts[-1]:.3f} s"))
        if apart is not None:
            a.until = min(a.until, apart)
    common = sorted(t for t in pa if t in pb and t <= a.until + 1e-9)
    end = common[-1]
    ta, tb = travel(pa, end), travel(pb, end)
    gap, at, yaw, yat = 0.0, 0.0, 0.0, 0.0
    for t in common:
        d = math.dist(pa[t][0], pb[t][0])
        if d > gap:
            gap, at = d, t
        dy = abs((pa[t][1] - pb[t][1] + 180) % 360 - 180)
        if dy > yaw:
            yaw, yat = dy, t
    last_a, last_b = pa[end], pb[end]
    share = 100 * gap / ta if ta > 0 else float("nan")
    print(f"until t = {end:.3f} s: travel {ta:.4f} / {tb:.4f} m "
          f"({100 * abs(ta - tb) / ta if ta > 0 else float('nan'):.3f} %); largest gap "
          f"{1000 * gap:.2f} mm ({share:.3f} % of travel) at {at:.3f} s; largest yaw gap "
          f"{yaw:.4f} deg at {yat:.3f} s; theta at the end {last_a[1]:.4f} / {last_b[1]:.4f} deg")
    for k in ("tilt_deg", "min_gap_m", "ridge_gap_m"):
        if k in last_a[2] and k in last_b[2]:
            print(f"  {k} at the end: {last_a[2][k]} / {last_b[2][k]}")


if __name__ == "__main__":
    main()
