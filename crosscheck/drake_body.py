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
--reach of the footprint, --line-gap (20 µm) below it, which meet a thin plate on the block (a
2 cm Box, or the outline's convex hull, whose underside is the base); the plate meets only those,
and the base's grid only the cells and prisms. Set so low, a row of them carries only where a
ridge alone carries the base: where the base lies flush over a ridge a line has no share of a
uniform bed, and on the ridge itself each point would carry as a grid point does.

A base cast onto its rock (--cast, slideroute's `[base] cast = true`,
derivations/13-base-contact.md §10; needs --start): the base's underside is the ground's own
surface under the footprint where slideroute set the block down, seen along the block's y' (the
relief). The bed's spheres lie on the relief, a uniform bed over each of its faces (Relief.bed):
each --grid point stands for its cell, and each face's part of the cell is one sphere weighted
by that part's area (a point on a bend is one sphere for each face beside it, nudged into it);
and points every --bend-step along each relief bend (where two of the ground's faces that are
not coplanar meet under the footprint), their ends on the rim included, each weighing
--bend-weight of a cell. A ridge of the ground must not pass through a relief face between the
bed's points: the block carries, for each planar relief face (the ground's coplanar triangles
clipped to the footprint), a thin plate whose underside is that face raised by the radius (a Box
on a rectangle, else a Convex prism), meeting only the ground's ridge points (spheres centred
--line-gap below the ridges, so that they carry only where a ridge alone carries the base: a
line has no share of a uniform bed). And a ridge of the ground crossing a convex edge of the
underside (a valley of the ground under the footprint, or the footprint's rim) meets it between
both rows of points: a square Box (--edge-size) along each such edge of the block and each ridge
of the ground, only its edge on the surface, meets only the other kind (Drake's box-box contact
is exact, edge against edge too; the ridges' boxes --line-gap low as their points). The ground's
cell boxes end where their neighbour's lowered plane cuts them at a ridge, and the plates where
theirs does at a valley (ridge_trims, Relief.valley_trims), so that a sphere crossing a bend
rides over it at its centre's distance.

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
from t = 0. With --start it settles only if --settle is given. Either way the scene's [initial]
rates are given as drake_route --base gives them.

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
    grid whose heights are planar over it): each as (its four corners, the two triangles, the
    corners' vertex indices).
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
        out.append((np.array(quad), ks, (c, a, d, b)))
    return out


def face_box(quad, n, shift, depth, trims):
    """A Box on the rectangle `quad` (corners in order): its face moved by `shift` along the unit
    normal n, the box reaching `depth` from it (below with depth < 0), each edge k (quad[k] to
    quad[k + 1]) moved inward by trims.get(k, 0). Returns (pose, shape)."""
    u, w = quad[1] - quad[0], quad[3] - quad[0]
    lu, lw = np.linalg.norm(u), np.linalg.norm(w)
    uh, wh = u / lu, w / lw
    t = [trims.get(k, 0.0) for k in range(4)]
    centre = (quad[0] + uh * (t[3] + lu - t[1]) / 2 + wh * (t[0] + lw - t[2]) / 2
              + n * (shift + depth / 2))
    rot = RotationMatrix(np.column_stack([uh, np.cross(n, uh), n]))
    return RigidTransform(rot, centre), Box(lu - t[1] - t[3], lw - t[0] - t[2], abs(depth))


def ridge_trims(corners, ks, v, tris, edges, n, r):
    """A cell's (its corners' vertex indices, its triangles ks, its upward normal n) edges that
    are ridges of the ground (the neighbour across falls away below the cell's plane), each with
    the trim r tan(θ/2) (θ between the two faces' normals) that makes the cell's box, lowered by
    r along n, end where the neighbour's lowered plane cuts it: the union of the lowered boxes
    is then the ground eroded by r, and a sphere of radius r crossing the ridge touches it only
    at its centre's distance r (untrimmed, the neighbour box's corner sticks out past the
    bisector and a sphere crossing the ridge goes up to r (1 - cos θ) into it: 60 µm at a 20°
    bend for r = 1 mm)."""
    out = {}
    for k in range(4):
        a, b = corners[k], corners[(k + 1) % 4]
        other = [j for j in edges.get((min(a, b), max(a, b)), []) if j not in ks]
        if len(other) != 1:
            continue
        t = tris[other[0]]
        p0, p1, p2 = v[t]
        m = np.cross(p1 - p0, p2 - p0)
        if abs(m[1]) < 1e-12:
            continue
        m = m / np.linalg.norm(m) * np.sign(m[1])
        far = [int(x) for x in t if x not in (a, b)][0]
        if (v[far] - v[a]) @ n < -1e-12:
            theta = math.acos(min(1.0, max(-1.0, float(n @ m))))
            out[k] = r * math.tan(theta / 2)
    return out


def ridge_edges(v, tris):
    """The ground's ridges (convex edges: the neighbouring triangle falls away below the plane
    of the other) as (end, end, the unit bisector of the two faces' upward normals, the angle
    between them)."""
    edges = {}
    for k, t in enumerate(tris):
        for e in range(3):
            a, b = int(t[e]), int(t[(e + 1) % 3])
            edges.setdefault((min(a, b), max(a, b)), []).append((k, int(t[(e + 2) % 3])))
    out = []
    for (a, b), side in edges.items():
        if len(side) != 2:
            continue
        normals = []
        for k, _ in side:
            p0, p1, p2 = v[tris[k]]
            n = np.cross(p1 - p0, p2 - p0)
            normals.append(None if abs(n[1]) < 1e-12 else n / np.linalg.norm(n) * np.sign(n[1]))
        if normals[0] is None or normals[1] is None:
            continue
        if (v[side[1][1]] - v[a]) @ normals[0] > -1e-9:
            continue  # level or a valley
        mid = normals[0] + normals[1]
        theta = math.acos(min(1.0, max(-1.0, float(normals[0] @ normals[1]))))
        out.append((v[a], v[b], mid / np.linalg.norm(mid), theta))
    return out


def edge_box(p, q, inward, half_angle, size, face=None):
    """A Box of square section `size` along the convex edge p-q of a solid whose only part on
    the solid's surface is that edge (Drake's box-box contact is exact, edge against edge
    too): set as a diamond, its corner on the edge and its diagonal along the unit bisector
    `inward` into the solid, where the solid's angle there is at least 90° (half_angle, half the
    angle between the faces' outward normals, at most 45°); else (a footprint's rim sharper
    than 90°) with one side on the face whose inward unit normal is `face`, sticking out past the
    other face by the difference. Returns (pose, shape)."""
    d = q - p
    length = float(np.linalg.norm(d))
    e = d / length
    if half_angle <= math.pi / 4 + 1e-9 or face is None:
        c = np.cross(e, inward)
        a2, a3 = (inward + c) / math.sqrt(2), (inward - c) / math.sqrt(2)
    else:
        a3 = face - (face @ e) * e
        a3 = a3 / np.linalg.norm(a3)
        a2 = np.cross(a3, e)
        if a2 @ inward < 0:
            a2 = -a2
    centre = (p + q) / 2 + (a2 + a3) * size / 2
    rot = np.column_stack([a2, a3, e])
    if np.linalg.det(rot) < 0:
        rot = np.column_stack([a3, a2, e])
    return RigidTransform(RotationMatrix(rot), centre), Box(size, size, length)


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


def _clip(poly, outline):
    """Sutherland-Hodgman: the convex polygon `poly` ((x, z) pairs) clipped to the convex,
    counter-clockwise `outline`."""
    out = [np.asarray(q, dtype=float) for q in poly]
    m = len(outline)
    for k in range(m):
        a, b = np.asarray(outline[k], float), np.asarray(outline[(k + 1) % m], float)
        e = b - a

        def side(q):
            return e[0] * (q[1] - a[1]) - e[1] * (q[0] - a[0])

        src, out = out, []
        for i in range(len(src)):
            p, q = src[i], src[(i + 1) % len(src)]
            sp, sq = side(p), side(q)
            if sp >= 0:
                out.append(p)
            if (sp >= 0) != (sq >= 0):
                out.append(p + (q - p) * sp / (sp - sq))
        if not out:
            return []
    return out


def _area(poly):
    return 0.5 * sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(poly, poly[1:] + poly[:1]))


def _hull(pts):
    """Convex hull (counter-clockwise, no collinear points) of (x, z) points."""
    pts = sorted(set((round(float(x), 12), round(float(z), 12)) for x, z in pts))
    if len(pts) < 3:
        return pts

    def half(seq):
        h = []
        for q in seq:
            while len(h) >= 2 and ((h[-1][0] - h[-2][0]) * (q[1] - h[-2][1])
                                   - (h[-1][1] - h[-2][1]) * (q[0] - h[-2][0])) <= 1e-12:
                h.pop()
            h.append(q)
        return h

    lo, hi = half(pts), half(pts[::-1])
    return lo[:-1] + hi[:-1]


class Relief:
    """The underside of a base cast onto its rock: the ground (world vertices v, triangles tris)
    under the footprint `outline` (x', z' about the CM, convex, counter-clockwise), seen along
    the block's y' at the pose (rotation body-to-world `rot`, centre of mass `cm`), in body
    axes about the CM."""

    def __init__(self, v, tris, rot, cm, outline):
        if _area(list(outline)) < 0:
            outline = list(outline)[::-1]
        self.outline = [tuple(map(float, q)) for q in outline]
        vb = (np.asarray(v) - np.asarray(cm)) @ np.asarray(rot)  # body axes
        self.height = Ground(surface=(vb, tris))  # y'(x', z') of the ground seen along y'
        # Each triangle's plane y' = h0 + hx x' + hz z' over the body's plan.
        planes = []
        for t in tris:
            p0, p1, p2 = vb[t]
            n = np.cross(p1 - p0, p2 - p0)
            if abs(n[1]) < 1e-12 * (n @ n) ** 0.5:
                planes.append(None)
                continue
            planes.append(np.array([(n @ p0) / n[1], -n[0] / n[1], -n[2] / n[1]]))
        self.planes = planes
        scale = max(max(abs(x), abs(z)) for x, z in self.outline)

        def same(a, b):
            return (a is not None and b is not None
                    and abs(a[1] - b[1]) < 1e-9 and abs(a[2] - b[2]) < 1e-9
                    and abs(a[0] - b[0]) < 1e-9 * max(1.0, scale))

        # Coplanar neighbours are one face (union-find over shared edges); a shared edge between
        # faces that are not coplanar is a bend.
        parent = list(range(len(tris)))

        def find(i):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        edges = {}
        for k, t in enumerate(tris):
            for e in range(3):
                a, b = int(t[e]), int(t[(e + 1) % 3])
                edges.setdefault((min(a, b), max(a, b)), []).append(k)
        bends = []
        for (a, b), ks in edges.items():
            if len(ks) != 2:
                continue
            if same(planes[ks[0]], planes[ks[1]]):
                parent[find(ks[0])] = find(ks[1])
            elif planes[ks[0]] is not None and planes[ks[1]] is not None:
                # A valley of the ground (the far vertex of one triangle above the other's
                # plane) is a convex edge of the block's underside; θ between the normals.
                h = planes[ks[0]]
                far = [int(x) for x in tris[ks[1]] if x not in (a, b)][0]
                q = vb[far]
                valley = q[1] > h[0] + h[1] * q[0] + h[2] * q[2]
                n0 = np.array([-h[1], 1.0, -h[2]])
                h1 = planes[ks[1]]
                n1 = np.array([-h1[1], 1.0, -h1[2]])
                cos = n0 @ n1 / np.linalg.norm(n0) / np.linalg.norm(n1)
                bends.append((a, b, bool(valley), math.acos(min(1.0, max(-1.0, cos)))))
        # The relief's faces: each face's triangles clipped to the footprint, lifted onto its
        # plane; one polygon where they make a convex one, else each piece apart.
        lo = np.array([min(x for x, _ in self.outline), min(z for _, z in self.outline)])
        hi = np.array([max(x for x, _ in self.outline), max(z for _, z in self.outline)])
        groups = {}
        for k, t in enumerate(tris):
            if planes[k] is None:
                continue
            plan = vb[t][:, [0, 2]]
            if (plan.max(axis=0) < lo - 1e-9).any() or (plan.min(axis=0) > hi + 1e-9).any():
                continue
            poly = [tuple(q) for q in plan]
            if _area(poly) < 0:
                poly = poly[::-1]
            piece = _clip(poly, self.outline)
            if len(piece) >= 3 and _area([tuple(q) for q in piece]) > 1e-12 * scale * scale:
                groups.setdefault(find(k), []).append(([tuple(q) for q in piece], planes[k]))
        self.faces = []
        for pieces in groups.values():
            hull = _hull([q for poly, _ in pieces for q in poly])
            total = sum(_area(poly) for poly, _ in pieces)
            polys = ([hull] if abs(_area(hull) - total) <= 1e-9 * max(total, 1.0)
                     else [_hull(poly) for poly, _ in pieces])
            h = pieces[0][1]
            for poly in polys:
                self.faces.append(np.array([[x, h[0] + h[1] * x + h[2] * z, z]
                                            for x, z in poly]))
        covered = sum(_area([(q[0], q[2]) for q in f]) for f in self.faces)
        if abs(covered - _area(self.outline)) > 1e-6 * _area(self.outline):
            sys.exit(f"--cast: the ground covers {covered:.6g} m² of the footprint's "
                     f"{_area(self.outline):.6g} m² where the block rests")
        # The bends under the footprint, clipped to it (their ends on the rim where they cross).
        self.bends, self.kinks = [], []
        self.scale = scale
        for a, b, valley, theta in bends:
            p, q = vb[a][[0, 2]], vb[b][[0, 2]]
            seg = _clip_segment(p, q, self.outline)
            if seg is not None:
                self.bends.append(seg)
                self.kinks.append((valley, theta))

    def convex_edges(self):
        """The convex edges of the block's underside: the ground's valleys under the footprint
        and the footprint's rim (where a relief face meets the block's vertical side), each as
        (end, end, the unit bisector into the block, half the angle between the faces'
        outward normals, the relief face's upward unit normal on the rim, else None), in body
        axes. A bend on the rim is the rim's."""
        out = []
        m = len(self.outline)

        def on_rim(x):
            """The outline's edges (their lines) through x."""
            lines = set()
            for j in range(m):
                a = np.array(self.outline[j])
                e = np.array(self.outline[(j + 1) % m]) - a
                if abs(e[0] * (x[1] - a[1]) - e[1] * (x[0] - a[0])) <= 1e-9 * (e @ e):
                    lines.add(j)
            return lines

        for (p, q), (valley, theta) in zip(self.bends, self.kinks):
            if not valley or on_rim(p) & on_rim(q):
                continue
            ends = [np.array([x, float(self.height.height(np.array([[x, z]]))[0]), z])
                    for x, z in (p, q)]
            # The two faces' upward normals, from the relief's height on either side.
            d = q - p
            side = np.array([-d[1], d[0]]) / np.linalg.norm(d)
            mid = (p + q) / 2
            normals = [self._normal(mid + s * 1e-4 * max(1.0, self.scale) * side)
                       for s in (1, -1)]
            b = normals[0] + normals[1]
            out.append((ends[0], ends[1], b / np.linalg.norm(b), theta / 2, None))
        for face in self.faces:
            for k in range(len(face)):
                p, q = face[k], face[(k + 1) % len(face)]
                for j in range(m):
                    a = np.array(self.outline[j])
                    e = np.array(self.outline[(j + 1) % m]) - a
                    on = [abs(e[0] * (x[2] - a[1]) - e[1] * (x[0] - a[0])) <= 1e-9 * (e @ e)
                          for x in (p, q)]
                    if all(on) and np.linalg.norm((q - p)[[0, 2]]) > 1e-9:
                        n = np.cross(face[-1] - face[0], face[1] - face[0])
                        n = n / np.linalg.norm(n) * np.sign(n[1])
                        o = np.array([e[1], 0.0, -e[0]]) / np.linalg.norm(e)  # outward
                        b = n - o
                        half = math.acos(min(1.0, max(-1.0, float(-n @ o)))) / 2
                        out.append((p, q, b / np.linalg.norm(b), half, n))
                        break
        return out

    def _normal(self, xz):
        """The relief's upward unit normal at (x', z') (inside a face)."""
        h = 1e-6 * max(1.0, self.scale)
        pts = np.array([xz, xz + [h, 0.0], xz + [0.0, h]])
        y = self.height.height(pts)
        n = np.array([-(y[1] - y[0]) / h, 1.0, -(y[2] - y[0]) / h])
        return n / np.linalg.norm(n)

    def valley_trims(self, face, r):
        """The edges of a rectangular relief face (corners in order, body axes) that lie on a
        valley of the ground (a convex edge of the block's underside), each with the trim
        r tan(θ/2) that makes the face's plate, raised by r along its normal, end where its
        neighbour's raised plane cuts it (ridge_trims, the block's side)."""
        out = {}
        for k in range(len(face)):
            mid = (face[k] + face[(k + 1) % len(face)])[[0, 2]] / 2
            for (p, q), (valley, theta) in zip(self.bends, self.kinks):
                d = q - p
                t = float(np.clip((mid - p) @ d / (d @ d), 0.0, 1.0))
                if valley and np.linalg.norm(p + t * d - mid) < 1e-9 * max(1.0, self.scale):
                    out[k] = r * math.tan(theta / 2)
        return out

    def bed(self, grid, step, bend_weight):
        """The bed's points in body axes on the relief and each one's spring weight, a uniform bed
        over each face of the relief: its springs add up, face by face, to the face's area.

        Each point of dr.base_points stands for its cell (the grid's spacing about it, clipped to
        the footprint, as dr.base_weights), and each face's part of that cell is one sphere
        weighted by that part's area. A grid point on a face's boundary is nudged 1e-3 of the
        spacing into the face, and on a bend it is one sphere for each face beside it: when one
        face lifts off, the other keeps only its own share, and a bend on the rim (its face's
        share the face's) does not carry the next face of the rock it rides onto. Points every `step` along each bend that no grid point is on,
        each weighing `bend_weight` of a cell, keep the bends out of the rock between them.
        Weights are relative to the mean cell, as dr.base_weights. Returns (points, weights,
        the number of spheres that are not grid points).

        Until 2026-11-27 each grid point weighed its whole cell, whatever faces the cell spanned:
        a point on a bend carried both faces' shares on the one face that touched, and each 0.5 m
        flank of scenes/body/teeth.obj was a bed 0.5 m + one spacing long. The cast block's yaw
        then started 5.3 %, 3.6 % and 2.1 % slower than the continuum's at 20, 40 and 80 points a
        side (crosscheck/README.md, "The start on the teeth")."""
        xz0 = [(float(q[0]), float(q[2])) for q in dr.base_points(self.outline, grid)]
        xs, zs = [x for x, _ in self.outline], [z for _, z in self.outline]
        dx, dz = (max(xs) - min(xs)) / grid, (max(zs) - min(zs)) / grid
        per_area = len(xz0) / _area(self.outline)  # a weight per m², the mean cell's being 1
        plans = [[(float(q[0]), float(q[2])) for q in f] for f in self.faces]
        nudge = 1e-3 * min(dx, dz)

        def inside(q, poly):
            """q in the convex counter-clockwise `poly`, not within 1e-9 of its boundary."""
            for k in range(len(poly)):
                a, b = np.array(poly[k]), np.array(poly[(k + 1) % len(poly)])
                e = b - a
                if e[0] * (q[1] - a[1]) - e[1] * (q[0] - a[0]) <= 1e-9 * np.linalg.norm(e):
                    return False
            return True

        xz, w = [], []
        extra = 0
        for x, z in xz0:
            cell = [(x - dx / 2, z - dz / 2), (x + dx / 2, z - dz / 2),
                    (x + dx / 2, z + dz / 2), (x - dx / 2, z + dz / 2)]
            cell = [tuple(q) for q in _clip(cell, self.outline)]
            parts = []
            for plan in plans:
                piece = _clip(cell, plan) if len(cell) >= 3 else []
                piece = [tuple(q) for q in piece]
                area = _area(piece) if len(piece) >= 3 else 0.0
                if area > 1e-9 * dx * dz:
                    parts.append((plan, piece, area))
            for plan, piece, area in parts:
                q = np.array([x, z])
                if not inside(q, plan):
                    c = np.mean(np.array(piece), axis=0)
                    q = q + (c - q) / np.linalg.norm(c - q) * nudge
                xz.append((float(q[0]), float(q[1])))
                w.append(area * per_area)
            extra += max(0, len(parts) - 1)
        seen = {(round(x, 7), round(z, 7)) for x, z in xz0}
        for p, q in self.bends:
            n = max(1, int(math.ceil(np.linalg.norm(q - p) / step)))
            for j in range(n + 1):
                x, z = p + (q - p) * j / n
                key = (round(float(x), 7), round(float(z), 7))
                if key in seen:
                    continue
                seen.add(key)
                xz.append((float(x), float(z)))
                w.append(bend_weight * dx * dz * per_area)
                extra += 1
        xz = np.array(xz)
        y = self.height.height(xz)
        if np.isnan(y).any():
            sys.exit("--cast: a bed point is over no ground")
        return np.column_stack([xz[:, 0], y, xz[:, 1]]), w, extra

    def under(self, body):
        """The relief's height y' at body points' (x', z'), NaN outside the footprint."""
        xz = body[:, [0, 2]]
        out = np.full(len(body), np.nan)
        lo = np.min(self.outline, axis=0)
        hi = np.max(self.outline, axis=0)
        near = np.nonzero(((xz >= lo) & (xz <= hi)).all(axis=1))[0]
        near = [k for k in near if _inside(xz[k], self.outline)]
        if near:
            out[near] = self.height.height(xz[near])
        return out


def _clip_segment(p, q, outline):
    """The part of segment p-q inside the convex counter-clockwise `outline` (None if none)."""
    t0, t1 = 0.0, 1.0
    d = q - p
    m = len(outline)
    for k in range(m):
        a, b = np.asarray(outline[k], float), np.asarray(outline[(k + 1) % m], float)
        e = b - a
        # inside: e × (x - a) >= 0
        f0 = e[0] * (p[1] - a[1]) - e[1] * (p[0] - a[0])
        fd = e[0] * d[1] - e[1] * d[0]
        if abs(fd) < 1e-15:
            if f0 < -1e-12:
                return None
            continue
        t = -f0 / fd
        if fd > 0:
            t0 = max(t0, t)
        else:
            t1 = min(t1, t)
    if t1 < t0 + 1e-12:
        return None
    return p + d * t0, p + d * t1


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--t-end", type=float, default=3.0)
    ap.add_argument("--dt", type=float, default=1e-3)
    ap.add_argument("--mu-delta", type=float, default=0.0, help="added to every mu (chaos check)")
    ap.add_argument("--start", help="slideroute's summary.json: start where it rested")
    ap.add_argument("--settle", type=float, default=None,
                    help="settling time under the weight alone, s (default 1 without --start,"
                         " 0 with it)")
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
    ap.add_argument("--cast", action="store_true",
                    help="surface: the base cast onto its rock ([base] cast = true): the bed on"
                         " the ground's relief under the footprint where --start rests it")
    ap.add_argument("--bend-step", type=float, default=None,
                    help="--cast: spacing of the bed's points along the relief's bends, m"
                         " (default: the grid's)")
    ap.add_argument("--bend-weight", type=float, default=0.05,
                    help="--cast: a bend point's spring (off the grid) against a grid cell's")
    ap.add_argument("--line-gap", type=float, default=2e-5,
                    help="how far below the ridges their points (and with --cast their boxes) are"
                         " set, so that they carry only where a ridge alone carries the base, m")
    ap.add_argument("--edge-size", type=float, default=0.02,
                    help="--cast: the section of the boxes along the ground's ridges and the"
                         " base's convex edges, m")
    ap.add_argument("--dump-contacts", type=float, nargs="*", default=None,
                    help="print the contacts (geometries, force, where in body axes) at these"
                         " times, s (diagnosis)")
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
    rest = None
    if a.start:
        with open(a.start) as f:
            summary = json.load(f)
        rest = summary["resting"] if "resting" in summary else summary["base"]["resting"]
    relief, extra = None, 0
    if a.cast:
        if p["surface"] is None:
            sys.exit(f"{a.scene}: --cast takes a triangulated [foundation] surface")
        if rest is None:
            sys.exit("--cast: --start (slideroute's summary.json) gives where the base was cast")
        v, tris = read_obj(p["surface"])
        relief = Relief(v, tris, np.array(rest["rotation"]),
                        np.array([rest["x_m"], rest["y_m"], rest["z_m"]]), p["outline"])
        xs, zs = [x for x, _ in p["outline"]], [z for _, z in p["outline"]]
        step = a.bend_step or min(max(xs) - min(xs), max(zs) - min(zs)) / a.grid
        points, weights, extra = relief.bed(a.grid, step, a.bend_weight)
        if a.equal_springs:
            weights = [1.0] * len(points)
        top = float(np.max(points[:, 1]))
        if top > -p["height"] + 1e-9:
            sys.exit(f"--cast: the relief reaches {top + p['height']:.3e} m above the flat base")
    else:
        points = np.array([c + below for c in dr.base_points(p["outline"], a.grid)])
        # Each sphere's spring in proportion to the area it stands for (dr.base_weights: a
        # uniform bed to second order), unless --equal-springs.
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
        block_caps, ground_caps = [], []
        if not a.no_ridges:
            # A ridge or a vertex of the ground between the base's grid points would go into
            # the base unseen: points there (spheres on the ground) against a plate on the block
            # whose underside is the base.
            out = p["outline"]
            xs, zs = [x for x, _ in out], [z for _, z in out]
            size = max(math.hypot(x, z) for x, z in out)
            start = (0.0, 0.0)
            if rest is not None:
                start = (rest["x_m"], rest["z_m"])
            features, ridges = ridge_points(v, tris, start,
                                            (math.inf if a.cast else size + a.reach),
                                            a.ridge_step)
            if a.cast:  # the points themselves within reach (a long ridge's far part left out)
                features = features[np.hypot(features[:, 0] - start[0],
                                             features[:, 2] - start[1]) <= size + a.reach]
            kind += (f"; {len(features)} points at its vertices and along {ridges} ridges "
                     f"within {size + a.reach:.1f} m")
            thick = 0.02
            rect = (len(out) == 4 and len(set(xs)) == 2 and len(set(zs)) == 2)
            plates = []
            # The ridges' points against the base's plate (a cast base's: its relief's plates),
            # and with --cast the ridges' boxes against the base's convex edges, are lines, not
            # areas: where the base lies flush a uniform bed gives them no share. So they are set
            # --line-gap below the ridges, deeper than the bed sinks under the block's weight
            # (0.3 µm on the teeth), and touch only where a ridge carries the base. On the ridges
            # at full depth the rock's crests under scenes/body/cast-teeth.toml's flanks carried
            # 42 % of its weight at 0.05 s (--dump-contacts), and the yaw started 7 % slow; with
            # their springs at 1/50 instead, the crests sank 1.9 mm into the base once it rode on
            # them.
            gap = np.array([0.0, a.line_gap, 0.0])
            if a.cast:
                # A thin plate on each planar face of the relief, its underside the face raised
                # by the radius along the face's normal (the ground's points then are the
                # spheres' centres: a sphere lowered along Y would go r (1 - cos i) into a face
                # tilted by i, 15 µm at 10° for r = 1 mm, and hold the block off its bed).
                for j, face in enumerate(relief.faces):
                    u = face[1] - face[0]
                    n = np.cross(face[-1] - face[0], u)
                    n = n / np.linalg.norm(n) * np.sign(n[1])
                    face = face + r * n
                    trims = relief.valley_trims(face - r * n, r)
                    w = face[-1] - face[0]
                    box = len(face) == 4 and all(
                        abs((face[(i + 1) % 4] - face[i]) @ (face[(i + 2) % 4] - face[(i + 1) % 4]))
                        <= 1e-9 * (u @ u + w @ w) for i in range(4))
                    if box:
                        at, shape = face_box(face, n, 0.0, thick, trims)
                    else:
                        pts = np.vstack([face, face + thick * n])
                        centre = pts.mean(axis=0)
                        shape = Convex((pts - centre).T, f"relief{j}")
                        at = RigidTransform(centre)
                    plates.append(plant.RegisterCollisionGeometry(
                        block, at, shape, f"relief{j}", props()))
                # Edge against edge (a ridge of the ground across a convex edge of the block's
                # underside, which meet at a point between the rows of points): a box along
                # each, touching the surface only along its edge, meeting only each other.
                esize = a.edge_size
                for j, (e0, e1, inward, half, face_n) in enumerate(relief.convex_edges()):
                    at, shape = edge_box(e0, e1, inward, half, esize, face_n)
                    block_caps.append(plant.RegisterCollisionGeometry(
                        block, at, shape, f"edge{j}", props()))
                for j, (e0, e1, up, theta) in enumerate(ridge_edges(v, tris)):
                    seg = _clip_segment(e0[[0, 2]], e1[[0, 2]], [
                        (start[0] + dx * (size + a.reach), start[1] + dz * (size + a.reach))
                        for dx, dz in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
                    if seg is None:
                        continue
                    # The clipped ends, on the ridge.
                    d = e1 - e0
                    ends = [e0 + d * (float((q - e0[[0, 2]]) @ d[[0, 2]]) / float(d[[0, 2]] @ d[[0, 2]]))
                            for q in seg]
                    at, shape = edge_box(ends[0] - gap, ends[1] - gap, -up, theta / 2, esize)
                    ground_caps.append(plant.RegisterCollisionGeometry(
                        ground, at, shape, f"ridge{j}", props()))
                kind += (f"; cast: {len(relief.faces)} relief faces as plates, "
                         f"{len(relief.bends)} bends ({extra} bed points off the grid), "
                         f"{len(block_caps)} convex edges of the base and {len(ground_caps)} "
                         f"ridges as boxes of {esize * 1e3:g} mm")
            elif rect:
                plate_shape = Box(max(xs) - min(xs), thick, max(zs) - min(zs))
                plate_at = np.array([(max(xs) + min(xs)) / 2, -p["height"] + thick / 2,
                                     (max(zs) + min(zs)) / 2])
            else:  # the outline's convex hull, as a prism
                hull = np.array([[x, y, z] for x, z in out for y in (0.0, thick)])
                plate_at = np.array([0.0, -p["height"], 0.0])
                plate_shape = Convex(hull.T, "base")
            if not a.cast:
                plates.append(plant.RegisterCollisionGeometry(
                    block, RigidTransform(plate_at), plate_shape, "plate", props()))
            lower = gap if a.cast else np.array([0.0, r, 0.0]) + gap
            for i, q in enumerate(features):
                knobs.append(plant.RegisterCollisionGeometry(
                    ground, RigidTransform(q - lower), Sphere(r), f"knob{i}", props()))
        down = np.array([0.0, r, 0.0])
        boxed = set()
        if not a.all_prisms:
            edges = {}
            for k, t in enumerate(tris):
                for e in range(3):
                    i0, i1 = int(t[e]), int(t[(e + 1) % 3])
                    edges.setdefault((min(i0, i1), max(i0, i1)), []).append(k)
            trimmed = 0
            for j, (quad, ks, corners) in enumerate(rectangles(v, tris)):
                u, w = quad[1] - quad[0], quad[3] - quad[0]
                n = np.cross(w, u)
                if abs(n[1]) < 1e-12:
                    continue
                n = n / np.linalg.norm(n) * np.sign(n[1])
                # Lowered by the radius along its normal, as a half-space is; with --cast
                # ended short of the ground's ridges (ridge_trims).
                trims = ridge_trims(corners, ks, v, tris, edges, n, r) if a.cast else {}
                trimmed += len(trims)
                pose, shape = face_box(quad, n, -r, -CELL_DEPTH, trims)
                prisms.append(plant.RegisterCollisionGeometry(
                    ground, pose, shape, f"cell{j}", props()))
                boxed.update(ks)
            kind += f" ({len(boxed) // 2} planar rectangular cells as boxes"
            kind += f", {trimmed} of their edges trimmed at ridges)" if a.cast else ")"
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
        decl.ExcludeBetween(GeometrySet(plates), GeometrySet(prisms))
        decl.ExcludeBetween(GeometrySet(grid), GeometrySet(knobs))
        if block_caps or ground_caps:
            decl.ExcludeBetween(GeometrySet(block_caps), GeometrySet(prisms + knobs))
            decl.ExcludeBetween(GeometrySet(ground_caps), GeometrySet(grid + plates))
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
        if relief is not None:  # cast: the relief's height over each point, along y'
            gap = relief.under(body) - body[:, 1]
            return float(np.nanmin(gap)) if not np.isnan(gap).all() else float("nan")
        near = np.abs(body[:, 1] + p["height"]) < 1.0
        under = [k for k in np.nonzero(near)[0] if _inside(body[k, [0, 2]], out_poly)]
        if not under:
            return float("nan")
        # Height of the base plane above each point, measured along Y.
        return float(np.min((-p["height"] - body[under, 1]) / rot[1, 1]))

    def say(*x):
        if not a.quiet:
            print(*x, file=sys.stderr)

    say(f"{a.scene}: {len(points)} base points (grid {a.grid}"
        f"{', cast' if a.cast else ''}), ground {kind}, "
        f"m = {p['mass']:.4g} kg, ȳ = {p['height']:.4g} m, mu = {p['mu']}")
    i0 = p["init"]
    v_init = np.array([i0.get("vx_m_s", 0.0), 0.0, i0.get("vz_m_s", 0.0)])
    w_init = np.array([0.0, -math.radians(i0.get("omega_deg_s", 0.0)), 0.0])
    t0 = 0.0
    if rest is not None:
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
    settle = a.settle if a.settle is not None else (0.0 if rest is not None else 1.0)
    if settle > 0:
        port.FixValue(pc, [])
        if joints:
            shake(np.zeros(3))
        steps = int(round(settle / a.dt))
        simulator.AdvanceTo(steps * a.dt)
        t0 = steps * a.dt
        v = plant.EvalBodySpatialVelocityInWorld(pc, block)
        cm, rot, world = state()
        i_axis = rot[:, 0]
        say(f"settled after {settle} s: CM ({cm[0]:.6f}, {cm[1]:.6f}, {cm[2]:.6f}) m, "
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
        if a.dump_contacts and any(abs((k + 1) * a.dt - x) < a.dt / 2 for x in a.dump_contacts):
            dump_contacts(plant, scene_graph, pc, (k + 1) * a.dt, cm, rot)

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


def dump_contacts(plant, scene_graph, pc, t, cm, rot):
    """Prints every point contact's geometries, normal force and where (body axes) at time t."""
    results = plant.get_contact_results_output_port().Eval(pc)
    inspector = scene_graph.model_inspector()
    rows = []
    for i in range(results.num_point_pair_contacts()):
        info = results.point_pair_contact_info(i)
        pair = info.point_pair()
        names = sorted([inspector.GetName(pair.id_A), inspector.GetName(pair.id_B)])
        f = info.contact_force()
        nf = abs(f @ pair.nhat_BA_W)
        at = (info.contact_point() - cm) @ rot
        rows.append((nf, names, at, pair.nhat_BA_W, pair.depth, info.slip_speed(),
                     (pair.p_WCa - cm) @ rot, (pair.p_WCb - cm) @ rot,
                     inspector.GetName(pair.id_A)))
    rows.sort(key=lambda x: -x[0])
    total = sum(x[0] for x in rows)
    print(f"t = {t:.4f} s: {len(rows)} contacts, normal forces sum {total:.4e} N", file=sys.stderr)
    kinds = {}
    for nf, names, *_ in rows:
        kind = "-".join(sorted(name.rstrip("0123456789") for name in names))
        kinds[kind] = kinds.get(kind, 0.0) + nf
    print("  by kind: " + ", ".join(f"{k} {v:.4e} N" for k, v in sorted(kinds.items())),
          file=sys.stderr)
    for nf, names, at, n, depth, slip, pa, pb, name_a in rows:
        print(f"  {nf:11.4e} N {names[0]:>9} {names[1]:>9} at x'y'z' ({at[0]:+.4f}, {at[1]:+.5f},"
              f" {at[2]:+.4f}) n ({n[0]:+.3f}, {n[1]:+.3f}, {n[2]:+.3f}) depth {depth:.2e}"
              f" slip {slip:.2e}; deepest points {name_a} ({pa[0]:+.5f}, {pa[1]:+.5f},"
              f" {pa[2]:+.5f}), other ({pb[0]:+.5f}, {pb[1]:+.5f}, {pb[2]:+.5f})",
              file=sys.stderr)


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
