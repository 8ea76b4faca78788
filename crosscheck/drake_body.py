#!/usr/bin/env python3
"""The path of a slideroute scene's block on its WHOLE BASE in Drake (pydrake), for the
cross-check of slideroute's base contact model (`[solver] contacts = "base"`,
derivations/13-base-contact.md). Independent of slideroute's code: it reads only the scene file
(and, with --start, the resting pose from slideroute's summary.json).

The base: a flat polygon in the block's plane y' = -ȳ (ȳ the centre of mass's height above the
base: a monolith's, 0 for a [block]), the footprint being `[base] outline_m` (from the heel and
the width's middle for a monolith, about the CM for a block), a monolith's base rectangle, or
the bounding rectangle of the frame's three contacts (drake_route.load works it out). In Drake
it is a grid of point contacts: spheres of 1 mm radius at the corners, --grid points along each
edge and a --grid x --grid grid inside (every L/20 by default). Each sphere's centre is a base
point and the ground is lowered by the radius, so a sphere touching the ground is a base point on
the rock. Point contact gives one contact point per pair of geometries (the deepest), so a
single box or prism as the base would be held at one point that jumps from corner to corner; a
grid of spheres spreads the block's weight over its base as a stiff Winkler bed does.

The ground: `[[foundation.plane]]` faces, each a half-space (the rock under the highest face) when
there are at most 10 of them (Drake 1.51.1 fails with many more half-spaces), else each a large
box whose top face lies on the face's plane; or the paper's three planes, each then seen by every
base point. Over such a convex ground a flat base meets the rock first at its corners and edges
(derivations/13-base-contact.md §2), which the grid has.

A triangulated `[foundation] surface` (OBJ beside the scene): two triangles that make a planar
rectangle (a cell of a grid planar over it) are one Box, 1 m thick, under the cell; every other
triangle is a convex prism (Drake's Convex) reaching 10 m below it. Drake's point contact of a
sphere with a Box is exact; with a Convex it is not (on a 10° plane written as 1280 prisms the
block slid 5.6 % less in 3 s than on the plane's half-space, and thinner prisms were worse), so
a surface of prisms is no converged reference. A surface is not convex: a ridge or a vertex of
it can touch the base between its grid points (a crest 0.25 m from the nearest row of a 0.5 m
grid goes 35 mm into the base at 8°). So the ground also carries spheres of the same radius, their
tops every --ridge-step (0.1 m) along every ridge (a convex edge) and at the ridges' ends, within
--reach of the footprint, which meet a thin plate on the block (a 2 cm Box, or the outline's
convex hull, whose underside is the base); the plate meets only those, and the base's grid only
the cells and prisms.

Contact, friction and loads as drake_route.py: point contact with a stiff penalty (2e11 N/m per
geometry, 1e11 combined), Coulomb friction mu_k (static = dynamic), TAMSI at dt, the loads
(drake_route.applied_loads) re-applied before every step at the current pose; a ground-motion
record shakes the ground body (positions written relative to it). Hunt-Crossley dissipation is
50 s/m (drake_route's 1 s/m bounces, where slideroute's base closes a touch inelastically, and
made TAMSI fail to converge where a ridge met the base along a line of points).

Start: --start summary.json puts the block where slideroute set it down (`resting` or
`base.resting`: the CM and the body-to-world rotation). Without it the block is put flat (its
yaw zero), the point under the CM at the origin (a [block]'s CM at the origin), its base 1 mm
above the highest ground under the footprint, and left to settle under its weight alone (loads
off, friction on) for --settle s (default 1); then its velocities are zeroed and the loads act
from t = 0. Either way the scene's [initial] rates are given as drake_route --base gives them.

Writes CSV every millisecond: t_s, x_m, y_m, z_m (the CM), theta_deg (yaw of x' from +X towards
+Z), tilt_deg (between the body's y' and world Y), min_gap_m (the lowest base grid point's height
above the ground, vertical, negative inside), bx_m, by_m, bz_m (the base point under the CM, what
slideroute's route.csv writes as x_m, y_m, z_m), ridge_gap_m (on a surface: the lowest height of
the base over the ground's vertex and ridge points under the footprint).
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import drake_route as dr  # noqa: E402  (its scene reader, loads and base grid)
from pydrake.geometry import (  # noqa: E402
    CollisionFilterDeclaration,
    GeometrySet,
    Box,
    Convex,
    HalfSpace,
    Sphere,
)
from pydrake.math import RigidTransform, RotationMatrix  # noqa: E402
from pydrake.multibody.math import SpatialVelocity  # noqa: E402
from pydrake.multibody.plant import (  # noqa: E402
    AddMultibodyPlant,
    MultibodyPlantConfig,
)
from pydrake.systems.analysis import Simulator  # noqa: E402
from pydrake.systems.framework import DiagramBuilder  # noqa: E402

MAX_HALF_SPACES = 10  # more than about 12 half-spaces crash Drake 1.51.1
PRISM_DEPTH = 10.0  # m: a surface triangle's prism reaches this far below its lowest vertex
CELL_DEPTH = 1.0  # m: a planar rectangular cell's box, its thickness below the cell
BOX_SIZE = 2000.0  # m: a face as a box (more than MAX_HALF_SPACES faces): its side
BOX_DEPTH = 500.0  # m: and its depth below the face
DISSIPATION = 50.0  # s/m, Hunt-Crossley: near-plastic impacts, as slideroute's base closes a
# touch inelastically (1 s/m, drake_route's, bounces and makes TAMSI fail to converge where a
# ridge meets the base along a line of points)


def read_obj(path):
    """Vertices (n × 3) and triangles (m × 3 indices) of a Wavefront OBJ (polygons fanned)."""
    v, tris = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                v.append([float(x) for x in w[1:4]])
            elif w[0] == "f":
                idx = [int(x.split("/")[0]) for x in w[1:]]
                idx = [i - 1 if i > 0 else len(v) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    tris.append([idx[0], idx[k], idx[k + 1]])
    return np.array(v), np.array(tris, dtype=int)


class Ground:
    """The ground's height Y(X, Z): the highest plane, or the surface's triangle there."""

    def __init__(self, faces=None, surface=None):
        self.faces = faces
        if surface is not None:
            v, t = surface
            self.v, self.t = v, t
            a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
            self.a = a
            # Barycentric solve in (X, Z): q - a = s (b - a) + u (c - a).
            e1, e2 = (b - a)[:, [0, 2]], (c - a)[:, [0, 2]]
            det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
            keep = np.abs(det) > 1e-12  # vertical triangles hold nothing from above
            self.e1, self.e2, self.det, self.keep = e1, e2, det, keep
            self.ya, self.dyb, self.dyc = a[:, 1], (b - a)[:, 1], (c - a)[:, 1]
            lo = np.minimum(np.minimum(a, b), c)[:, [0, 2]]
            hi = np.maximum(np.maximum(a, b), c)[:, [0, 2]]
            self.cell = max(float(np.median(hi - lo)), 1e-3)
            self.origin = lo.min(axis=0)
            self.buckets = {}
            for k in np.nonzero(keep)[0]:
                i0, j0 = np.floor((lo[k] - self.origin) / self.cell).astype(int)
                i1, j1 = np.floor((hi[k] - self.origin) / self.cell).astype(int)
                for i in range(i0, i1 + 1):
                    for j in range(j0, j1 + 1):
                        self.buckets.setdefault((i, j), []).append(k)

    def height(self, xz):
        """Heights (NaN over no ground) at points (n × 2, X and Z)."""
        xz = np.atleast_2d(xz)
        if self.faces is not None:
            hs = [(pt @ n - n[0] * xz[:, 0] - n[2] * xz[:, 1]) / n[1] for n, pt in self.faces]
            return np.max(hs, axis=0)
        out = np.full(len(xz), np.nan)
        ij = np.floor((xz - self.origin) / self.cell).astype(int)
        for q in range(len(xz)):
            ks = self.buckets.get((ij[q, 0], ij[q, 1]))
            if not ks:
                continue
            ks = np.array(ks)
            d = xz[q] - self.a[ks][:, [0, 2]]
            e1, e2, det = self.e1[ks], self.e2[ks], self.det[ks]
            s = (d[:, 0] * e2[:, 1] - d[:, 1] * e2[:, 0]) / det
            u = (e1[:, 0] * d[:, 1] - e1[:, 1] * d[:, 0]) / det
            inside = (s >= -1e-9) & (u >= -1e-9) & (s + u <= 1 + 1e-9)
            if inside.any():
                y = self.ya[ks] + s * self.dyb[ks] + u * self.dyc[ks]
                out[q] = np.max(y[inside])
        return out


def rectangles(v, tris):
    """Pairs of triangles that share an edge and together make a planar rectangle (a cell of a
    grid whose heights are planar over it): each as (its four corners, the two triangles).
    Such a cell is a Box's top face, whose contact with a sphere Drake computes exactly."""
    edges = {}
    for k, t in enumerate(tris):
        for e in range(3):
            a, b = int(t[e]), int(t[(e + 1) % 3])
            edges.setdefault((min(a, b), max(a, b)), []).append(k)
    used, out = set(), []
    for (a, b), ks in edges.items():
        if len(ks) != 2 or ks[0] in used or ks[1] in used:
            continue
        c = [int(x) for x in tris[ks[0]] if x not in (a, b)][0]
        d = [int(x) for x in tris[ks[1]] if x not in (a, b)][0]
        # Diagonal a-b, corners c and d: a rectangle when c-a-d-b has right angles.
        pa, pb, pc, pd = v[a], v[b], v[c], v[d]
        quad = [pc, pa, pd, pb]
        ok = True
        for i in range(4):
            e1 = quad[(i + 1) % 4] - quad[i]
            e2 = quad[(i + 2) % 4] - quad[(i + 1) % 4]
            if abs(e1 @ e2) > 1e-9 * (e1 @ e1 + e2 @ e2):
                ok = False
        if not ok or np.linalg.norm(pa + pb - pc - pd) > 1e-9 * np.linalg.norm(pa - pb):
            continue
        used.update(ks)
        out.append((np.array(quad), ks))
    return out


