#!/usr/bin/env python3
"""The path of a slideroute scene's block in Drake (pydrake), for the cross-check of the
rigid-body mode. Independent of slideroute's code: it reads only the scene file.

Model: one free rigid body (mass, full inertia tensor about the CM in the block axes x', y', z')
with three small spheres welded at the contact points; each sphere collides only with its own
half-space (contact 0 with the horizontal plane, 1 with plane 1, 2 with plane 2; "from the
perspective of contact 2, plane 1 does not exist"). Point contact with a stiff penalty
(1e11 N/m combined), Coulomb friction mu_k, the TAMSI solver, time step dt. Each step the
hydraulic force F is re-applied along the current x' and its couple -c F along the current y'
(c > 0 turns the block so that theta grows). Coordinates are slideroute's: X forward, Y up,
Z lateral, gravity -g Y; the block starts flat with its CM at the origin.

The scene's [initial] section (vx_m_s, vz_m_s, omega_deg_s; default at rest) gives the motion
at t = 0: the block's twist is those rates made consistent with the three contacts staying on
their planes (the CM's vertical velocity and the roll and pitch rates solved from the three
normal-velocity constraints, as slideroute's velocity projection does).

A foundation of faces (`[[foundation.plane]]`) is the union of the faces'
half-spaces (the rock below the highest face), and every sphere collides with every face: a
contact rides a crease or crosses onto another face as Drake's contact forces decide. The frame
may be any triangle (`contacts_m`). --radius, --stiffness and --dissipation refine the contact
(tiny spheres, stiff contact, near-plastic impacts) until the path no longer changes.

A ground-motion record (`[seismic] record`: CSV t_s, ax_g, ay_g, az_g, found beside
the scene) moves the foundation itself: the half-spaces belong to a ground body on three
prismatic joints (X, Y, Z), a million times the block's mass, driven by joint forces that give it
the record's acceleration (each step's mean of the record, linear between samples; gravity on
it balanced); the block's loads at the contacts move it by a millionth of that. Positions are
written relative to the ground, as slideroute's route is. Pseudo-static kh, kv are forces
kh m g along +X and kv m g along +Y at the CM.

A monolith (`[monolith]`, `[water]`) is computed here from the file on its own: the
section's mass, centre of mass (ȳ above the base) and inertia tensor (Green's theorem on the
polygon heel, top of the upstream face, crest, toe), and the water's loads as body-fixed forces
at their points: the reservoir's push on the upstream face, the tailwater's push and weight on the
downstream face, the uplift (linear, or EM 1110-2-2100's bilinear head with drains) on the base,
and the lateral eccentricity's couple. The contact spheres sit ȳ below the centre of mass. The
written path is then of the base point under the centre of mass, as slideroute's is.

Writes CSV: t_s,x_m,y_m,z_m,theta_deg,p0x_m,...,p2z_m (theta: yaw of x' from +X towards +Z; pK:
contact K's position, so that a reader sees where each contact is, e.g. past a strike line).
"""
import argparse
import csv
import json
import math
import sys
import tomllib

import numpy as np
from pydrake.geometry import (
    AddContactMaterial,
    CollisionFilterDeclaration,
    GeometrySet,
    HalfSpace,
    ProximityProperties,
    Sphere,
)
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.math import SpatialForce, SpatialVelocity
from pydrake.multibody.plant import (
    AddMultibodyPlant,
    CoulombFriction,
    ExternallyAppliedSpatialForce,
    MultibodyPlantConfig,
)
from pydrake.multibody.tree import RotationalInertia, SpatialInertia
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

SPHERE_RADIUS = 1e-3  # m: small against L, large against the penetration (~1e-4 m)
STIFFNESS = 2e11  # N/m per geometry: 1e11 N/m combined in series
DISSIPATION = 1.0  # s/m, Hunt-Crossley
GROUND_MASS_RATIO = 1e6  # a shaken ground's mass over the block's


