#!/usr/bin/env python3
"""The path of a slideroute scene's block on its WHOLE BASE as a stiff bed of springs with exact
point-on-triangle contact, integrated explicitly in NumPy: a second whole-body reference beside
drake_body.py for grounds where Drake's own contact is not exact (crosscheck/README.md, "A bed of
springs in NumPy"). Independent of slideroute's code: it reads only the scene file and the
resting pose from slideroute's summary.json (--start).

Why. Drake's point contact of a sphere with a Box or a half-space is exact, with a Convex it is
not (on a 10° plane written as prisms the block slid 5.6 % less in 3 s), and a rough surveyed
ground or a base cast onto it has no planar rectangles to make boxes of: drake_body.py is then
no converged reference (cast-adverse does not even start). Here every contact is measured
exactly against the triangles:

* the base's bed (drake_body.py's, the same points and area weights: dr.base_points and
  dr.base_weights for a flat base, Relief.bed on a cast one) against the ground's triangles,
  each point's depth along the normal of the triangle under it;
* the ground's ridge points and peaks (drake_body.ridge_points, --line-gap low as in
  drake_body.py) against the base's underside (the plane y' = -ȳ, or the relief's triangles in
  body axes) inside the footprint;
* each of the ground's ridges across each convex edge of the base (its rim, and a cast base's
  valleys), edge against edge: the depth between the two lines along their common normal where
  both segments meet, so that no crossing hides between the rows of points.

Each contact is a spring (the bed's in proportion to its point's area, as drake_body.py; a
single point or crossing as stiff as one that carries the block's whole weight at a sink of
--sink), damped at the bed's critical rate, with Coulomb friction (static = dynamic = mu_k) as
an elastic-plastic tangential spring of the same stiffness (a contact sticks exactly, without
creep). The rigid body's Newton-Euler equations are integrated by semi-implicit Euler at --dt,
the loads (drake_route.applied_loads's, by hand) at the current pose. Refine --dt and --sink
together until the path stops moving.

Writes the CSV of drake_body.py (every millisecond): t_s, x_m, y_m, z_m (the CM), theta_deg,
tilt_deg, min_gap_m (the bed's least depth-signed gap, negative inside), bx_m, by_m, bz_m (the
base point under the CM, what route.csv writes as x_m, y_m, z_m), ridge_gap_m (the least gap of
the ground's points and ridges to the base).
"""
import argparse
import csv
import json
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import drake_route as dr  # noqa: E402  (the scene reader, base grid and weights)
import drake_body as db  # noqa: E402  (the OBJ reader, the ridges, the cast relief's bed)


