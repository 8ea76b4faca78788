//! The pose of the frame for given tilts.
//!
//! [`Pose::from_tilts`] follows the paper: γ from eq. (1), h from eq. (2), the projected
//! triangle (Figure 5) and the CM height of eq. (21). [`Pose::from_tilt_roll`] builds the same
//! pose from the tilt α of side 01 and the roll ψ about it (the unknowns of the exact form,
//! `derivations/04-exact.md`). Neither checks that the contacts are on their planes: that is
//! what the polynomial systems and the direct solver decide.

use super::site::{PaperSite, Site};
use super::{Displacement, GeometryError, LocalFrame};
use nalgebra::Vector3;
use std::f64::consts::SQRT_2;

/// A placed frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// The displacement it is at.
    pub displacement: Displacement,
    /// α: the elevation of side 01 (rad).
    pub alpha: f64,
    /// β: the elevation of side 02 (rad).
    pub beta: f64,
    /// γ: the elevation of side 1→2 (rad).
    pub gamma: f64,
    /// Interior projection angle between sides 01 and 02 (rad, eq. 2).
    pub h: f64,
    /// Roll of the frame about side 01 (rad): k' = cos ψ·w + sin ψ·n, with w the horizontal
    /// normal of i' and n the upward normal of i' in its vertical plane.
    pub psi: f64,
    /// Vertices 0, 1, 2 in global (X, Y, Z).
    pub vertices: [Vector3<f64>; 3],
    /// CM in global coordinates (eq. 21).
    pub cm: Vector3<f64>,
    /// The local axes (i', j', k').
    pub frame: LocalFrame,
}

/// cos h from eq. (2): (cos 45° − sin α sin β) / (cos α cos β).
pub fn cos_h(alpha: f64, beta: f64) -> f64 {
    (SQRT_2 / 2.0 - alpha.sin() * beta.sin()) / (alpha.cos() * beta.cos())
}

/// sin γ from eq. (1): √2 sin β − sin α.
pub fn sin_gamma(alpha: f64, beta: f64) -> f64 {
    SQRT_2 * beta.sin() - alpha.sin()
}

/// CM height from eq. (21): (L1X − L1Z) sin α + √2 L1Z sin β.
pub fn cm_height(site: &PaperSite, alpha: f64, beta: f64) -> f64 {
    let f = &site.frame;
    (f.l1x - f.l1z) * alpha.sin() + SQRT_2 * f.l1z * beta.sin()
}

/// ψ from (α, β) on the branch cos ψ ≥ 0 (sin h ≥ 0).
pub fn roll_of_tilts(alpha: f64, beta: f64) -> f64 {
    (-sin_gamma(alpha, beta) / alpha.cos()).asin()
}

fn finite(d: Displacement, a: f64, b: f64) -> Result<(), GeometryError> {
    if d.is_finite() && a.is_finite() && b.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::NonFinite(format!(
            "X = {}, Z = {}, θ = {}, angles {a}, {b}",
            d.x, d.z, d.theta
        )))
    }
}

impl Pose {
    /// The pose at displacement `d` with tilts α, β (rad), by the paper's relations (the
    /// paper's frame).
    pub fn from_tilts(
        site: &PaperSite,
        d: Displacement,
        alpha: f64,
        beta: f64,
    ) -> Result<Pose, GeometryError> {
        finite(d, alpha, beta)?;
        let ch = cos_h(alpha, beta);
        let sg = sin_gamma(alpha, beta);
        if !(-1.0..=1.0).contains(&ch) || !(-1.0..=1.0).contains(&sg) || alpha.cos() <= 0.0 {
            return Err(GeometryError::NoRealFrame(format!(
                "α = {:.6}°, β = {:.6}° give cos h = {ch}, sin γ = {sg}",
                alpha.to_degrees(),
                beta.to_degrees()
            )));
        }
        let h = ch.acos();
        let (sa, ca) = alpha.sin_cos();
        let cb = beta.cos();
        let l = site.frame.l();
        let (st, ct) = d.theta.sin_cos();
        let (sth, cth) = (d.theta - h).sin_cos();
        // Projected sides (Figure 5): 01 along θ with length L cos α, 02 along θ − h with
        // length √2 L cos β; k' = (P1 − P2)/L.
        let i = Vector3::new(ca * ct, sa, ca * st);
        let k = Vector3::new(
            ca * ct - SQRT_2 * cb * cth,
            -sg,
            ca * st - SQRT_2 * cb * sth,
        );
        let f = &site.frame;
        let cm = Vector3::new(d.x, cm_height(site, alpha, beta), d.z);
        let p0 = cm - f.l1x * i + f.l1z * k;
        let vertices = [p0, p0 + l * i, p0 + l * i - l * k];
        let frame = LocalFrame::from_vertices(&vertices, l);
        Ok(Pose {
            displacement: d,
            alpha,
            beta,
            gamma: sg.asin(),
            h,
            psi: roll_of_tilts(alpha, beta),
            vertices,
            cm,
            frame,
        })
    }