def ridge_points(v, tris, centre, reach, step):
    """Points of a surface that a flat base can rest on between the base's own grid points:
    points every `step` along every convex edge (a ridge: the neighbouring triangle falls away
    below the plane of the other) and the ridges' ends, within `reach` (horizontally) of
    `centre`."""
    near = np.hypot(v[:, 0] - centre[0], v[:, 2] - centre[1]) <= reach
    pts, ends = [], set()
    edges = {}
    for k, t in enumerate(tris):
        for e in range(3):
            a, b = int(t[e]), int(t[(e + 1) % 3])
            edges.setdefault((min(a, b), max(a, b)), []).append((k, int(t[(e + 2) % 3])))
    ridges = 0
    for (a, b), side in edges.items():
        if len(side) != 2 or not (near[a] or near[b]):
            continue
        (k, _), (_, w) = side
        p0, p1, p2 = v[tris[k]]
        n = np.cross(p1 - p0, p2 - p0)
        if abs(n[1]) < 1e-12:
            continue
        n = n / np.linalg.norm(n) * np.sign(n[1])
        if (v[w] - v[a]) @ n > -1e-9:
            continue  # level or a valley: the faces on either side hold the base there
        ridges += 1
        ends.update((a, b))
        m = max(1, int(math.ceil(np.linalg.norm(v[b] - v[a]) / step)))
        pts.extend(v[a] + (v[b] - v[a]) * j / m for j in range(1, m))
    # The ridges' ends: a peak, a saddle or where a ridge meets level ground. A vertex on a
    # plane or in a hollow is held by its triangles: a point there would only add stiffness
    # (and shift the base's pressure towards it: on a 10° plane with a point at every vertex the
    # yaw at 3 s moved by 2.7°).
    pts.extend(v[i] for i in sorted(ends) if near[i])
    return np.array(pts).reshape(-1, 3), ridges


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--t-end", type=float, default=3.0)
    ap.add_argument("--dt", type=float, default=1e-3)
    ap.add_argument("--mu-delta", type=float, default=0.0, help="added to every mu (chaos check)")
    ap.add_argument("--start", help="slideroute's summary.json: start where it rested")
    ap.add_argument("--settle", type=float, default=1.0, help="without --start: settling time, s")
    ap.add_argument("--save-rest", help="without --start: write the settled pose here, in"
                                        " summary.json's form (for --start of another run)")
    ap.add_argument("--grid", type=int, default=20, help="base points along each side")
    ap.add_argument("--equal-springs", action="store_true",
                    help="every base point's spring alike (the rim then over-weighted)")
    ap.add_argument("--radius", type=float, default=dr.SPHERE_RADIUS, help="contact sphere, m")
    ap.add_argument("--stiffness", type=float, default=dr.STIFFNESS, help="per geometry, N/m")
    ap.add_argument("--dissipation", type=float, default=DISSIPATION,
                    help="Hunt-Crossley, s/m")
    ap.add_argument("--reach", type=float, default=12.0,
                    help="surface: ridge points within this distance of the footprint, m")
    ap.add_argument("--ridge-step", type=float, default=0.1,
                    help="surface: spacing of the points along a ridge, m")
    ap.add_argument("--no-ridges", action="store_true",
                    help="surface: the base's grid against the prisms only (no plate, no"
                         " points at the surface's vertices and ridges)")
    ap.add_argument("--prism-depth", type=float, default=PRISM_DEPTH,
                    help="surface: a triangle's prism reaches this far below it, m")
    ap.add_argument("--all-prisms", action="store_true",
                    help="surface: every triangle a Convex prism, planar rectangular cells too")
    ap.add_argument("--boxes", action="store_true",
                    help="faces as boxes even when there are few of them")
    ap.add_argument("--quiet", action="store_true")
    a = ap.parse_args()
    p = dr.load(a.scene, surface=True)
    p["mu"] += a.mu_delta

    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(
        MultibodyPlantConfig(time_step=a.dt, contact_model="point",
                             discrete_contact_approximation="tamsi"),
        builder,
    )
    block, ground, joints = dr.add_block_and_ground(plant, p)

    def props(stiffness=None):
        return dr.contact_properties(a, p, stiffness)

    below = np.array([0.0, -p["height"], 0.0])
    points = np.array([c + below for c in dr.base_points(p["outline"], a.grid)])
    # Each sphere's spring in proportion to the area it stands for (dr.base_weights: a uniform
    # bed to second order), unless --equal-springs.
    weights = ([1.0] * len(points) if a.equal_springs
               else dr.base_weights(p["outline"], a.grid))
    grid = [plant.RegisterCollisionGeometry(
                block, RigidTransform(q), Sphere(a.radius), f"base{i}",
                props(dr.sphere_stiffness(a.stiffness, 0.5 * a.stiffness * weights[i])))
            for i, q in enumerate(points)]

    # The ground, lowered by the sphere radius (along each face's normal; a surface along Y).
    r = a.radius
    features = np.zeros((0, 3))
    if p["surface"] is not None:
        v, tris = read_obj(p["surface"])
        height = Ground(surface=(v, tris))
        kind = f"surface {os.path.basename(p['surface'])}: {len(tris)} triangles as prisms"
        prisms, knobs = [], []
        if not a.no_ridges:
            # A ridge or a vertex of the ground between the base's grid points would go into
            # the base unseen: points there (spheres on the ground) against a plate on the block
            # whose underside is the base.
            out = p["outline"]
            xs, zs = [x for x, _ in out], [z for _, z in out]
            size = max(math.hypot(x, z) for x, z in out)
            start = (0.0, 0.0)
            if a.start:
                with open(a.start) as f:
                    sm = json.load(f)
                rs = sm["resting"] if "resting" in sm else sm["base"]["resting"]
                start = (rs["x_m"], rs["z_m"])
            features, ridges = ridge_points(v, tris, start, size + a.reach, a.ridge_step)
            kind += (f"; {len(features)} points at its vertices and along {ridges} ridges "
                     f"within {size + a.reach:.1f} m")
            thick = 0.02
            rect = (len(out) == 4 and len(set(xs)) == 2 and len(set(zs)) == 2)
            if rect:
                plate_shape = Box(max(xs) - min(xs), thick, max(zs) - min(zs))
                plate_at = np.array([(max(xs) + min(xs)) / 2, -p["height"] + thick / 2,
                                     (max(zs) + min(zs)) / 2])
            else:  # the outline's convex hull, as a prism
                hull = np.array([[x, y, z] for x, z in out for y in (0.0, thick)])
                plate_at = np.array([0.0, -p["height"], 0.0])
                plate_shape = Convex(hull.T, "base")
            plate = plant.RegisterCollisionGeometry(block, RigidTransform(plate_at), plate_shape,
                                                    "plate", props())
            for i, q in enumerate(features):
                knobs.append(plant.RegisterCollisionGeometry(
                    ground, RigidTransform(q - np.array([0.0, r, 0.0])), Sphere(r),
                    f"knob{i}", props()))
        down = np.array([0.0, r, 0.0])
        boxed = set()
        if not a.all_prisms:
            for j, (quad, ks) in enumerate(rectangles(v, tris)):
                u, w = quad[1] - quad[0], quad[3] - quad[0]
                n = np.cross(w, u)
                if abs(n[1]) < 1e-12:
                    continue
                n = n / np.linalg.norm(n) * np.sign(n[1])
                rot = RotationMatrix(np.column_stack(
                    [u / np.linalg.norm(u), np.cross(n, u / np.linalg.norm(u)), n]))
                # Lowered by the radius along its normal, as a half-space is.
                centre = quad.mean(axis=0) - r * n - CELL_DEPTH / 2 * n
                prisms.append(plant.RegisterCollisionGeometry(
                    ground, RigidTransform(rot, centre),
                    Box(np.linalg.norm(u), np.linalg.norm(w), CELL_DEPTH),
                    f"cell{j}", props()))
                boxed.update(ks)
            kind += f" ({len(boxed) // 2} planar rectangular cells as boxes)"
        for k, t in enumerate(tris):
            if k in boxed:
                continue
            top = v[t] - down
            if abs(np.cross(top[1] - top[0], top[2] - top[0])[1]) < 1e-12:
                continue  # a vertical triangle: its neighbours' prisms already fill below it
            bottom = top.copy()
            bottom[:, 1] = top[:, 1].min() - a.prism_depth
            pts = np.vstack([top, bottom])
            centre = pts.mean(axis=0)
            prisms.append(plant.RegisterCollisionGeometry(
                ground, RigidTransform(centre), Convex((pts - centre).T, f"tri{k}"),
                f"tri{k}", props()))
    else:
        faces = dr.planes(p)
        height = Ground(faces=faces)
        boxes = a.boxes or len(faces) > MAX_HALF_SPACES
        kind = f"{len(faces)} faces as {'boxes' if boxes else 'half-spaces'}"
        for j, (n, point) in enumerate(faces):
            if boxes:
                # The box's +z face on the plane, centred under the origin's projection.
                top = (point @ n) * n - r * n
                rot = RotationMatrix.MakeFromOneVector(n, 2)
                plant.RegisterCollisionGeometry(
                    ground, RigidTransform(rot, top - BOX_DEPTH / 2 * n),
                    Box(BOX_SIZE, BOX_SIZE, BOX_DEPTH), f"face{j}", props())
            else:
                plant.RegisterCollisionGeometry(
                    ground, RigidTransform(HalfSpace.MakePose(n, point - r * n)),
                    HalfSpace(), f"face{j}", props())
    plant.Finalize()
    if len(features):
        # The plate meets the ground's points only; the base's grid meets the prisms only.
        decl = CollisionFilterDeclaration()
        decl.ExcludeBetween(GeometrySet(plate), GeometrySet(prisms))
        decl.ExcludeBetween(GeometrySet(grid), GeometrySet(knobs))
        scene_graph.collision_filter_manager().Apply(decl)

    diagram = builder.Build()
    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    pc = plant.GetMyMutableContextFromRoot(context)
    port = plant.get_applied_spatial_force_input_port()
    if joints:
        velocity = dr.ground_velocity(p["record"], p["g"])
        carried = np.array([3.0, 2.0, 1.0]) * dr.GROUND_MASS_RATIO * p["mass"]
        generalized = plant.get_applied_generalized_force_input_port()
        starts = [j.velocity_start() for j in joints]

        def shake(accel):
            tau = np.zeros(plant.num_velocities())
            tau[starts] = carried * (accel + np.array([0.0, p["g"], 0.0]))
            generalized.FixValue(pc, tau)

    def ground_at():
        if not joints:
            return np.zeros(3)
        return np.array([j.get_translation(pc) for j in joints])

    def state():
        """(CM, rotation, the base points in world axes), relative to the ground."""
        pose = plant.EvalBodyPoseInWorld(pc, block)
        rot = pose.rotation().matrix()
        shift = ground_at()
        cm = pose.translation() - shift
        return cm, rot, cm + points @ rot.T

    def gaps(world):
        return world[:, 1] - height.height(world[:, [0, 2]])

    out_poly = p["outline"]

    def feature_gap(cm, rot):
        """The lowest height (along Y) of the base over the ground's vertex and ridge points
        under the footprint (NaN with none under it)."""
        if not len(features):
            return float("nan")
        body = (features - cm) @ rot  # body axes: x', y', z' about the CM
        near = np.abs(body[:, 1] + p["height"]) < 1.0
        under = [k for k in np.nonzero(near)[0] if _inside(body[k, [0, 2]], out_poly)]
        if not under:
            return float("nan")
        # Height of the base plane above each point, measured along Y.
        return float(np.min((-p["height"] - body[under, 1]) / rot[1, 1]))

    def say(*x):
        if not a.quiet:
            print(*x, file=sys.stderr)

    say(f"{a.scene}: {len(points)} base points (grid {a.grid}), ground {kind}, "
        f"m = {p['mass']:.4g} kg, ȳ = {p['height']:.4g} m, mu = {p['mu']}")
    i0 = p["init"]
    v_init = np.array([i0.get("vx_m_s", 0.0), 0.0, i0.get("vz_m_s", 0.0)])
    w_init = np.array([0.0, -math.radians(i0.get("omega_deg_s", 0.0)), 0.0])
    t0 = 0.0
    if a.start:
        with open(a.start) as f:
            summary = json.load(f)
        rest = summary["resting"] if "resting" in summary else summary["base"]["resting"]
        plant.SetFreeBodyPose(pc, block, RigidTransform(
            RotationMatrix(np.array(rest["rotation"])),
            np.array([rest["x_m"], rest["y_m"], rest["z_m"]])))
    else:
        # Flat, the point under the CM at the origin, 1 mm above the highest ground under the
        # footprint (sampled on a fine grid, plus the surface's vertices inside it).
        fine = np.array([c for c in dr.base_points(p["outline"], 100)])[:, [0, 2]]
        if p["surface"] is not None:
            inside = [q for q in height.v[:, [0, 2]]
                      if _inside(q, p["outline"])]
            if inside:
                fine = np.vstack([fine, inside])
        top = np.nanmax(height.height(fine))
        if np.isnan(height.height(fine)).any():
            sys.exit(f"{a.scene}: part of the footprint is over no ground")
        plant.SetFreeBodyPose(pc, block, RigidTransform(np.array(
            [0.0, top + 1e-3 + p["height"], 0.0])))
        port.FixValue(pc, [])
        if joints:
            shake(np.zeros(3))
        steps = int(round(a.settle / a.dt))
        simulator.AdvanceTo(steps * a.dt)
        t0 = steps * a.dt
        v = plant.EvalBodySpatialVelocityInWorld(pc, block)
        cm, rot, world = state()
        i_axis = rot[:, 0]
        say(f"settled after {a.settle} s: CM ({cm[0]:.6f}, {cm[1]:.6f}, {cm[2]:.6f}) m, "
            f"theta {math.degrees(math.atan2(i_axis[2], i_axis[0])):.4f} deg, "
            f"tilt {math.degrees(math.acos(np.clip(rot[1, 1], -1, 1))):.4f} deg, "
            f"min gap {np.nanmin(gaps(world)):.3e} m (ridge points {feature_gap(cm, rot):.3e} m), "
            f"speed {np.linalg.norm(v.translational()):.2e} m/s, "
            f"turning {np.linalg.norm(v.rotational()):.2e} rad/s")
        say("rotation (body to world, rows):", np.array2string(rot, precision=9))
        if a.save_rest:
            with open(a.save_rest, "w") as f:
                json.dump({"resting": {
                    "x_m": cm[0], "y_m": cm[1], "z_m": cm[2],
                    "theta_deg": math.degrees(math.atan2(i_axis[2], i_axis[0])),
                    "tilt_deg": math.degrees(math.acos(np.clip(rot[1, 1], -1, 1))),
                    "rotation": rot.tolist(), "settled_by": "drake_body.py"}}, f, indent=1)
        if joints:
            for j in joints:
                j.set_translation_rate(pc, 0.0)
    plant.SetFreeBodySpatialVelocity(pc, block, SpatialVelocity(w_init, v_init))

    rows = []
    steps = int(round(a.t_end / a.dt))
    every = max(1, int(round(1e-3 / a.dt)))
    for k in range(steps + 1):
        cm, rot, world = state()
        if k % every == 0 or k == steps:
            i_axis = rot[:, 0]
            base = cm + rot @ below
            rows.append((round(k * a.dt, 9), *cm,
                         math.degrees(math.atan2(i_axis[2], i_axis[0])),
                         math.degrees(math.acos(np.clip(rot[1, 1], -1.0, 1.0))),
                         float(np.nanmin(gaps(world))), *base, feature_gap(cm, rot)))
        if k == steps:
            break
        port.FixValue(pc, dr.applied_loads(p, block, rot, below))
        if joints:
            t = k * a.dt
            shake((velocity(t + a.dt) - velocity(t)) / a.dt)
        simulator.AdvanceTo(t0 + (k + 1) * a.dt)

    with open(a.out, "w", newline="") as out:
        w = csv.writer(out)
        w.writerow(["t_s", "x_m", "y_m", "z_m", "theta_deg", "tilt_deg", "min_gap_m",
                    "bx_m", "by_m", "bz_m", "ridge_gap_m"])
        w.writerows(rows)
    last = rows[-1]
    travel = sum(math.hypot(b[1] - c[1], b[3] - c[3]) for b, c in zip(rows[1:], rows))
    ridge = [x[10] for x in rows if not math.isnan(x[10])]
    say(f"t = {last[0]:.3f} s: travel {travel:.4f} m (horizontal CM path), theta "
        f"{last[4]:.4f} deg, tilt {last[5]:.4f} deg, min gap {last[6]:.3e} m "
        f"(lowest over the run {min(x[6] for x in rows):.3e} m"
        + (f"; over the ground's ridge points {min(ridge):.3e} m)" if ridge else ")"))


def _inside(q, outline):
    x, z = q
    c = False
    m = len(outline)
    for k in range(m):
        (xa, za), (xb, zb) = outline[k], outline[(k + 1) % m]
        if (za > z) != (zb > z) and x < xa + (z - za) / (zb - za) * (xb - xa):
            c = not c
    return c


if __name__ == "__main__":
    main()