class Mesh:
    """A height field Y(X, Z) of triangles (vertical ones left out), queried in bulk: the
    triangle under each point, its height there and its upward unit normal."""

    def __init__(self, v, tris):
        v = np.asarray(v, dtype=float)
        a, b, c = v[tris[:, 0]], v[tris[:, 1]], v[tris[:, 2]]
        n = np.cross(b - a, c - a)
        keep = np.abs(n[:, 1]) > 1e-12 * np.linalg.norm(n, axis=1)
        a, b, c, n = a[keep], b[keep], c[keep], n[keep]
        n = n / np.linalg.norm(n, axis=1)[:, None] * np.sign(n[:, 1])[:, None]
        self.n = n
        # The plane y = h0 + hx x + hz z of each triangle.
        self.h = np.column_stack([(n * a).sum(1) / n[:, 1], -n[:, 0] / n[:, 1],
                                  -n[:, 2] / n[:, 1]])
        e1, e2 = (b - a)[:, [0, 2]], (c - a)[:, [0, 2]]
        self.a, self.e1, self.e2 = a[:, [0, 2]], e1, e2
        self.det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
        lo = np.minimum(np.minimum(a, b), c)[:, [0, 2]]
        hi = np.maximum(np.maximum(a, b), c)[:, [0, 2]]
        # Buckets of half a typical triangle's extent, aligned with the lowest corner: on a grid
        # of cells each bucket then meets the two triangles of its cell.
        self.cell = max(float(np.median(hi - lo)) / 2, 1e-3)
        self.origin = lo.min(axis=0)
        size = np.floor((hi.max(axis=0) - self.origin) / self.cell).astype(int) + 1
        buckets = [[[] for _ in range(size[1])] for _ in range(size[0])]
        tol = 1e-9 * self.cell
        i0 = np.floor((lo + tol - self.origin) / self.cell).astype(int)
        i1 = np.ceil((hi - tol - self.origin) / self.cell).astype(int) - 1
        i0, i1 = np.minimum(i0, i1), np.maximum(i0, i1)
        for k in range(len(a)):
            for i in range(max(i0[k, 0], 0), min(i1[k, 0], size[0] - 1) + 1):
                for j in range(max(i0[k, 1], 0), min(i1[k, 1], size[1] - 1) + 1):
                    buckets[i][j].append(k)
        width = max(len(q) for row in buckets for q in row)
        self.cand = np.full((size[0], size[1], width), -1, dtype=int)
        for i in range(size[0]):
            for j in range(size[1]):
                self.cand[i, j, :len(buckets[i][j])] = buckets[i][j]
        self.size = size

    def under(self, xz):
        """(triangle index or -1, height) at points xz (n × 2)."""
        ij = np.floor((xz - self.origin) / self.cell).astype(int)
        ok = (ij >= 0).all(axis=1) & (ij < self.size).all(axis=1)
        ij = np.where(ok[:, None], ij, 0)
        ks = self.cand[ij[:, 0], ij[:, 1]]  # n × width
        ks = np.where(ok[:, None], ks, -1)
        kk = np.maximum(ks, 0)
        d = xz[:, None, :] - self.a[kk]
        e1, e2, det = self.e1[kk], self.e2[kk], self.det[kk]
        s = (d[..., 0] * e2[..., 1] - d[..., 1] * e2[..., 0]) / det
        u = (e1[..., 0] * d[..., 1] - e1[..., 1] * d[..., 0]) / det
        tol = 1e-9
        inside = (ks >= 0) & (s >= -tol) & (u >= -tol) & (s + u <= 1 + tol)
        hit = inside.any(axis=1)
        first = np.argmax(inside, axis=1)
        k = np.where(hit, ks[np.arange(len(xz)), first], -1)
        kc = np.maximum(k, 0)
        y = self.h[kc, 0] + self.h[kc, 1] * xz[:, 0] + self.h[kc, 2] * xz[:, 1]
        return k, np.where(hit, y, np.nan)


def inside_convex(xz, outline):
    """Points (n × 2) strictly inside the convex polygon `outline` (either winding)."""
    poly = np.asarray(outline, dtype=float)
    e = np.roll(poly, -1, axis=0) - poly
    cross = (e[None, :, 0] * (xz[:, None, 1] - poly[None, :, 1])
             - e[None, :, 1] * (xz[:, None, 0] - poly[None, :, 0]))
    return (cross > 0).all(axis=1) | (cross < 0).all(axis=1)


def cross(a, b):
    """a × b for rows (n × 3, or one 3-vector against rows): np.cross without its overhead."""
    a, b = np.broadcast_arrays(a, b)
    out = np.empty(a.shape)
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def rodrigues(w, dt):
    """The rotation by the angle |w| dt about w."""
    th = np.linalg.norm(w) * dt
    if th < 1e-15:
        return np.eye(3)
    k = w / np.linalg.norm(w)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(th) * kx + (1 - math.cos(th)) * kx @ kx