    /// The pose at displacement `d` with tilt α of the x' axis (side 01 of the paper's frame)
    /// and roll ψ about it (rad), with contact 0 on its plane. Any ψ is allowed (cos ψ < 0 is
    /// the mirrored frame, h < 0).
    pub fn from_tilt_roll(
        site: &Site,
        d: Displacement,
        alpha: f64,
        psi: f64,
    ) -> Result<Pose, GeometryError> {
        finite(d, alpha, psi)?;
        let (sa, ca) = alpha.sin_cos();
        let (sp, cp) = psi.sin_cos();
        let (st, ct) = d.theta.sin_cos();
        let i = Vector3::new(ca * ct, sa, ca * st);
        let w = Vector3::new(-st, 0.0, ct);
        let n = Vector3::new(-sa * ct, ca, -sa * st);
        let k = cp * w + sp * n;
        let (vertices, cm, frame, lengths) = match site.as_paper() {
            Some(p) => {
                let f = &p.frame;
                let l = f.l();
                // Vertex 0 on the horizontal plane fixes the CM height.
                let cm_y = f.l1x * i.y - f.l1z * k.y;
                let cm = Vector3::new(d.x, cm_y, d.z);
                let p0 = cm - f.l1x * i + f.l1z * k;
                let vertices = [p0, p0 + l * i, p0 + l * i - l * k];
                let frame = LocalFrame::from_vertices(&vertices, l);
                (vertices, cm, frame, (SQRT_2 * l, l))
            }
            None => {
                // Contact 0 on its plane fixes the CM height: m0·(C + x0 i' + z0 k') = e0.
                let c = site.contacts();
                let plane = site.planes()[0];
                let m = plane.normal();
                let local = |q: &[f64; 2]| q[0] * i + q[1] * k;
                let cm_y = (plane.offset() - m.x * d.x - m.z * d.z - m.dot(&local(&c[0]))) / m.y;
                let cm = Vector3::new(d.x, cm_y, d.z);
                let vertices = c.map(|q| cm + local(&q));
                let side = |a: usize, b: usize| (c[b][0] - c[a][0]).hypot(c[b][1] - c[a][1]);
                (
                    vertices,
                    cm,
                    LocalFrame::from_axes(i, k),
                    (side(0, 2), side(1, 2)),
                )
            }
        };
        let beta = ((vertices[2].y - vertices[0].y) / lengths.0).asin();
        let gamma = ((vertices[2].y - vertices[1].y) / lengths.1).asin();
        // Signed projection angle between sides 01 and 02 (positive: vertex 2 on the −z' side
        // of side 01, as in the paper's frame).
        let e01 = vertices[1] - vertices[0];
        let e01 = Vector3::new(e01.x, 0.0, e01.z);
        let e02 = vertices[2] - vertices[0];
        let e02 = Vector3::new(e02.x, 0.0, e02.z);
        let h = (e01.z * e02.x - e01.x * e02.z).atan2(e01.dot(&e02));
        Ok(Pose {
            displacement: d,
            alpha,
            beta,
            gamma,
            h,
            psi,
            vertices,
            cm,
            frame,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    fn scene() -> Scene {
        Scene::default_scene()
    }

    #[test]
    fn flat_pose_puts_vertices_at_their_start_positions() {
        let s = scene();
        let p = Pose::from_tilts(
            s.site().as_paper().unwrap(),
            Displacement::default(),
            0.0,
            0.0,
        )
        .unwrap();
        for (v, r) in p
            .vertices
            .iter()
            .zip(s.site.as_paper().unwrap().frame.vertices())
        {
            assert!((v - Vector3::new(r[0], 0.0, r[1])).norm() < 1e-14);
        }
        assert!((p.h - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
    }

    #[test]
    fn both_constructions_agree_and_keep_the_frame_rigid() {
        let s = scene();
        let d = Displacement::new(0.8, -0.4, 0.2);
        for &(alpha, psi) in &[(0.05, 0.02), (0.3, -0.25), (0.6, 0.9)] {
            let a = Pose::from_tilt_roll(s.site(), d, alpha, psi).unwrap();
            let b = Pose::from_tilts(s.site().as_paper().unwrap(), d, alpha, a.beta).unwrap();
            for (u, v) in a.vertices.iter().zip(&b.vertices) {
                assert!((u - v).norm() < 1e-12, "{u} vs {v}");
            }
            assert!((a.h - b.h).abs() < 1e-12);
            assert!((b.psi - psi).abs() < 1e-12);
            let l = s.l();
            let side = |p: usize, q: usize| (a.vertices[p] - a.vertices[q]).norm();
            assert!((side(0, 1) - l).abs() < 1e-12);
            assert!((side(1, 2) - l).abs() < 1e-12);
            assert!((side(0, 2) - SQRT_2 * l).abs() < 1e-12);
            assert!(a.vertices[0].y.abs() < 1e-12);
            let r = a.frame.r();
            assert!((r * r.transpose() - nalgebra::Matrix3::identity()).norm() < 1e-14);
            assert!((r.determinant() - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn tilts_without_a_real_frame_are_an_error() {
        let s = scene();
        let e = Pose::from_tilts(
            s.site().as_paper().unwrap(),
            Displacement::default(),
            1.5,
            -1.5,
        );
        assert!(matches!(e, Err(GeometryError::NoRealFrame(_))));
        let e = Pose::from_tilts(
            s.site().as_paper().unwrap(),
            Displacement::default(),
            f64::NAN,
            0.0,
        );
        assert!(matches!(e, Err(GeometryError::NonFinite(_))));
    }
}
