#!/usr/bin/env python3
"""The path of a slideroute scene's block in MuJoCo, for peers.py. Independent of slideroute's
code: it reads only the scene file, and builds the scene drake_route.py builds, in MJCF.

Model: one free body (mass, the inertia about the CM in the block axes x', y', z'; a product
∫x'z' dm as fullinertia) with three spheres (--radius, 1 mm as Drake's) centred on the contact
points; each sphere collides only with its own plane (contype/conaffinity bits: "from the
perspective of contact 2, plane 1 does not exist"), the plane lowered by the radius, as in
drake_route.py. Coulomb friction mu_k (condim 3, both geoms alike), elliptic cones. Gravity -g Y;
X forward, Y up, Z lateral; the block starts flat with its CM at the origin, at the rates of
[initial] made consistent with the contacts (drake_route.py's initial_twist).

Loads: F along the current x' and the couple -c F along the current y' (c > 0 turns the block so
that theta grows), as drake_route.py re-applies them before every step; here they are one motor
on a site at the CM whose six-component gear is that wrench in the site's (the block's) frame, so
MuJoCo turns them with the block inside its own step.

Contact hardness (chosen on the default scene, 2026-11-28): solref = (--timeconst-steps × dt,
--dampratio), default (2 dt, 1), MuJoCo's own floor (refsafe) and the hardest that is stable: with
refsafe off, 1 dt threw the block 13 m up and 0.5 dt diverged. solimp --solimp, default
0.99 0.999 0.001 (impedance 0.99 at contact, 0.999 beyond 1 mm; 0.9 0.95 or 0.999 0.9999 move
the route by less than the hopping below does). --impratio (1) for the friction directions and
--noslip (0) changed little; --margin (0) > 0 made it worse. Integrator --integrator: Euler
(MuJoCo's default, semi-implicit), implicitfast or RK4. Pyramidal cones (--cone) are ~50 % off.
The run is mujoco.rollout (the steps in C, the states of every step returned): no Python runs
per step.

What it shows: MuJoCo's contacts are a convex (Anitescu-like) relaxation of Coulomb's, in which
a sliding contact's solution separates at a normal speed of mu times its slip speed (measured
at dt = 0.25 ms: contact 0 leaves its plane at 0.44-0.53 times its slip speed, median 0.48, for
mu = 0.40). The block hops from its first steps (at 1 ms all three spheres touch in 0.3 % of
steps; by 2-3 s it rises tens of mm between touches), and as dt falls it converges, but to a
route of its own: it turns faster than ours (peers.py; docs/performance.md, "Against Drake and
MuJoCo").

Writes CSV like drake_route.py: t_s,x_m,y_m,z_m,theta_deg,p0x_m,...,p2z_m at every step, and
prints the travel (the sum of the CM's 3-D chords at every step), the final CM and the share of
steps in which each sphere, and all three, touch their planes (within the margin).

Plain [block] scenes on the paper's three planes only (no monolith, faces, record or seismic).
"""
import argparse
import csv
import math
import sys
import tomllib

import numpy as np
import mujoco
import mujoco.rollout

SPHERE_RADIUS = 1e-3


def load(path):
    with open(path, "rb") as f:
        s = tomllib.load(f)
    for key in ("monolith", "water", "seismic"):
        if key in s:
            sys.exit(f"{path}: [{key}]: the MuJoCo peer takes a plain [block] only")
    fr, fo, lo, fi, bl = s["frame"], s["foundation"], s["loads"], s["friction"], s["block"]
    if "plane" in fo or "surface" in fo or "contacts_m" in fr:
        sys.exit(f"{path}: the MuJoCo peer takes the paper's frame and three planes only")
    if fi.get("model") != "coulomb" or "cohesion_pa" in fi or "face" in fi:
        sys.exit(f"{path}: friction: the MuJoCo peer takes one Coulomb friction")
    corners = [
        np.array([-fr["l1x"], 0.0, fr["l1z"]]),
        np.array([fr["l2x"], 0.0, fr["l1z"]]),
        np.array([fr["l2x"], 0.0, -fr["l2z"]]),
    ]
    xi, zeta, kappa = (math.radians(fo[k]) for k in ("xi_deg", "zeta_deg", "kappa_deg"))
    normals = [
        np.array([0.0, 1.0, 0.0]),
        np.array([-math.sin(xi), math.cos(xi), 0.0]),
        np.array([-math.sin(zeta) * math.cos(kappa), math.cos(zeta),
                  math.sin(zeta) * math.sin(kappa)]),
    ]
    iy = bl["inertia_kg_m2"]
    return dict(corners=corners, normals=normals, mass=bl["mass_kg"], iy=iy,
                ix=bl.get("inertia_x_kg_m2", iy / 2), iz=bl.get("inertia_z_kg_m2", iy / 2),
                ixz=bl.get("inertia_xz_kg_m2", 0.0), force=lo.get("hydraulic_force_n", 0.0),
                c=lo["eccentricity_m"], g=lo["gravity_m_s2"], mu=fi["mu_k"],
                init=s.get("initial", {}))


