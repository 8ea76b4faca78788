//! The direct pose solver: the independent oracle.
//!
//! Given (X, Z, θ), find the orientation and height of the rigid frame that put each contact
//! on its plane (the paper's: vertex 0 on the horizontal plane, vertex 1 on plane 1 and vertex 2
//! on plane 2; each plane extended without limit). Unknowns: tilt (rotation about the horizontal normal of side 01), roll (rotation
//! about side 01) and CM height; the body is placed with nalgebra rotations and the residuals
//! are plain point-to-plane height differences. No polynomial and no paper formula is used.
//!
//! Newton's method with a central-difference Jacobian, continued along the straight segment
//! from the start pose (X = Z = θ = 0, frame flat) so that the pose found is the one reached
//! by sliding, not another solution of the same constraints.

use super::site::Site;
use super::{Displacement, GeometryError, LocalFrame};
use nalgebra::{Matrix3, Rotation3, Vector3};
use std::f64::consts::SQRT_2;

/// A pose found by the direct solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectPose {
    /// The displacement it is at.
    pub displacement: Displacement,
    /// Rotation about the horizontal normal of side 01 (rad): the elevation of side 01.
    pub tilt: f64,
    /// Rotation about side 01 (rad).
    pub roll: f64,
    /// CM height (m).
    pub cm_y: f64,
    /// Vertices 0, 1, 2 (global).
    pub vertices: [Vector3<f64>; 3],
    /// Largest constraint residual at the solution (m).
    pub residual: f64,
    /// Newton's iterations it took.
    pub iterations: usize,
}

impl DirectPose {
    /// Elevation of side 01 from the vertex heights: sin α = (Y1 − Y0)/L.
    pub fn alpha(&self, l: f64) -> f64 {
        ((self.vertices[1].y - self.vertices[0].y) / l).asin()
    }

    /// Elevation of side 02: sin β = (Y2 − Y0)/(√2 L).
    pub fn beta(&self, l: f64) -> f64 {
        ((self.vertices[2].y - self.vertices[0].y) / (SQRT_2 * l)).asin()
    }

    /// Elevation of side 1→2: sin γ = (Y2 − Y1)/L.
    pub fn gamma(&self, l: f64) -> f64 {
        ((self.vertices[2].y - self.vertices[1].y) / l).asin()
    }

    /// The local frame of its vertices (L the frame's side, m).
    pub fn frame(&self, l: f64) -> LocalFrame {
        LocalFrame::from_vertices(&self.vertices, l)
    }
}

/// Substeps of the continuation from the start pose.
const STEPS: usize = 16;
const MAX_ITERATIONS: usize = 60;

/// Places the rigid frame: yaw θ about +Y (so x' projects to (cos θ, 0, sin θ)), then tilt
/// about the body z axis, then roll about the body x axis.
fn place(site: &Site, d: Displacement, u: &Vector3<f64>) -> [Vector3<f64>; 3] {
    let rot = Rotation3::from_axis_angle(&Vector3::y_axis(), -d.theta)
        * Rotation3::from_axis_angle(&Vector3::z_axis(), u[0])
        * Rotation3::from_axis_angle(&Vector3::x_axis(), -u[1]);
    let cm = Vector3::new(d.x, u[2], d.z);
    site.contacts()
        .map(|[x, z]| cm + rot * Vector3::new(x, 0.0, z))
}

fn residual(site: &Site, d: Displacement, u: &Vector3<f64>) -> Vector3<f64> {
    let p = place(site, d, u);
    let mut r = Vector3::zeros();
    for (i, v) in p.iter().enumerate() {
        r[i] = v.y - site.planes()[i].height(v.x, v.z);
    }
    r
}

