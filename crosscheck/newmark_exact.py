#!/usr/bin/env python3
"""Records against the exact solution: the route on synthetic records beside
Newmark's one-dimensional block with a constant push, solved in closed form.

A block on one level face, three points of the paper's frame, pushed along X through its centre
of mass by `push` of its weight, friction `mu`, shaken along X by a synthetic record (white
noise through a 2.5 Hz, 60 %-damped filter, under an envelope, scaled to a PGA), the record
linear between its 5 ms samples. The exact solution follows the same continuous problem
interval by interval: the onset where the linear acceleration leaves the band [push − μ,
push + μ] g, the velocity a quadratic while it slides, the stop at its zero. Printed per case:
the exact and the route's permanent displacement, their relative difference, the route's
rotation, its energy residual against the work, how it ended and the wall time.

    crosscheck/.venv/bin/python crosscheck/newmark_exact.py --seeds 1 11 \
        --bin target/release/slideroute --out /tmp/newmark

With `--both-ways`, the same records without a push (μ = 0.1 and 0.2, along X and along Z): the
block slides back and forth, stopping and starting from rest at each reversal.

With `--records DIR`, real records instead (two columns, time s and acceleration g, as SLAMMER's
samples come; `crosscheck/setup.sh` puts eighteen in crosscheck/.records), each at ky = 0.05,
0.1 and 0.2 g along X and along Z without a push, and along X with μ = 1 and a push of 1 − ky:

    crosscheck/.venv/bin/python crosscheck/newmark_exact.py --records crosscheck/.records

(numpy only; `tests/integration/common/newmark.rs` is the same solution in Rust, for the tests.)
"""

import argparse
import json
import math
import os
import subprocess
import time

import numpy as np

G = 9.81

SCENE = """name = "{name}"
[frame]
l1x = 6.0
l2x = 4.0
l1z = 5.0
l2z = 5.0
[foundation]
[[foundation.plane]]
dip_deg = 0.0
dip_direction_deg = 0.0
point_m = [0.0, 0.0, 0.0]
[block]
mass_kg = 1.0e6
inertia_kg_m2 = 1.1e7
[loads]
hydraulic_force_n = {force}
eccentricity_m = 0.0
gravity_m_s2 = 9.81
[friction]
model = "coulomb"
mu_k = {mu}
[solver]
mode = "exact"
contacts = "frame"
dt_s = {dt}
t_end_s = {t_end}
[seismic]
record_{axis} = "record.txt"
dt_s = {record_dt}
"""


def record(seed, length=20.0, dt=0.005, pga=0.4, f0=2.5, zeta=0.6):
    """A synthetic record along X (g)."""
    rng = np.random.default_rng(seed)
    n = int(round(length / dt)) + 1
    t = np.arange(n) * dt
    w = rng.standard_normal(n)
    om = 2 * math.pi * f0
    x = v = 0.0
    out = np.zeros(n)
    for i in range(n):
        a = -2 * zeta * om * v - om * om * x + w[i] / math.sqrt(dt)
        v += a * dt
        x += v * dt
        out[i] = -(2 * zeta * om * v + om * om * x)
    env = np.minimum(1, t / 2.0) * np.exp(-np.maximum(0, t - 0.4 * length) / (0.15 * length))
    out *= env
    out[0] = 0.0
    out *= pga / np.max(np.abs(out))
    return t, out


def exact(t, a, mu, push):
    """The exact permanent displacement (m, along +X)."""
    u = v = 0.0
    s = 0

    def band(acc):
        return 1 if acc < push - mu else (-1 if acc > push + mu else 0)

    for i in range(len(t) - 1):
        h = t[i + 1] - t[i]
        a0, a1 = a[i], a[i + 1]
        k = (a1 - a0) / h
        tau = 0.0
        while tau < h:
            at = a0 + k * tau
            if s == 0:
                s = band(at)
                if s:
                    continue
                leaves = [(e - a0) / k for e in (push - mu, push + mu) if (a1 - e) * (at - e) < 0]
                if not leaves or min(leaves) >= h:
                    break
                tau = max(min(leaves), tau)
                s = 1 if k < 0 else -1
                continue
            c0, c1 = G * (push - s * mu - at), -G * k
            rem = h - tau
            roots = []
            qa, qb, qc = 0.5 * c1, c0, v
            if qa == 0:
                roots = [-qc / qb] if qb else []
            else:
                disc = qb * qb - 4 * qa * qc
                if disc >= 0:
                    q = -0.5 * (qb + math.copysign(math.sqrt(disc), qb))
                    roots = [q / qa] + ([qc / q] if q else [])
            roots = sorted(r for r in roots if 1e-15 < r <= rem)
            r = roots[0] if roots else rem
            u += v * r + 0.5 * c0 * r * r + c1 * r**3 / 6
            if roots:
                v = 0.0
                tau += r
                s = band(a0 + k * tau)
            else:
                v += c0 * r + 0.5 * c1 * r * r
                tau = h
    if s and v:
        dec = G * (push - s * mu)
        if s * dec < 0:
            r = -v / dec
            u += v * r + 0.5 * dec * r * r
    return u