def section(m):
    """Mass, centre of mass (x̄ from the heel, ȳ above the base) and the inertia (I_x', I_y',
    I_z', I_x'y') about it of a [monolith]: vertical upstream face, crest, straight downstream
    face; z' across the width."""
    b, w, h, c, rho = (m["base_length_m"], m["width_m"], m["height_m"], m["crest_length_m"],
                       m["density_kg_m3"])
    pts = [(0.0, 0.0), (b, 0.0), (c, h), (0.0, h)]  # counter-clockwise
    a = sx = sy = sxx = syy = sxy = 0.0
    for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]):
        d = x0 * y1 - x1 * y0
        a += d / 2
        sx += (x0 + x1) * d / 6
        sy += (y0 + y1) * d / 6
        sxx += (x0 * x0 + x0 * x1 + x1 * x1) * d / 12
        syy += (y0 * y0 + y0 * y1 + y1 * y1) * d / 12
        sxy += (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * d / 24
    mass = rho * w * a
    xb, yb = sx / a, sy / a
    jx = rho * w * (sxx - a * xb * xb)
    jy = rho * w * (syy - a * yb * yb)
    ixy = rho * w * (sxy - a * xb * yb)
    return mass, xb, yb, (jy + mass * w * w / 12, jx + mass * w * w / 12, jx + jy, ixy)


def water_forces(s, xb, yb, g):
    """The water's loads as (point, force) in the block axes (x', y', z') about the centre of
    mass, and the net push along x' (for the eccentricity's couple)."""
    m, wa = s["monolith"], s["water"]
    b, w, h, c = m["base_length_m"], m["width_m"], m["height_m"], m["crest_length_m"]
    h1, h2 = wa["headwater_m"], wa.get("tailwater_m", 0.0)
    gamma = wa.get("density_kg_m3", 1000.0) * g
    e, xd = wa.get("drain_efficiency", 0.0), wa.get("drain_position_m", 0.0)
    out = []
    # Reservoir on the vertical upstream face, wetted to min(H1, h).
    top = min(h1, h)
    push = gamma * w * (h1 * top - top * top / 2)
    at = (h1 * top ** 2 / 2 - top ** 3 / 3) / (h1 * top - top * top / 2)
    out.append(((0.0 - xb, at - yb), (push, 0.0)))
    # Tailwater on the downstream face (slope s horizontal per vertical).
    slope = (b - c) / h
    if h2 > 0:
        out.append(((b - slope * h2 / 3 - xb, h2 / 3 - yb), (-0.5 * gamma * h2 * h2 * w, 0.0)))
        out.append(((b - slope * h2 / 3 - xb, 0.0 - yb),
                    (0.0, -0.5 * gamma * h2 * h2 * slope * w)))
    # Uplift: the head diagram from heel to toe, with drains EM 1110-2-2100's bilinear one.
    if e > 0:
        h3 = h2 + (1 - e) * (h1 - h2) * (b - xd) / b
        diagram = [(0.0, h1), (xd, h3), (b, h2)]
    else:
        diagram = [(0.0, h1), (b, h2)]
    for (x0, p0), (x1, p1) in zip(diagram, diagram[1:]):
        force = gamma * w * (x1 - x0) * (p0 + p1) / 2
        if force > 0:
            x = (x1 - x0) * (p0 * (2 * x0 + x1) + p1 * (x0 + 2 * x1)) / 6 / ((x1 - x0) * (p0 + p1) / 2)
            out.append(((x - xb, 0.0 - yb), (0.0, force)))
    net = push - (0.5 * gamma * h2 * h2 * w if h2 > 0 else 0.0)
    return [(np.array([x, y, 0.0]), np.array([fx, fy, 0.0])) for (x, y), (fx, fy) in out], net


def load(path, surface=False):
    """The scene's block, loads and ground as one dict. A triangulated `[foundation] surface`
    is refused unless `surface` (drake_body.py's prisms); then p["surface"] is the OBJ's path."""
    with open(path, "rb") as f:
        s = tomllib.load(f)
    fr, fo, lo, fi = s["frame"], s["foundation"], s["loads"], s["friction"]
    if fi.get("model") != "coulomb":
        sys.exit(f"{path}: friction.model: the Drake cross-check supports coulomb only")
    if "cohesion_pa" in fi or "face" in fi:
        sys.exit(f"{path}: friction: the Drake cross-check has one Coulomb friction, no cohesion")
    height, water, net = 0.0, [], lo.get("hydraulic_force_n", 0.0)
    if "monolith" in s:
        mass, xb, height, (ix, iy, iz, ixy) = section(s["monolith"])
        bl = {"mass_kg": mass, "inertia_kg_m2": iy, "inertia_x_kg_m2": ix,
              "inertia_z_kg_m2": iz}
        if "water" in s:
            water, net = water_forces(s, xb, height, lo["gravity_m_s2"])
    else:
        bl = s["block"]
        ixy = 0.0
    iy = bl["inertia_kg_m2"]
    if "contacts_m" in fr:
        corners = [np.array([x, 0.0, z]) for x, z in fr["contacts_m"]]
    else:
        corners = [
            np.array([-fr["l1x"], 0.0, fr["l1z"]]),
            np.array([fr["l2x"], 0.0, fr["l1z"]]),
            np.array([fr["l2x"], 0.0, -fr["l2z"]]),
        ]
    obj = None
    if "surface" in fo:
        if not surface:
            sys.exit(f"{path}: foundation.surface: the Drake cross-check takes planes only")
        import os
        obj = os.path.join(os.path.dirname(os.path.abspath(path)), fo["surface"])
    faces = None
    if "plane" in fo:
        faces = []
        for f in fo["plane"]:
            d, a = math.radians(f["dip_deg"]), math.radians(f["dip_direction_deg"])
            n = np.array([math.sin(d) * math.cos(a), math.cos(d), math.sin(d) * math.sin(a)])
            faces.append((n, np.array(f["point_m"], dtype=float)))
    seismic = s.get("seismic", {})
    record = None
    if "record" in seismic:
        import os
        folder = os.path.dirname(os.path.abspath(path))
        data = np.loadtxt(os.path.join(folder, seismic["record"]), delimiter=",", skiprows=1,
                          ndmin=2)
        record = (data[:, 0], data[:, 1:4])
    # The base (slideroute's `contacts = "base"`): [base] outline_m (from the heel and the
    # width's middle for a monolith, about the CM for a block), a monolith's base rectangle, or
    # the bounding box of the frame's contacts; corners (x', z') about the CM.
    shift = 0.0
    if "monolith" in s:
        shift = section(s["monolith"])[1]
    if "base" in s and "outline_m" in s["base"]:
        outline = [(x - shift, z) for x, z in s["base"]["outline_m"]]
    elif "monolith" in s:
        b, w = s["monolith"]["base_length_m"], s["monolith"]["width_m"]
        outline = [(-shift, -w / 2), (b - shift, -w / 2), (b - shift, w / 2), (-shift, w / 2)]
    else:
        xs, zs = [c[0] for c in corners], [c[2] for c in corners]
        outline = [(min(xs), min(zs)), (max(xs), min(zs)), (max(xs), max(zs)), (min(xs), max(zs))]
    return dict(
        corners=corners, faces=faces, record=record, outline=outline, surface=obj,
        kh=seismic.get("kh", 0.0), kv=seismic.get("kv", 0.0),
        xi=math.radians(fo.get("xi_deg", 0.0)), zeta=math.radians(fo.get("zeta_deg", 0.0)),
        kappa=math.radians(fo.get("kappa_deg", 0.0)),
        mass=bl["mass_kg"], iy=iy,
        ix=bl.get("inertia_x_kg_m2", iy / 2), iz=bl.get("inertia_z_kg_m2", iy / 2),
        ixz=bl.get("inertia_xz_kg_m2", 0.0),
        force=net, c=lo["eccentricity_m"], g=lo["gravity_m_s2"],
        height=height, water=water, ixy=ixy, plain="monolith" not in s or "water" not in s,
        mu=fi["mu_k"],
        init=s.get("initial", {}),
    )


def base_points(outline, n):
    """Points of the base polygon (x', z') as (x', 0, z'): its corners, n along each edge, and
    an n × n grid inside."""
    pts = []
    m = len(outline)
    for k in range(m):
        (x0, z0), (x1, z1) = outline[k], outline[(k + 1) % m]
        for j in range(n):
            t = j / n
            pts.append((x0 + t * (x1 - x0), z0 + t * (z1 - z0)))
    xs, zs = [x for x, _ in outline], [z for _, z in outline]

    def inside(x, z):
        c = False
        for k in range(m):
            (xa, za), (xb, zb) = outline[k], outline[(k + 1) % m]
            if (za > z) != (zb > z) and x < xa + (z - za) / (zb - za) * (xb - xa):
                c = not c
        return c

    for i in range(1, n):
        for j in range(1, n):
            x = min(xs) + (max(xs) - min(xs)) * i / n
            z = min(zs) + (max(zs) - min(zs)) * j / n
            if inside(x, z):
                pts.append((x, z))
    return [np.array([x, 0.0, z]) for x, z in pts]


def base_weights(outline, n):
    """The share of the base's area each of base_points(outline, n) stands for, relative to the
    mean (the trapezoid rule on the grid): 1 inside, 1/2 on an edge, 1/4 at a corner. A grid of
    equal springs over-weights the base's rim by O(1/n) (its yaw converges slowly, at first
    order); springs in these proportions are a uniform bed to second order. Exact for a
    rectangle; for another outline the rim's shares are only near."""
    m = len(outline)
    w = []
    for _ in range(m):
        for j in range(n):
            w.append(0.25 if j == 0 else 0.5)
    inside = len(base_points(outline, n)) - len(w)
    w += [1.0] * inside
    mean = sum(w) / len(w)
    return [x / mean for x in w]


def sphere_stiffness(ground, combined):
    """The stiffness of a base sphere whose contact with a ground geometry of stiffness `ground`
    has the stiffness `combined` (Drake combines them as k1 k2 / (k1 + k2))."""
    combined = min(combined, 0.9 * ground)
    return ground * combined / (ground - combined)


def planes(p):
    """Upward unit normal and a point of each foundation plane: the paper's three, each through
    its contact's start (conventions.md), or the scene's faces."""
    if p["faces"] is not None:
        return p["faces"]
    xi, zeta, kappa = p["xi"], p["zeta"], p["kappa"]
    c = p["corners"]
    return [
        (np.array([0.0, 1.0, 0.0]), c[0]),
        (np.array([-math.sin(xi), math.cos(xi), 0.0]), c[1]),
        (
            np.array([-math.sin(zeta) * math.cos(kappa), math.cos(zeta),
                      math.sin(zeta) * math.sin(kappa)]),
            c[2],
        ),
    ]


def start_normals(p):
    """The normal of the plane each contact starts on: its own (the paper's), or the highest
    face over it (the first of equal ones)."""
    if p["faces"] is None:
        return [n for n, _ in planes(p)]
    out = []
    for c in p["corners"]:
        heights = [(pt @ n - n[0] * c[0] - n[2] * c[2]) / n[1] for n, pt in p["faces"]]
        out.append(p["faces"][int(np.argmax(heights))][0])
    return out


def initial_twist(p, corners, normals):
    """(v, w) at the flat start: v_X, v_Z and the yaw rate from [initial]; v_Y, w_X, w_Z such
    that every contact's velocity along its plane's normal vanishes. At θ = 0 the yaw rate is
    -w_Y (theta grows from +X towards +Z)."""
    init = p["init"]
    vx, vz = init.get("vx_m_s", 0.0), init.get("vz_m_s", 0.0)
    wy = -math.radians(init.get("omega_deg_s", 0.0))
    # n·(v + w × r) = 0 with unknowns (v_Y, w_X, w_Z): w × r = (wY rz - wZ ry, wZ rx - wX rz, wX ry - wY rx)
    a, b = np.zeros((3, 3)), np.zeros(3)
    for k, (n, r) in enumerate(zip(normals, corners)):
        # coefficients of v_Y, w_X, w_Z
        a[k] = [n[1], -n[1] * r[2] + n[2] * r[1], -n[0] * r[1] + n[1] * r[0]]
        b[k] = -(n[0] * (vx + wy * r[2]) + n[2] * (vz - wy * r[0]))
    vy, wx, wz = np.linalg.solve(a, b)
    return np.array([vx, vy, vz]), np.array([wx, wy, wz])


def ground_velocity(record, g):
    """V(t) = ∫ a dt of the record (m/s along X, Y, Z), linear between samples, zero outside."""
    t, a = record
    # Velocity at each sample: trapezoids.
    v = np.vstack([np.zeros(3), np.cumsum(0.5 * (a[1:] + a[:-1]) * np.diff(t)[:, None], axis=0)])

    def at(s):
        if s <= t[0]:
            return np.zeros(3)
        if s >= t[-1]:
            return v[-1] * g
        k = int(np.searchsorted(t, s, side="right")) - 1
        h = s - t[k]
        slope = (a[k + 1] - a[k]) / (t[k + 1] - t[k])
        return (v[k] + a[k] * h + 0.5 * slope * h * h) * g

    return at


def applied_loads(p, block, rot, below):
    """The scene's loads on the block at the pose whose rotation (body to world) is `rot`, as
    Drake's externally applied spatial forces: the eccentricity's couple -c F along y' and the
    pseudo-static forces kh m g, kv m g at the centre of mass; the push F along x' at the base
    point under it (`below`, body axes), or the water's loads where they act."""
    def applied(point, torque, force):
        f = ExternallyAppliedSpatialForce()
        f.body_index = block.index()
        f.p_BoBq_B = point
        f.F_Bq_W = SpatialForce(torque, force)
        return f

    i_axis, j_axis = rot[:, 0], rot[:, 1]
    seismic = np.array([p["kh"], p["kv"], 0.0]) * p["mass"] * p["g"]
    forces = [applied(np.zeros(3), -p["c"] * p["force"] * j_axis, seismic)]
    if p["plain"]:
        forces.append(applied(below, np.zeros(3), p["force"] * i_axis))
    for point, force in p["water"]:
        forces.append(applied(point, np.zeros(3), rot @ force))
    return forces


def add_block_and_ground(plant, p):
    """The block (its inertia about the CM; gravity along -Y) and the body the foundation
    belongs to: the world, or, under a record, a heavy body on three prismatic joints the record
    drives. Returns (block, ground, joints)."""
    # Product of inertia I_xz = ∫x'z' dm enters the tensor as -I_xz.
    inertia = RotationalInertia(p["ix"], p["iy"], p["iz"], -p["ixy"], -p["ixz"], 0.0)
    block = plant.AddRigidBody(
        "block", SpatialInertia.MakeFromCentralInertia(p["mass"], np.zeros(3), inertia)
    )
    plant.mutable_gravity_field().set_gravity_vector([0.0, -p["g"], 0.0])
    ground = plant.world_body()
    joints = []
    if p["record"] is not None:
        from pydrake.multibody.tree import PrismaticJoint
        big = GROUND_MASS_RATIO * p["mass"]
        parent = plant.world_body()
        for k, axis in enumerate(np.eye(3)):
            body = plant.AddRigidBody(
                f"ground{k}", SpatialInertia.MakeFromCentralInertia(
                    big, np.zeros(3), RotationalInertia(big, big, big)))
            joints.append(plant.AddJoint(PrismaticJoint(
                f"ground_{'xyz'[k]}", plant.world_frame() if k == 0 else parent.body_frame(),
                body.body_frame(), axis)))
            parent = body
        ground = parent
    return block, ground, joints


def contact_properties(a, p, stiffness=None):
    """Point contact's properties: Hunt-Crossley dissipation and stiffness (the command line's
    unless given), Coulomb's mu (static = dynamic)."""
    pp = ProximityProperties()
    k = a.stiffness if stiffness is None else stiffness
    AddContactMaterial(a.dissipation, k, CoulombFriction(p["mu"], p["mu"]), pp)
    return pp


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--t-end", type=float, default=3.0)
    ap.add_argument("--dt", type=float, default=1e-3)
    ap.add_argument("--out", required=True)
    ap.add_argument("--radius", type=float, default=SPHERE_RADIUS, help="contact sphere, m")
    ap.add_argument("--stiffness", type=float, default=STIFFNESS, help="per geometry, N/m")
    ap.add_argument("--dissipation", type=float, default=DISSIPATION, help="Hunt-Crossley, s/m")
    ap.add_argument("--base", action="store_true",
                    help="the block's whole base: spheres on a grid over its footprint, every one"
                         " against every face (slideroute's contacts = \"base\")")
    ap.add_argument("--grid", type=int, default=9, help="base: grid points along each side")
    ap.add_argument("--equal-springs", action="store_true",
                    help="base: every grid point's spring alike (the rim then over-weighted)")
    ap.add_argument("--start", help="base: slideroute's summary.json, whose base.resting pose"
                                    " the block starts in")
    ap.add_argument("--mu-delta", type=float, default=0.0, help="added to mu (chaos check)")
    a = ap.parse_args()
    p = load(a.scene)
    p["mu"] += a.mu_delta

    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(
        MultibodyPlantConfig(time_step=a.dt, contact_model="point",
                             discrete_contact_approximation="tamsi"),
        builder,
    )
    block, ground, joints = add_block_and_ground(plant, p)

    def props(stiffness=None):
        return contact_properties(a, p, stiffness)

    corners = p["corners"]
    # The base plane lies ȳ below the centre of mass (a monolith's; zero for [block]).
    below = np.array([0.0, -p["height"], 0.0])
    spheres, halves = [], []
    points = base_points(p["outline"], a.grid) if a.base else corners
    # On a base, each sphere's spring in proportion to the area it stands for (a uniform bed),
    # unless --equal-springs; the mean combined stiffness as two equal ones give.
    weights = ([1.0] * len(points) if (not a.base or a.equal_springs or a.grid <= 1)
               else base_weights(p["outline"], a.grid))
    for i, corner in enumerate(points):
        # The sphere's centre is the contact point; each plane is lowered by the radius.
        k = sphere_stiffness(a.stiffness, 0.5 * a.stiffness * weights[i])
        spheres.append(plant.RegisterCollisionGeometry(
            block, RigidTransform(corner + below), Sphere(a.radius), f"contact{i}", props(k)))
    for j, (n, point) in enumerate(planes(p)):
        halves.append(plant.RegisterCollisionGeometry(
            ground, RigidTransform(HalfSpace.MakePose(n, point - a.radius * n)),
            HalfSpace(), f"plane{j}", props()))
    plant.Finalize()
    if p["faces"] is None and not a.base:
        # The paper's model: each contact sees only its own plane.
        decl = CollisionFilterDeclaration()
        for i, s in enumerate(spheres):
            for j, h in enumerate(halves):
                if i != j:
                    decl.ExcludeBetween(GeometrySet(s), GeometrySet(h))
        scene_graph.collision_filter_manager().Apply(decl)

    diagram = builder.Build()
    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    if a.base:
        # Where slideroute set the block down, and the scene's rates as slideroute takes them.
        with open(a.start) as f:
            rest = json.load(f)["base"]["resting"]
        pose0 = RigidTransform(RotationMatrix(np.array(rest["rotation"])),
                               np.array([rest["x_m"], rest["y_m"], rest["z_m"]]))
        plant.SetFreeBodyPose(plant_context, block, pose0)
        i0 = p["init"]
        v0 = np.array([i0.get("vx_m_s", 0.0), 0.0, i0.get("vz_m_s", 0.0)])
        w0 = np.array([0.0, -math.radians(i0.get("omega_deg_s", 0.0)), 0.0])
        plant.SetFreeBodySpatialVelocity(plant_context, block, SpatialVelocity(w0, v0))
    else:
        plant.SetFreeBodyPose(plant_context, block, RigidTransform(-below))
    if p["height"] > 0 and p["init"] and not a.base:
        sys.exit(f"{a.scene}: initial: the Drake cross-check starts a monolith at rest only")
    v0, w0 = initial_twist(p, corners, start_normals(p)) if not a.base else (v0, w0)
    plant.SetFreeBodySpatialVelocity(plant_context, block, SpatialVelocity(w0, v0))
    port = plant.get_applied_spatial_force_input_port()
    if joints:
        # The joint forces that give the ground the record's mean acceleration over each step
        # (the X joint carries three bodies, Y two, Z one; Y's also holds them against gravity).
        velocity = ground_velocity(p["record"], p["g"])
        carried = np.array([3.0, 2.0, 1.0]) * GROUND_MASS_RATIO * p["mass"]
        generalized = plant.get_applied_generalized_force_input_port()
        starts = [j.velocity_start() for j in joints]

        def shake(t0, t1):
            tau = np.zeros(plant.num_velocities())
            accel = (velocity(t1) - velocity(t0)) / (t1 - t0)
            accel[1] += p["g"]
            tau[starts] = carried * accel
            generalized.FixValue(plant_context, tau)

    def ground_at():
        if not joints:
            return np.zeros(3)
        return np.array([j.get_translation(plant_context) for j in joints])

    rows = []
    steps = int(round(a.t_end / a.dt))
    for k in range(steps + 1):
        pose = plant.EvalBodyPoseInWorld(plant_context, block)
        rot = pose.rotation().matrix()
        i_axis = rot[:, 0]
        shift = ground_at()
        # The base point under the centre of mass.
        cm = pose.multiply(below) - shift
        t = k * a.dt
        contacts = [pose.multiply(c + below) - shift for c in corners]
        rows.append((t, cm[0], cm[1], cm[2], math.degrees(math.atan2(i_axis[2], i_axis[0])),
                     *[x for c in contacts for x in c]))
        if k == steps:
            break
        port.FixValue(plant_context, applied_loads(p, block, rot, below))
        if joints:
            shake(t, t + a.dt)
        simulator.AdvanceTo((k + 1) * a.dt)

    with open(a.out, "w", newline="") as out:
        w = csv.writer(out)
        w.writerow(["t_s", "x_m", "y_m", "z_m", "theta_deg"]
                   + [f"p{k}{a}_m" for k in range(3) for a in "xyz"])
        w.writerows(rows)


if __name__ == "__main__":
    main()