/// Newton from `guess` at a fixed displacement.
fn newton(site: &Site, d: Displacement, guess: Vector3<f64>) -> Result<Converged, GeometryError> {
    let l = site.l();
    let tol = 1e-14 * l;
    let mut u = guess;
    let mut r = residual(site, d, &u);
    for it in 1..=MAX_ITERATIONS {
        let mut jac = Matrix3::zeros();
        for j in 0..3 {
            let step = if j == 2 { 1e-6 * l } else { 1e-6 };
            let mut up = u;
            let mut dn = u;
            up[j] += step;
            dn[j] -= step;
            let col = (residual(site, d, &up) - residual(site, d, &dn)) / (2.0 * step);
            jac.set_column(j, &col);
        }
        let Some(delta) = jac.lu().solve(&(-r)) else {
            break;
        };
        u += delta;
        r = residual(site, d, &u);
        let small_step =
            delta[0].abs() < 1e-15 && delta[1].abs() < 1e-15 && delta[2].abs() < 1e-15 * l;
        if r.amax() <= tol || (small_step && r.amax() <= 1e-12 * l) {
            return Ok(Converged {
                u,
                residual: r.amax(),
                iterations: it,
            });
        }
    }
    Err(GeometryError::NotConverged {
        at: format!("X = {} m, Z = {} m, θ = {} rad", d.x, d.z, d.theta),
        residual: r.amax(),
        iterations: MAX_ITERATIONS,
    })
}

/// The pose reached by sliding from the start to `d` along a straight segment.
pub fn solve(site: &Site, d: Displacement) -> Result<DirectPose, GeometryError> {
    if !d.is_finite() {
        return Err(GeometryError::NonFinite(format!("{d:?}")));
    }
    let mut result = Converged {
        u: Vector3::zeros(),
        residual: 0.0,
        iterations: 0,
    };
    for k in 1..=STEPS {
        result = newton(site, d.scaled(k as f64 / STEPS as f64), result.u)?;
    }
    Ok(finish(site, d, result))
}

/// The pose at `d` by Newton from a nearby pose (e.g. the previous increment's). The tests
/// follow routes with it; the library's own routes follow the polynomial systems.
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn solve_from(
    site: &Site,
    d: Displacement,
    near: &DirectPose,
) -> Result<DirectPose, GeometryError> {
    let guess = Vector3::new(near.tilt, near.roll, near.cm_y);
    let result = newton(site, d, guess)?;
    Ok(finish(site, d, result))
}

/// Where Newton converged: u = (tilt, roll, CM height), the largest residual left and the
/// iterations it took.
struct Converged {
    u: Vector3<f64>,
    residual: f64,
    iterations: usize,
}

/// The pose at `d` from Newton's converged unknowns.
fn finish(site: &Site, d: Displacement, c: Converged) -> DirectPose {
    let u = c.u;
    DirectPose {
        displacement: d,
        tilt: u[0],
        roll: u[1],
        cm_y: u[2],
        vertices: place(site, d, &u),
        residual: c.residual,
        iterations: c.iterations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn start_is_the_flat_frame() {
        let s = Scene::default_scene();
        let p = solve(s.site(), Displacement::default()).unwrap();
        assert!(p.tilt.abs() < 1e-15 && p.roll.abs() < 1e-15 && p.cm_y.abs() < 1e-15);
    }

    #[test]
    fn pure_forward_slide_lifts_vertex_1_onto_plane_1() {
        // Sliding forward by X with θ = 0: vertex 1 climbs plane 1, vertex 0 stays down.
        let s = Scene::default_scene();
        let p = solve(s.site(), Displacement::new(0.5, 0.0, 0.0)).unwrap();
        let l = s.l();
        assert!(p.residual < 1e-12 * l);
        assert!(p.vertices[0].y.abs() < 1e-12);
        assert!(p.vertices[1].y > 0.0 && p.vertices[2].y > 0.0);
        let side = |a: usize, b: usize| (p.vertices[a] - p.vertices[b]).norm();
        assert!((side(0, 1) - l).abs() < 1e-12);
        assert!((side(1, 2) - l).abs() < 1e-12);
    }
}
