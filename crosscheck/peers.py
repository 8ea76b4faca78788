#!/usr/bin/env python3
"""CPU cost of slideroute, Drake (drake_route.py) and MuJoCo (mujoco_route.py) to reach a given
accuracy of the default scene's route, measured in one run.

All three tools run the default (paper-like) scene to --t-end (3 s by default; its route slides
until 4.36 s). The error of a run is its travel at --t-end relative to a reference:

- slideroute's converged route (`solver.tolerance = 1e-13`, rows every 1 ms): its `travel_m`
  from summary.json and its CM from route.csv's last row;
- for Drake also Drake's own finest run (--drake-ref-dt, 15.625 us): as dt -> 0 Drake's travel
  grows to about 0.6 % more than ours (measured 2026-11-28), more than the 0.1 % and 0.01 %
  targets, so Drake's error is measured against Drake's finest run whenever the two differ by more
  than the smallest target (both errors are printed). Drake's travel
  is the sum of its CM's 3-D chords at every step (as tests/integration/drake_crosscheck.rs).
- MuJoCo (a ladder of dt for each of --mujoco-integrators: Euler, MuJoCo's default, and RK4)
  against our converged route, its travel also the sum of its CM's 3-D chords at every step;
  printed beside it: its CM's distance at --t-end from ours (over our travel), its yaw, and the
  share of steps in which all three contact spheres touch their planes. mujoco_route.py writes
  no CSV here (it prints its summary), so MuJoCo's runs are its cheapest loop; Drake's write one.

Cost is whole-process CPU (user + sys of the child from getrusage(RUSAGE_CHILDREN) deltas):
slideroute's `run --quiet --no-plots --no-3d`, Drake's `python drake_route.py` with Python's
start-up and pydrake's import, as a user pays them, and MuJoCo's `python mujoco_route.py` likewise.
CPU time, not wall time, because the machine may be shared. Median of --repeats-ours (5),
--repeats-drake (3) and --repeats-mujoco (3) runs.

For each target (1 %, 0.1 %, 0.01 %) the cheapest measured run of each tool whose error is at or
below it (nothing interpolated) and Drake's and MuJoCo's CPU over slideroute's; where no MuJoCo
run reaches a target, the smallest error it reached. Prints markdown.

    crosscheck/.venv/bin/python crosscheck/peers.py --slideroute target/release/slideroute
"""
import argparse
import csv
import importlib.metadata
import math
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOLERANCES = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9]
DRAKE_DTS = [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5]
MUJOCO_DTS = [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5, 3.125e-5, 1.5625e-5]
TARGETS = [1e-2, 1e-3, 1e-4]


