#!/usr/bin/env python3
"""Random whole-body scenes for slideroute's base contact (derivations/13-base-contact.md), run
through the command line and held to what issue #26 asks of every route, whatever the scene:

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

Standard library only (make_terrain.py too), so it needs no environment. Exit 1 if a case failed.
"""

import argparse
import json
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "target", "release", "slideroute"))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=20)
    ap.add_argument("--out", required=True, help="a folder for the cases' scenes and routes")
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
        print(f"{'FAIL' if wrong else 'ok  '} {head}: {term['reason']} at {term['t_s']:.3f} s"
              + (f": {'; '.join(wrong)} [{folder}]" if wrong else ""), flush=True)
        failed += bool(wrong)
    print(f"{a.cases - failed} of {a.cases} cases ok")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