class Springs:
    """Contacts by identity (a bed point, a ground point, a pair of edges): normal spring and
    damper, and an elastic-plastic tangential spring whose stretch persists while in touch."""

    def __init__(self, n, k, c, mu):
        self.k, self.c, self.mu = np.asarray(k, float), np.asarray(c, float), mu
        self.xi = np.zeros((n, 3))

    def force(self, idx, depth, normal, vel, dt):
        """Force on the block at contacts idx (depth > 0 inside, normal along which the block is
        pushed, vel the block's velocity there relative to the ground); the rest of the
        identities released."""
        k, c = self.k[idx], self.c[idx]
        vn = (vel * normal).sum(1)
        fn = np.maximum(k * depth - c * vn, 0.0)
        vt = vel - vn[:, None] * normal
        xi = self.xi[idx]
        xi = xi - (xi * normal).sum(1)[:, None] * normal + vt * dt
        ft = -k[:, None] * xi - c[:, None] * vt
        mag = np.linalg.norm(ft, axis=1)
        cap = self.mu * fn
        over = mag > cap
        scale = np.where(over, cap / np.maximum(mag, 1e-300), 1.0)
        ft = ft * scale[:, None]
        xi = np.where(over[:, None], -ft / np.maximum(k, 1e-300)[:, None], xi)
        keep = np.zeros(len(self.xi), bool)
        keep[idx] = True
        self.xi[~keep] = 0.0
        self.xi[idx] = xi
        return fn[:, None] * normal + ft, fn