def cpu_of(cmd, output=None):
    """Run cmd to completion; the child's user + sys CPU seconds. Its stdout is appended to the
    list `output` if given, else discarded."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL if output is None else subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"peers.py: {' '.join(cmd)} failed:\n{done.stderr}")
    if output is not None:
        output.append(done.stdout)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def median_cpu(cmd, n, output=None):
    runs = [cpu_of(cmd, output) for _ in range(n)]
    return statistics.median(runs), runs


def read_summary(folder):
    import json
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def last_row(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows[-1], len(rows)


def drake_path(path):
    with open(path) as f:
        rows = [(float(r["t_s"]), float(r["x_m"]), float(r["y_m"]), float(r["z_m"]))
                for r in csv.DictReader(f)]
    travel = sum(math.dist(a[1:], b[1:]) for a, b in zip(rows, rows[1:]))
    return travel, rows[-1]


def mujoco_summary(text):
    """mujoco_route.py's printed summary: {first word of a line: [the line's numbers]}."""
    def number(w):
        try:
            return float(w)
        except ValueError:
            return None

    out = {}
    for line in text.splitlines():
        words = line.split()
        if words:
            out[words[0]] = [x for x in map(number, words[1:]) if x is not None]
    return out


def pct(x):
    if x == 0:
        return "0 %"
    return f"{100 * x:.2g} %" if x >= 1e-6 else f"{100 * x:.1e} %"


def ms(x):
    """CPU seconds as the docs write them: 4.6 ms, 409 ms, 1.72 s, 22.1 s."""
    if x < 0.1:
        return f"{1000 * x:.1f} ms"
    if x < 1:
        return f"{1000 * x:.0f} ms"
    return f"{x:.2f} s" if x < 10 else f"{x:.1f} s"


def step(dt):
    """A time step as the docs write it: 4 ms, 0.125 ms, 62.5 µs."""
    return f"{dt * 1000:g} ms" if dt >= 1e-4 else f"{dt * 1e6:g} µs"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--slideroute", default="target/release/slideroute")
    ap.add_argument("--t-end", type=float, default=3.0)
    ap.add_argument("--repeats-ours", type=int, default=5)
    ap.add_argument("--repeats-drake", type=int, default=3)
    ap.add_argument("--drake-dts", type=float, nargs="+", default=DRAKE_DTS)
    ap.add_argument("--drake-ref-dt", type=float, default=1.5625e-5,
                    help="Drake's own converged run (timed once, not in the ladder)")
    ap.add_argument("--repeats-mujoco", type=int, default=3)
    ap.add_argument("--mujoco-dts", type=float, nargs="+", default=MUJOCO_DTS)
    ap.add_argument("--mujoco-integrators", nargs="*", default=["Euler", "RK4"],
                    help="a ladder of --mujoco-dts for each (none: MuJoCo not run)")
    a = ap.parse_args()
    exe = os.path.abspath(a.slideroute)
    tmp = tempfile.mkdtemp(prefix="peers-")
    scene = os.path.join(tmp, "default.toml")
    text = subprocess.run([exe, "scene", "--print-default"], check=True, capture_output=True,
                          text=True).stdout
    text, n = re.subn(r"(?m)^t_end_s\s*=\s*[0-9.eE+-]+", f"t_end_s = {a.t_end!r}", text)
    if n != 1:
        sys.exit("peers.py: no t_end_s line in the default scene")
    with open(scene, "w") as f:
        f.write(text)
    T = a.t_end
    version = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout.strip()

    def ours(tol, dt, out):
        return [exe, "run", "--scene", scene, "--set", f"solver.tolerance={tol!r}",
                "--set", f"solver.t_end_s={T!r}", "--set", f"solver.dt_s={dt!r}",
                "--out", out, "--quiet", "--no-plots", "--no-3d"]

    # The converged reference.
    ref_dir = os.path.join(tmp, "ref")
    subprocess.run(ours(1e-13, 1e-3, ref_dir), check=True)
    s = read_summary(ref_dir)
    if abs(s["termination"]["t_s"] - T) > 1e-9:
        sys.exit(f"peers.py: the reference ends at {s['termination']['t_s']} s, before {T} s")
    ref_travel = s["travel_m"]
    row, _ = last_row(os.path.join(ref_dir, "route.csv"))
    ref_cm = (float(row["x_m"]), float(row["y_m"]), float(row["z_m"]))
    ref_theta = float(row["theta_deg"])
    peers = []
    for name in ("drake", "mujoco"):
        try:
            peers.append(f"{name} {importlib.metadata.version(name)}")
        except importlib.metadata.PackageNotFoundError:
            peers.append(f"{name} not installed")
    print(f"# {version}; {', '.join(peers)}; default scene to {T} s; {os.cpu_count()} CPUs; "
          f"load average {os.getloadavg()[0]:.2f} at the start")
    print(f"reference: slideroute tolerance 1e-13, 1 ms rows: travel {ref_travel:.12f} m, "
          f"CM at {T} s ({ref_cm[0]:.9f}, {ref_cm[1]:.9f}, {ref_cm[2]:.9f}) m, "
          f"yaw {ref_theta:.4f}°, {s['steps']['taken']} steps")

    # slideroute's ladder.
    mine = []  # (label, cpu, err, runs, steps)
    for tol, dt in [(t, 0.01) for t in TOLERANCES] + [(1e-9, 1e-3)]:
        out = os.path.join(tmp, f"ours-{tol:g}-{dt:g}")
        cpu, runs = median_cpu(ours(tol, dt, out), a.repeats_ours)
        s = read_summary(out)
        err = abs(s["travel_m"] - ref_travel) / ref_travel
        label = f"tolerance {tol:g}, rows {dt * 1000:g} ms"
        mine.append(dict(label=label, cpu=cpu, err=err, runs=runs, steps=s["steps"]["taken"],
                         rows=dt))
        print(f"ours {label}: travel {s['travel_m']:.12f} m, error {err:.2e}, {s['steps']['taken']}"
              f" steps, CPU {['%.4f' % r for r in runs]} s", flush=True)

    # Drake's ladder and its own converged run.
    def drake(dt, out):
        return [sys.executable, os.path.join(HERE, "drake_route.py"), "--scene", scene,
                "--t-end", repr(T), "--dt", repr(dt), "--out", out]

    ref_out = os.path.join(tmp, "drake-ref.csv")
    ref_cpu = cpu_of(drake(a.drake_ref_dt, ref_out))
    dref_travel, dref_last = drake_path(ref_out)
    gap = abs(dref_travel - ref_travel) / ref_travel
    cm_gap = math.dist(dref_last[1:], ref_cm)
    print(f"Drake converged (dt {a.drake_ref_dt:g} s, CPU {ref_cpu:.2f} s): travel "
          f"{dref_travel:.6f} m, {100 * gap:.3f} % from ours; CM at {dref_last[0]:g} s "
          f"{1000 * cm_gap:.2f} mm ({100 * cm_gap / ref_travel:.3f} % of travel) from ours",
          flush=True)
    own = gap > min(TARGETS)
    theirs = []
    for dt in a.drake_dts:
        out = os.path.join(tmp, f"drake-{dt:g}.csv")
        cpu, runs = median_cpu(drake(dt, out), a.repeats_drake)
        travel, last = drake_path(out)
        theirs.append(dict(label=f"dt {step(dt)}", cpu=cpu, travel=travel,
                           err_ours=abs(travel - ref_travel) / ref_travel,
                           err_own=abs(travel - dref_travel) / dref_travel, runs=runs))
        print(f"Drake dt {dt:g}: travel {travel:.6f} m, error against ours "
              f"{theirs[-1]['err_ours']:.2e}, against Drake converged {theirs[-1]['err_own']:.2e},"
              f" CPU {['%.3f' % r for r in runs]} s", flush=True)
    key = "err_own" if own else "err_ours"
    for d in theirs:
        d["err"] = d[key]

    # MuJoCo's ladders (one per integrator), against our converged route.
    def mujoco(dt, integrator):
        return [sys.executable, os.path.join(HERE, "mujoco_route.py"), "--scene", scene,
                "--t-end", repr(T), "--dt", repr(dt), "--integrator", integrator]

    jo = []
    for integrator in a.mujoco_integrators:
        for dt in a.mujoco_dts:
            cmd = mujoco(dt, integrator)
            printed = []
            cpu, runs = median_cpu(cmd, a.repeats_mujoco, printed)
            got = mujoco_summary(printed[-1])
            travel, cm = got["travel_m"][0], got["cm_m"]
            jo.append(dict(label=f"{integrator}, dt {step(dt)}", dt=dt, cpu=cpu,
                           travel=travel, err=abs(travel - ref_travel) / ref_travel,
                           cm=math.dist(cm, ref_cm) / ref_travel, theta=got["theta_deg"][0],
                           touch=got["touching"], runs=runs))
            j = jo[-1]
            print(f"MuJoCo {j['label']}: travel {travel:.6f} m, error {j['err']:.2e}, CM "
                  f"{100 * j['cm']:.2f} % of travel from ours, yaw {j['theta']:.3f}°, touching "
                  f"{['%.4f' % x for x in j['touch'][:3]]} all {j['touch'][3]:.4f}, "
                  f"CPU {['%.3f' % r for r in runs]} s", flush=True)
        # Each against the finest dt of its integrator: does MuJoCo's route converge?
        ladder_j = jo[-len(a.mujoco_dts):]
        finest = min(ladder_j, key=lambda j: j["dt"])
        for j in ladder_j:
            j["own"] = (f"{abs(j['travel'] - finest['travel']) / finest['travel']:.1e} from its"
                        " finest dt" if j is not finest else "its finest dt")

    print()
    print("| tool, setting | CPU, whole process (median) | travel error at "
          f"{T:g} s | |")
    print("| --- | --- | --- | --- |")
    for m in mine:
        print(f"| slideroute, {m['label']} | {ms(m['cpu'])} | {m['err']:.1e} | "
              f"{m['steps']} steps |")
    for d in theirs:
        print(f"| Drake, {d['label']} | {ms(d['cpu'])} | {d['err_own']:.1e} "
              f"(against ours: {d['err_ours']:.1e}) | travel {d['travel']:.5f} m |")
    print(f"| Drake, dt {step(a.drake_ref_dt)} (Drake's reference, run once) | "
          f"{ms(ref_cpu)} | — (against ours: {gap:.1e}) | travel {dref_travel:.5f} m |")
    for j in jo:
        print(f"| MuJoCo, {j['label']} | {ms(j['cpu'])} | {j['err']:.1e} | travel "
              f"{j['travel']:.5f} m |")
    if not jo:
        print("| MuJoCo | not measured in this run | | |")
    print()
    print(f"Drake's error is against {'its own converged run' if own else 'our converged route'}"
          f"; ours and MuJoCo's against ours (tolerance 1e-13).")
    if jo:
        print()
        print(f"| MuJoCo, setting | travel at {T:g} s, from its finest dt | CM at {T:g} s from ours"
              f" (of our travel) | yaw at {T:g} s (ours {ref_theta:.2f}°) | steps touching: "
              "contact 0, 1, 2, all three |")
        print("| --- | --- | --- | --- | --- |")
        for j in jo:
            t = j["touch"]
            print(f"| {j['label']} | {j['travel']:.5f} m ({j['own']}) | "
                  f"{1000 * j['cm'] * ref_travel:.0f} mm ({pct(j['cm'])}) | {j['theta']:.2f}° | "
                  f"{pct(t[0])}, {pct(t[1])}, {pct(t[2])}, {pct(t[3])} |")
    print()
    print("| accuracy of travel | slideroute: cheapest run reaching it | Drake: cheapest run "
          "reaching it | Drake CPU / slideroute CPU | MuJoCo: cheapest run reaching it | "
          "MuJoCo CPU / slideroute CPU |")
    print("| --- | --- | --- | --- | --- | --- |")
    ladder = [m for m in mine if m["rows"] == 0.01]
    for target in TARGETS:
        o = min((m for m in ladder if m["err"] <= target), key=lambda m: m["cpu"], default=None)
        d = min((x for x in theirs if x["err"] <= target), key=lambda x: x["cpu"], default=None)
        cell_o = f"{o['label']}, {ms(o['cpu'])}" if o else "none of the ladder"
        cell_d = f"{d['label']}, {ms(d['cpu'])}" if d else "none of the ladder"
        ratio = f"{d['cpu'] / o['cpu']:.0f}×" if o and d else "—"
        j = min((x for x in jo if x["err"] <= target), key=lambda x: x["cpu"], default=None)
        if j:
            cell_j = (f"{j['label']}, {ms(j['cpu'])} (its CM {pct(j['cm'])} of travel from "
                      "ours)")
            ratio_j = f"{j['cpu'] / o['cpu']:.0f}×" if o else "—"
        elif jo:
            b = min(jo, key=lambda x: x["err"])
            cell_j = f"not reached (best {b['err']:.1e}: {b['label']}, {ms(b['cpu'])})"
            ratio_j = "—"
        else:
            cell_j, ratio_j = "not run", "—"
        print(f"| {pct(target)} | {cell_o} | {cell_d} | {ratio} | {cell_j} | {ratio_j} |")
    print()
    print(f"(scratch: {tmp}; load average {os.getloadavg()[0]:.2f} at the end)")


if __name__ == "__main__":
    main()