def initial_twist(p):
    """drake_route.py's: v_X, v_Z and the yaw rate from [initial]; v_Y, w_X, w_Z such that every
    contact's velocity along its plane's normal vanishes."""
    init = p["init"]
    vx, vz = init.get("vx_m_s", 0.0), init.get("vz_m_s", 0.0)
    wy = -math.radians(init.get("omega_deg_s", 0.0))
    a, b = np.zeros((3, 3)), np.zeros(3)
    for k, (n, r) in enumerate(zip(p["normals"], p["corners"])):
        a[k] = [n[1], -n[1] * r[2] + n[2] * r[1], -n[0] * r[1] + n[1] * r[0]]
        b[k] = -(n[0] * (vx + wy * r[2]) + n[2] * (vz - wy * r[0]))
    vy, wx, wz = np.linalg.solve(a, b)
    return np.array([vx, vy, vz]), np.array([wx, wy, wz])


def vec(v):
    return " ".join(repr(float(x)) for x in v)


def mjcf(p, a):
    """The scene as MJCF."""
    tc = a.timeconst_steps * a.dt
    contact = (f'condim="3" friction="{p["mu"]!r} 0 0" solref="{tc!r} {a.dampratio!r}" '
               f'solimp="{a.solimp}" margin="{a.margin!r}"')
    spheres = "\n".join(
        f'      <geom name="contact{i}" type="sphere" size="{a.radius!r}" pos="{vec(c)}" '
        f'contype="{1 << i}" conaffinity="0" mass="0" {contact}/>'
        for i, c in enumerate(p["corners"]))
    planes = "\n".join(
        f'    <geom name="plane{j}" type="plane" size="0 0 1" pos="{vec(c - a.radius * n)}" '
        f'zaxis="{vec(n)}" contype="0" conaffinity="{1 << j}" {contact}/>'
        for j, (n, c) in enumerate(zip(p["normals"], p["corners"])))
    # Products of inertia: MuJoCo's fullinertia is (Ixx Iyy Izz Ixy Ixz Iyz) of the tensor, whose
    # off-diagonal terms are -∫x'z' dm (as Drake's RotationalInertia takes them).
    inertia = f'fullinertia="{vec([p["ix"], p["iy"], p["iz"], 0.0, -p["ixz"], 0.0])}"'
    force, couple = p["force"], -p["c"] * p["force"]
    return f"""<mujoco model="slideroute-block">
  <option timestep="{a.dt!r}" gravity="0 {-p['g']!r} 0" integrator="{a.integrator}"
          cone="{a.cone}" impratio="{a.impratio!r}" iterations="{a.iterations}"
          tolerance="{a.tolerance!r}" noslip_iterations="{a.noslip}">
    <flag refsafe="{'enable' if a.refsafe else 'disable'}"/>
  </option>
  <worldbody>
{planes}
    <body name="block" pos="0 0 0">
      <freejoint name="free"/>
      <inertial pos="0 0 0" mass="{p['mass']!r}" {inertia}/>
{spheres}
      <site name="cm" pos="0 0 0"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="water" site="cm" gear="{force!r} 0 0 0 {couple!r} 0"/>
  </actuator>
</mujoco>
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--t-end", type=float, default=3.0)
    ap.add_argument("--dt", type=float, default=1e-3)
    ap.add_argument("--out", help="CSV of every step (omitted: only the summary is printed)")
    ap.add_argument("--radius", type=float, default=SPHERE_RADIUS, help="contact sphere, m")
    ap.add_argument("--timeconst-steps", type=float, default=2.0,
                    help="solref's time constant in steps (MuJoCo keeps it at 2 or more)")
    ap.add_argument("--dampratio", type=float, default=1.0)
    ap.add_argument("--solimp", default="0.99 0.999 0.001")
    ap.add_argument("--impratio", type=float, default=1.0)
    ap.add_argument("--margin", type=float, default=0.0)
    ap.add_argument("--integrator", default="Euler", choices=["Euler", "implicitfast", "RK4"])
    ap.add_argument("--cone", default="elliptic", choices=["elliptic", "pyramidal"])
    ap.add_argument("--no-refsafe", dest="refsafe", action="store_false",
                    help="let solref's time constant go under 2 dt")
    ap.add_argument("--iterations", type=int, default=100)
    ap.add_argument("--tolerance", type=float, default=1e-10, help="the solver's")
    ap.add_argument("--noslip", type=int, default=0, help="noslip_iterations")
    ap.add_argument("--print-xml", action="store_true")
    a = ap.parse_args()
    p = load(a.scene)
    xml = mjcf(p, a)
    if a.print_xml:
        print(xml)
        return
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    v0, w0 = initial_twist(p)
    # A free joint's velocity: the CM's linear velocity in the world, the angular velocity in
    # the body's frame (here the world's at t = 0).
    data.qvel[:] = np.concatenate([v0, w0])
    data.ctrl[:] = 1.0
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state0 = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_getState(model, data, state0, spec)
    steps = int(round(a.t_end / a.dt))
    state, _ = mujoco.rollout.rollout(model, data, state0, np.ones((1, 1)), nstep=steps)
    # FULLPHYSICS begins with time, qpos (x, y, z, quaternion w x y z), qvel.
    st = np.vstack([state0[None, :], state[0]])
    t, pos, quat = st[:, 0], st[:, 1:4], st[:, 4:8]
    rot = np.empty((len(st), 9))
    for k in range(len(st)):
        mujoco.mju_quat2Mat(rot[k], quat[k])
    rot = rot.reshape(-1, 3, 3)
    travel = float(np.sum(np.linalg.norm(np.diff(pos, axis=0), axis=1)))
    theta = np.degrees(np.arctan2(rot[:, 2, 0], rot[:, 0, 0]))
    contacts = [pos + rot @ c for c in p["corners"]]
    # Each sphere's gap to its plane (its centre's height over the plane, less the radius, which
    # the plane was lowered by): touching where it is within the margin.
    gaps = np.stack([(q - c) @ n for q, n, c in zip(contacts, p["normals"], p["corners"])], 1)
    touch = gaps[1:] <= a.margin
    end = pos[-1]
    print(f"travel_m {travel:.9f}")
    flat = float(np.sum(np.linalg.norm(np.diff(pos[:, [0, 2]], axis=0), axis=1)))
    print(f"horizontal_travel_m {flat:.9f}")
    print(f"cm_m {end[0]:.9f} {end[1]:.9f} {end[2]:.9f}")
    print(f"theta_deg {theta[-1]:.6f}")
    print(f"t_s {t[-1]:.9f} steps {steps}")
    print("touching " + " ".join(f"{x:.6f}" for x in touch.mean(0))
          + f" all {np.all(touch, 1).mean():.6f}")
    print(f"gap_m min {gaps.min():.3e} max {gaps.max():.3e}")
    if a.out:
        with open(a.out, "w", newline="") as out:
            w = csv.writer(out)
            w.writerow(["t_s", "x_m", "y_m", "z_m", "theta_deg"]
                       + [f"p{k}{x}_m" for k in range(3) for x in "xyz"])
            w.writerows(np.column_stack([t, pos, theta, *contacts]).tolist())


if __name__ == "__main__":
    main()