def read_record(path):
    """A record as it comes: two columns (time s, acceleration g) or one, `#` comments and a
    header line skipped."""
    rows = []
    for line in open(path):
        parts = line.replace(",", " ").split()
        try:
            rows.append([float(p) for p in parts])
        except ValueError:
            continue
    rows = np.array([r for r in rows if r])
    return rows[:, 0] - rows[0, 0], rows[:, 1]


def case(binary, out, seed, mu, push, pga, dt, given=None, axis="x"):
    name = f"s{seed}-{axis}-mu{mu}-push{push}"
    if given:
        name = f"{os.path.splitext(os.path.basename(given))[0]}-{axis}-mu{mu}-push{push}"
    d = os.path.join(out, name)
    os.makedirs(d, exist_ok=True)
    t, a = read_record(given) if given else record(seed, pga=pga)
    np.savetxt(os.path.join(d, "record.txt"), a, fmt="%.17g")
    with open(os.path.join(d, "scene.toml"), "w") as f:
        f.write(SCENE.format(name=name, force=push * 1e6 * G, mu=mu, dt=dt, axis=axis,
                             t_end=t[-1] + 10, record_dt=t[1] - t[0]))
    start = time.time()
    run = subprocess.run([binary, "run", "--scene", os.path.join(d, "scene.toml"),
                          "--out", os.path.join(d, "out"), "--no-plots"],
                         capture_output=True, text=True)
    wall = time.time() - start
    if run.returncode != 0:
        print(f"{name}: failed: {run.stderr.strip()}")
        return
    s = json.load(open(os.path.join(d, "out", "summary.json")))
    want = exact(t, a, mu, push)
    got = s["permanent_displacement_xz_m"][0 if axis == "x" else 1]
    e = s["energy"]
    work = max(abs(e["work_hydraulic_j"]), abs(e["work_friction_j"]))
    balance = f"{e['residual_j'] / work:+.1e} of the work" if work else f"{e['residual_j']:+.1e} J"
    off = (got - want) / abs(want) if abs(want) > 1e-6 else got - want
    print(f"{name:28s} exact {want:.6f} m  route {got:.6f} m  {off:+.1e}  "
          f"turned {s['permanent_rotation_deg']:+.1e}°  residual {balance}  {s['termination']['reason']}  {wall:.2f} s")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--bin", default="target/release/slideroute")
    p.add_argument("--out", default="/tmp/slideroute-newmark")
    p.add_argument("--seeds", nargs=2, type=int, default=[1, 4])
    p.add_argument("--dt", type=float, default=1e-3)
    p.add_argument("--both-ways", action="store_true",
                   help="the synthetic records without a push (μ = 0.1 and 0.2, along X and Z): "
                   "the block slides both ways, stopping and starting from rest")
    p.add_argument("--records", help="a folder of records (time s, acceleration g), each run at "
                   "ky = 0.05, 0.1, 0.2 g without a push and with one (μ = 1), along X and Z")
    args = p.parse_args()
    if args.records:
        for f in sorted(os.listdir(args.records)):
            for ky in (0.05, 0.1, 0.2):
                for mu, push, axis in [(ky, 0.0, "x"), (ky, 0.0, "z"), (1.0, 1.0 - ky, "x")]:
                    case(args.bin, args.out, 0, mu, round(push, 2), 0, args.dt,
                         os.path.join(args.records, f), axis)
        return
    if args.both_ways:
        for seed in range(*args.seeds):
            for mu in (0.1, 0.2):
                for axis in "xz":
                    case(args.bin, args.out, seed, mu, 0.0, 0.4, args.dt, axis=axis)
        return
    for seed in range(*args.seeds):
        for mu, push in [(1.0, 0.9), (1.0, 0.95), (1.0, 0.8), (0.6, 0.5), (0.3, 0.25)]:
            case(args.bin, args.out, seed, mu, push, 0.3 + 0.1 * (seed % 5), args.dt)


if __name__ == "__main__":
    main()
