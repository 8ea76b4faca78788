#!/usr/bin/env python3
"""Random whole-body scenes for slideroute's base contact (derivations/13-base-contact.md), run
through the command line and held to what is asked of every route, whatever the scene:

- it ends for a physical reason (`time-limit`, `stopped`, `does-not-slide`, `base-off-ground`,
  `overturned`), never at a three-point limit and never refused after its scene was accepted;
- its base is nowhere more than 1e-6 of the block's size inside the rock
  (`base.max_penetration_m`, the independent check of derivations/13-base-contact.md §5);
- its energy balance closes to 2e-3 of the work done (§7).

Each case draws a ground from make_terrain.py (rough, rough, bump or step, its parameters at
random), a square block or a monolith, flat or cast (`[base] cast = true`), μ in 0.25–0.7, a push
of 0.2–1.1 W off the centre of mass by up to 1.5 m, and runs 1.5 s at dt 1 ms. A case that fails
prints its scene's folder; the scene is kept there to be run again.

    cargo build --release
    python3 crosscheck/fuzz_body.py --seed 12 --cases 30 --out /tmp/fuzz

With `--bed PYTHON` (crosscheck/.venv/bin/python, which has NumPy) each case that moves is also
run in bed_body.py, the bed of springs on the ground's own triangles, until `--bed-until` s, and
the base point under the centre of mass must stay within 1 % of our travel and the yaw within
0.5°, as tests/integration/drake_crosscheck.rs asks; where it does not, the bed is run again
with μ ± 0.001 and the case is compared only until those two part by as much (a route that
sensitive to μ has no sharper reference). About a minute a case.

    python3 crosscheck/fuzz_body.py --seed 21 --cases 8 --out /tmp/fuzz-bed \
        --bed crosscheck/.venv/bin/python

Standard library only (make_terrain.py too), so it needs no environment. Exit 1 if a case failed.
"""

import argparse
import csv
import json
import math
import os
import random
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
PHYSICAL = ("time-limit", "stopped", "does-not-slide", "base-off-ground", "overturned")


def ground(rng, path):
    """A terrain OBJ at `path` from make_terrain.py; returns its kind."""
    kind = rng.choice(["rough", "rough", "bump", "step"])
    args = [sys.executable, os.path.join(HERE, "make_terrain.py"), kind, "--out", path,
            "--seed", str(rng.randint(1, 9999))]
    if kind == "rough":
        args += ["--dip", f"{rng.uniform(-4, 4):.2f}", "--slope", f"{rng.uniform(0.5, 8):.2f}"]
    elif kind == "bump":
        args += ["--ridge-deg", f"{rng.uniform(2, 15):.1f}", "--at", f"{rng.uniform(-3, 3):.2f}"]
    else:
        args += ["--at", f"{rng.uniform(0, 6):.2f}", "--drop", f"{rng.uniform(0.05, 1.0):.2f}"]
    subprocess.run(args, check=True, capture_output=True)
    return kind


def scene(rng, name):
    """A scene's text (its ground `g.obj` beside it) and the block's size L (m)."""
    push = rng.uniform(0.2, 1.1)
    if rng.random() < 0.5:
        body = f"""[frame]
contacts_m = [[-1.0, 1.0], [1.0, 1.0], [1.0, -1.0]]
[monolith]
base_length_m = {rng.uniform(8, 20):.2f}
width_m = {rng.uniform(4, 12):.2f}
height_m = {rng.uniform(6, 20):.2f}
crest_length_m = {rng.uniform(2, 5):.2f}
density_kg_m3 = 2400.0
[loads]
hydraulic_force_n = {push * 2.0e7:.4e}
"""
        size = 20.0
    else:
        a = rng.uniform(1, 4)
        body = f"""[frame]
contacts_m = [[{-a}, {a}], [{a}, {a}], [{a}, {-a}]]
[block]
mass_kg = 1.0e6
inertia_kg_m2 = {1e6 * (2 * a) ** 2 / 6:.4e}
[loads]
hydraulic_force_n = {push * 9.81e6:.4e}
"""
        size = 2 * a
    text = f"""name = "{name}"
{body}eccentricity_m = {rng.uniform(-1.5, 1.5):.2f}
gravity_m_s2 = 9.81
[foundation]
surface = "g.obj"
[friction]
model = "coulomb"
mu_k = {rng.uniform(0.25, 0.7):.3f}
[solver]
mode = "exact"
dt_s = 1.0e-3
t_end_s = 1.5
contacts = "base"
"""
    if rng.random() < 0.5:
        text += "[base]\ncast = true\n"
    return text, size


def judge(summary, size):
    """What is wrong with a finished route (empty if nothing)."""
    wrong = []
    term = summary["termination"]
    if term["reason"] not in PHYSICAL:
        wrong.append(f"ended '{term['reason']}'")
    pen = (summary.get("base") or {}).get("max_penetration_m")
    if pen is not None and pen > 1e-6 * size:
        wrong.append(f"{pen:.3g} m into the rock")
    e = summary.get("energy") or {}
    work = sum(abs(e.get(k, 0.0)) for k in
               ("work_hydraulic_j", "work_friction_j", "potential_change_j", "kinetic_initial_j"))
    if work > 0 and abs(e.get("residual_j", 0.0)) > 2e-3 * work:
        wrong.append(f"energy residual {abs(e['residual_j']) / work:.2e} of the work")
    return wrong