def segment_pairs(p0, p1, q0, q1):
    """For segment pairs (p0 p1, q0 q1), n × 3 each: the closest points of their lines, whether
    both lie within their segments, and the unit common normal (upward)."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a = (d1 * d1).sum(1)
    e = (d2 * d2).sum(1)
    b = (d1 * d2).sum(1)
    c = (d1 * r).sum(1)
    f = (d2 * r).sum(1)
    den = a * e - b * b
    ok = den > 1e-12 * a * e
    den = np.where(ok, den, 1.0)
    s = (b * f - c * e) / den
    t = (a * f - b * c) / den
    within = ok & (s >= 0) & (s <= 1) & (t >= 0) & (t <= 1)
    n = cross(d1, d2)
    norm = np.linalg.norm(n, axis=1)
    # Edges within 6° of parallel (in plan) meet along a line, which the rows of points carry:
    # their common normal is then ill-defined (a rim along a ridge of the rock's grid).
    plan = np.abs(d1[:, 0] * d2[:, 2] - d1[:, 2] * d2[:, 0])
    crossing = plan > 0.1 * np.hypot(d1[:, 0], d1[:, 2]) * np.hypot(d2[:, 0], d2[:, 2])
    n = n / np.maximum(norm, 1e-300)[:, None]
    n = n * np.where(n[:, 1] < 0, -1.0, 1.0)[:, None]
    return p0 + s[:, None] * d1, q0 + t[:, None] * d2, within & crossing & (n[:, 1] > 0.05), n


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--start", required=True, help="slideroute's summary.json: start where it"
                                                   " rested")
    ap.add_argument("--out", required=True)
    ap.add_argument("--t-end", type=float, default=1.0)
    ap.add_argument("--dt", type=float, default=2e-5)
    ap.add_argument("--sink", type=float, default=1e-4,
                    help="m: a single contact carrying the whole weight sinks this far; the bed's"
                         " springs are as stiff per unit weight as such a contact")
    ap.add_argument("--mu-delta", type=float, default=0.0)
    ap.add_argument("--grid", type=int, default=20)
    ap.add_argument("--cast", action="store_true")
    ap.add_argument("--bend-weight", type=float, default=0.05)
    ap.add_argument("--reach", type=float, default=4.0,
                    help="the ground's ridges within this distance of the footprint, m")
    ap.add_argument("--ridge-step", type=float, default=0.1)
    ap.add_argument("--line-gap", type=float, default=2e-5)
    ap.add_argument("--point-ratio", type=float, default=1.0,
                    help="a ground point's or a crossing's spring against a mean bed cell's")
    ap.add_argument("--no-edges", action="store_true", help="no edge-against-edge contact")
    ap.add_argument("--dump", type=float, nargs="*", default=(),
                    help="print the contacts carrying the block at these times, s (diagnosis)")
    ap.add_argument("--quiet", action="store_true")
    a = ap.parse_args()
    clock = time.process_time()
    p = dr.load(a.scene, surface=True)
    p["mu"] += a.mu_delta
    if p["surface"] is None or p["record"] is not None:
        sys.exit(f"{a.scene}: bed_body.py takes a [foundation] surface and no record")
    with open(a.start) as f:
        summary = json.load(f)
    rest = summary["resting"] if "resting" in summary else summary["base"]["resting"]
    rot0 = np.array(rest["rotation"])
    cm0 = np.array([rest["x_m"], rest["y_m"], rest["z_m"]])
    v, tris = db.read_obj(p["surface"])
    ground = Mesh(v, tris)
    m, g, height = p["mass"], p["g"], p["height"]
    below = np.array([0.0, -height, 0.0])
    outline = p["outline"]
    xs, zs = [x for x, _ in outline], [z for _, z in outline]
    size = max(math.hypot(x, z) for x, z in outline)

    # The base: its bed (points, weights), its underside as seen by the ground's points, and
    # its convex edges (body axes).
    if a.cast:
        relief = db.Relief(v, tris, rot0, cm0, outline)
        step = min(max(xs) - min(xs), max(zs) - min(zs)) / a.grid
        bed, weights, _ = relief.bed(a.grid, step, a.bend_weight)
        underside = Mesh((v - cm0) @ rot0, tris)
        edges = [(e0, e1) for e0, e1, *_ in relief.convex_edges()]
    else:
        bed = np.array([c + below for c in dr.base_points(outline, a.grid)])
        weights = dr.base_weights(outline, a.grid)
        underside = None
        edges = [(np.array([x0, -height, z0]), np.array([x1, -height, z1]))
                 for (x0, z0), (x1, z1) in zip(outline, outline[1:] + outline[:1])]
    weights = np.asarray(weights, float)
    stiff = m * g / a.sink  # N/m of one contact of unit weight
    omega = math.sqrt(stiff * weights.sum() / m)  # the bed's bouncing, rad/s
    tau = 2.0 / omega  # damping time: the bed's bouncing critically damped
    every = max(1, int(round(1e-3 / a.dt)))
    if abs(every * a.dt - 1e-3) > 1e-12:
        sys.exit(f"--dt {a.dt:g} s: take a step that divides the millisecond the rows are at")
    if omega * a.dt > 0.3:
        sys.exit(f"--dt {a.dt:g} s: the bed bounces at {omega:.0f} rad/s; take dt below "
                 f"{0.3 / omega:.2e} s (or a larger --sink)")
    beds = Springs(len(bed), stiff * weights, stiff * weights * tau, p["mu"])

    start = (cm0[0], cm0[2])
    feats, _ = db.ridge_points(v, tris, start, math.inf, a.ridge_step)  # a long ridge's near part too
    feats = feats[np.hypot(feats[:, 0] - start[0], feats[:, 2] - start[1]) <= size + a.reach]
    feats = feats - np.array([0.0, a.line_gap, 0.0])
    lone = stiff * a.point_ratio  # a ground point's or a crossing's spring
    points = Springs(len(feats), np.full(len(feats), lone), np.full(len(feats), lone * tau),
                     p["mu"])
    ridges = []
    for e0, e1, _, _ in db.ridge_edges(v, tris):
        mid = (e0 + e1) / 2
        if math.hypot(mid[0] - start[0], mid[2] - start[1]) <= size + a.reach + np.linalg.norm(
                e1 - e0):
            ridges.append((e0, e1))
    if a.no_edges:
        ridges, edges = [], []
    r0 = np.array([q[0] for q in ridges]).reshape(-1, 3) - [0.0, a.line_gap, 0.0]
    r1 = np.array([q[1] for q in ridges]).reshape(-1, 3) - [0.0, a.line_gap, 0.0]
    b0 = np.array([q[0] for q in edges]).reshape(-1, 3)
    b1 = np.array([q[1] for q in edges]).reshape(-1, 3)
    ne, nr = len(b0), len(r0)
    crossings = Springs(ne * nr, np.full(ne * nr, lone), np.full(ne * nr, lone * tau),
                        p["mu"])

    inertia = np.array([[p["ix"], -p["ixy"], -p["ixz"]],
                        [-p["ixy"], p["iy"], 0.0],
                        [-p["ixz"], 0.0, p["iz"]]])
    cm, rot = cm0.copy(), rot0.copy()
    i0 = p["init"]
    vel = np.array([i0.get("vx_m_s", 0.0), 0.0, i0.get("vz_m_s", 0.0)])
    w = np.array([0.0, -math.radians(i0.get("omega_deg_s", 0.0)), 0.0])

    def loads(rot):
        """Force and moment about the CM (world) of the scene's loads and the weight."""
        force = np.array([p["kh"], p["kv"] - 1.0, 0.0]) * m * g
        moment = -p["c"] * p["force"] * rot[:, 1]
        acting = [(below, p["force"] * np.array([1.0, 0.0, 0.0]))] if p["plain"] else []
        acting += list(p["water"])
        for point, f in acting:
            fw = rot @ f
            force = force + fw
            moment = moment + cross(rot @ point, fw)
        return force, moment

    def say(*x):
        if not a.quiet:
            print(*x, file=sys.stderr)

    def report(kind, fn, body):
        """The contacts of one kind: their count, total and largest few."""
        say(f"  {kind}: {len(fn)} touching, {fn.sum():.4e} N")
        for j in np.argsort(-fn)[:6]:
            say(f"    {fn[j]:.4e} N at ({body[j, 0]:+.4f}, {body[j, 1]:+.4f}, {body[j, 2]:+.4f})")

    say(f"{a.scene}: {len(bed)} bed points{' (cast)' if a.cast else ''}, {len(feats)} ground"
        f" points, {ne} base edges x {nr} ridges; bed at {omega:.0f} rad/s, dt {a.dt:g} s,"
        f" sink {a.sink:g} m, mu {p['mu']}")
    pairs = np.zeros(0, int)
    rows = []
    steps = int(round(a.t_end / a.dt))
    min_ridge = math.inf
    for step_k in range(steps + 1):
        force, moment = loads(rot)
        # The bed against the ground.
        world = cm + bed @ rot.T
        k, y = ground.under(world[:, [0, 2]])
        n = ground.n[np.maximum(k, 0)]
        gap = (world[:, 1] - y) * n[:, 1]
        touch = np.nonzero((k >= 0) & (gap < 0))[0]
        arm = world[touch] - cm
        f, fn = beds.force(touch, -gap[touch], n[touch], vel + cross(w, arm), a.dt)
        dump = any(abs(step_k * a.dt - x) < a.dt / 2 for x in a.dump)
        if dump:
            say(f"t = {step_k * a.dt:.4f} s, weight {m * g:.4e} N; contacts (normal force, body"
                " point x', y', z'):")
            report("bed", fn, (world[touch] - cm) @ rot)
            faces = {}
            for j, kk in enumerate(k[touch]):
                faces.setdefault(int(kk), []).append(fn[j])
            say("    by the ground's triangle (Mesh index): " + ", ".join(
                f"{kk}: {len(x)} points {sum(x):.3e} N" for kk, x in
                sorted(faces.items(), key=lambda q: -sum(q[1]))))
        force = force + f.sum(0)
        moment = moment + cross(arm, f).sum(0)
        min_gap = float(np.nanmin(np.where(k >= 0, gap, np.nan)))
        # The ground's points against the base's underside.
        if step_k % every == 0:  # candidates: within 0.3 m of the footprint, every ms
            local = ((feats - cm) @ rot)[:, [0, 2]]
            close = np.nonzero((local[:, 0] > min(xs) - 0.3) & (local[:, 0] < max(xs) + 0.3)
                               & (local[:, 1] > min(zs) - 0.3)
                               & (local[:, 1] < max(zs) + 0.3))[0]
        body = (feats[close] - cm) @ rot
        near = close[inside_convex(body[:, [0, 2]], outline)
                     & (np.abs(body[:, 1] + height) < 1.0)]
        body = (feats[near] - cm) @ rot
        if underside is None:
            nb = np.tile([0.0, 1.0, 0.0], (len(near), 1))
            depth = body[:, 1] + height
        else:
            ku, yu = underside.under(body[:, [0, 2]])
            nb = underside.n[np.maximum(ku, 0)]
            depth = np.where(ku >= 0, (body[:, 1] - yu) * nb[:, 1], -np.inf)
        ridge_gap = float(-depth.max()) if len(near) else math.inf
        on = depth > 0
        idx, nw = near[on], nb[on] @ rot.T
        arm = feats[idx] - cm
        f, fn = points.force(idx, depth[on], nw, vel + cross(w, arm), a.dt)
        if dump:
            report("ground points", fn, (feats[idx] - cm) @ rot)
        force = force + f.sum(0)
        moment = moment + cross(arm, f).sum(0)
        # The ground's ridges across the base's convex edges.
        if ne and nr:
            e0, e1 = cm + b0 @ rot.T, cm + b1 @ rot.T
            if step_k % every == 0:  # candidates: plans within 0.2 m, refreshed every ms
                lo = np.minimum(e0, e1)[:, [0, 2]] - 0.2
                hi = np.maximum(e0, e1)[:, [0, 2]] + 0.2
                rlo, rhi = np.minimum(r0, r1)[:, [0, 2]], np.maximum(r0, r1)[:, [0, 2]]
                hitp = ((lo[:, None, :] <= rhi[None, :, :])
                        & (rlo[None, :, :] <= hi[:, None, :])).all(axis=2)
                pairs = np.flatnonzero(hitp)
            ie, ir = pairs // nr, pairs % nr
            pe, pr, within, nrm = segment_pairs(e0[ie], e1[ie], r0[ir], r1[ir])
            depth = ((pr - pe) * nrm).sum(1)
            on = within & (depth > 0)
            if within.any():
                ridge_gap = min(ridge_gap, float(-depth[within].max()))
            arm = pe[on] - cm
            f, fn = crossings.force(pairs[on], depth[on], nrm[on], vel + cross(w, arm), a.dt)
            if dump:
                report("edge crossings", fn, (pe[on] - cm) @ rot)
            force = force + f.sum(0)
            moment = moment + cross(arm, f).sum(0)
        min_ridge = min(min_ridge, ridge_gap)
        if step_k % every == 0 or step_k == steps:
            base = cm + rot @ below
            rows.append((round(step_k * a.dt, 9), *cm,
                         math.degrees(math.atan2(rot[2, 0], rot[0, 0])),
                         math.degrees(math.acos(np.clip(rot[1, 1], -1.0, 1.0))),
                         min_gap, *base, ridge_gap))
        if step_k == steps:
            break
        # Semi-implicit Euler: the velocities from the forces, then the pose from them.
        iw = rot @ inertia @ rot.T
        vel = vel + a.dt * force / m
        w = w + a.dt * np.linalg.solve(iw, moment - cross(w, iw @ w))
        cm = cm + a.dt * vel
        rot = rodrigues(w, a.dt) @ rot
        if step_k % 1000 == 0:
            u, _, vt = np.linalg.svd(rot)
            rot = u @ vt
        if not np.isfinite(cm).all() or np.linalg.norm(cm - cm0) > 1e3:
            sys.exit(f"{a.scene}: the block left at t = {step_k * a.dt:.4f} s")

    tmp = a.out + ".tmp"
    with open(tmp, "w", newline="") as out:
        wr = csv.writer(out)
        wr.writerow(["t_s", "x_m", "y_m", "z_m", "theta_deg", "tilt_deg", "min_gap_m",
                     "bx_m", "by_m", "bz_m", "ridge_gap_m"])
        wr.writerows(rows)
    os.replace(tmp, a.out)
    last = rows[-1]
    travel = sum(math.hypot(b[1] - c[1], b[3] - c[3]) for b, c in zip(rows[1:], rows))
    say(f"t = {last[0]:.3f} s: travel {travel:.4f} m, theta {last[4]:.4f} deg, tilt "
        f"{last[5]:.4f} deg; least gap {min(r[6] for r in rows):.3e} m (bed), "
        f"{min_ridge:.3e} m (ground's points and ridges); {time.process_time() - clock:.1f} s CPU")


if __name__ == "__main__":
    main()