def path(file, cols):
    """{millisecond: (x, y, z, theta)} of a CSV's columns `cols` (three positions and a yaw)."""
    out = {}
    with open(file) as f:
        for row in csv.DictReader(f):
            t = round(float(row["t_s"]) * 1000)
            out[t] = tuple(float(row[c]) for c in cols)
    return out


def bed_run(a, folder, until, dmu):
    """bed_body.py's path for the case in `folder` with μ + dmu (None if it failed)."""
    cast = ["--cast"] if "cast = true" in open(os.path.join(folder, "scene.toml")).read() else []
    out = os.path.join(folder, f"bed{dmu}.csv")
    run = subprocess.run([a.bed, os.path.join(HERE, "bed_body.py"), "--scene",
                          os.path.join(folder, "scene.toml"), "--start",
                          os.path.join(folder, "out", "summary.json"), "--out", out,
                          "--t-end", str(until), "--mu-delta", str(dmu), "--quiet", *cast],
                         capture_output=True, text=True, timeout=3600)
    if run.returncode != 0:
        return None, run.stderr.strip()[-300:]
    return path(out, ("bx_m", "by_m", "bz_m", "theta_deg")), ""


def against_bed(a, folder, until):
    """What is wrong with the case's route against the bed of springs (empty if nothing), and
    a line of what was measured."""
    ours = path(os.path.join(folder, "out", "route.csv"), ("x_m", "y_m", "z_m", "theta_deg"))
    ms = sorted(t for t in ours if t <= round(until * 1000))
    travel = sum(math.dist(ours[s][:3], ours[t][:3]) for s, t in zip(ms, ms[1:]))
    if travel < 1e-3:
        return [], "held"
    bed, err = bed_run(a, folder, until, 0.0)
    if bed is None:
        return [f"bed_body.py failed: {err}"], ""

    def worst(end):
        gap = yaw = 0.0
        for t in ms:
            if t > end or t not in bed:
                continue
            gap = max(gap, math.dist(ours[t][:3], bed[t][:3]))
            yaw = max(yaw, abs((ours[t][3] - bed[t][3] + 180) % 360 - 180))
        return gap, yaw

    end = ms[-1]
    gap, yaw = worst(end)
    note = ""
    if gap > 0.01 * travel or yaw > 0.5:
        plus, _ = bed_run(a, folder, until, 0.001)
        minus, _ = bed_run(a, folder, until, -0.001)
        if plus and minus:
            for t in ms:
                if t in plus and t in minus and (
                        math.dist(plus[t][:3], minus[t][:3]) > 0.01 * travel
                        or abs((plus[t][3] - minus[t][3] + 180) % 360 - 180) > 0.5):
                    end = t
                    note = f", μ ± 0.001 part at {t / 1000:.3f} s"
                    break
        gap, yaw = worst(end)
    line = (f"bed to {end / 1000:.3f} s{note}: CM {gap * 1e3:.2f} mm "
            f"({100 * gap / travel:.2f} % of {travel:.3f} m), yaw {yaw:.3f}°")
    wrong = []
    if gap > 0.01 * travel or yaw > 0.5:
        wrong.append(line)
    return wrong, line


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "target", "release", "slideroute"))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=20)
    ap.add_argument("--out", required=True, help="a folder for the cases' scenes and routes")
    ap.add_argument("--bed", help="a Python with NumPy: compare each case with bed_body.py")
    ap.add_argument("--bed-until", type=float, default=0.5, help="s")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    failed = 0
    for case in range(a.cases):
        folder = os.path.join(a.out, f"case{case}")
        os.makedirs(folder, exist_ok=True)
        kind = ground(rng, os.path.join(folder, "g.obj"))
        text, size = scene(rng, f"fuzz-{a.seed}-{case}")
        with open(os.path.join(folder, "scene.toml"), "w") as f:
            f.write(text)
        run = subprocess.run([a.bin, "run", "--scene", os.path.join(folder, "scene.toml"),
                              "--out", os.path.join(folder, "out"), "--no-plots"],
                             capture_output=True, text=True, timeout=900)
        head = f"case {case} ({kind}, {'cast' if 'cast = true' in text else 'flat'})"
        if run.returncode != 0:
            failed += 1
            print(f"FAIL {head}: exit {run.returncode}: {run.stderr.strip()[-300:]} [{folder}]")
            continue
        with open(os.path.join(folder, "out", "summary.json")) as f:
            summary = json.load(f)
        wrong = judge(summary, size)
        term = summary["termination"]
        line = ""
        if a.bed and not wrong:
            more, line = against_bed(a, folder, min(a.bed_until, term["t_s"]))
            wrong += more
        print(f"{'FAIL' if wrong else 'ok  '} {head}: {term['reason']} at {term['t_s']:.3f} s"
              + (f": {'; '.join(wrong)} [{folder}]" if wrong else (f"; {line}" if line else "")),
              flush=True)
        failed += bool(wrong)
    print(f"{a.cases - failed} of {a.cases} cases ok")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
