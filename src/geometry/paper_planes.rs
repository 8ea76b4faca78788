//! The foundation (see `docs/conventions.md`, "The foundation"): the horizontal plane Y = 0
//! carries vertex 0; plane 1, Y = (X − L2X) tan ξ for X ≥ L2X, carries vertex 1; plane 2,
//! Y = (n·(X, Z) − R) tan ζ for n·(X, Z) ≥ R with n = (cos κ, −sin κ), carries vertex 2.
//! Each contact is held on its own infinite plane; the regions say where the plane is real.

use super::site::PaperSite;

/// R: the distance from the start CM to int. line 2/horiz (eq. 4).
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn r(site: &PaperSite) -> f64 {
    let k = site.foundation.kappa;
    site.frame.l2x * k.cos() + site.frame.l2z * k.sin()
}

/// n·(X, Z) with n = (cos κ, −sin κ) (S of eq. 5 when applied to the CM).
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn along_dip_2(site: &PaperSite, x: f64, z: f64) -> f64 {
    let k = site.foundation.kappa;
    x * k.cos() - z * k.sin()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use nalgebra::Vector3;

    /// Which of the paper's planes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    enum PaperPlane {
        /// The horizontal plane, under contact 0.
        Horizontal,
        /// Plane 1, under contact 1.
        One,
        /// Plane 2, under contact 2.
        Two,
    }

    /// The height of `plane` (extended without limit) above (X, Z), by the paper's eqs. (4), (5),
    /// written apart from the site's planes to hold them to it.
    fn height(site: &PaperSite, plane: PaperPlane, x: f64, z: f64) -> f64 {
        let g = &site.foundation;
        match plane {
            PaperPlane::Horizontal => 0.0,
            PaperPlane::One => (x - site.frame.l2x) * g.xi.tan(),
            PaperPlane::Two => (along_dip_2(site, x, z) - r(site)) * g.zeta.tan(),
        }
    }

    #[test]
    fn start_vertices_lie_on_the_strike_lines() {
        let scene = Scene::default_scene();
        let site = scene.site().as_paper().unwrap();
        let v = site.frame.vertices();
        // Vertex 1 on int. line 1/horiz, vertex 2 on int. line 2/horiz: both heights zero.
        assert!(height(site, PaperPlane::One, v[1][0], v[1][1]).abs() < 1e-12);
        assert!(height(site, PaperPlane::Two, v[2][0], v[2][1]).abs() < 1e-12);
    }

    #[test]
    fn normals_are_unit_and_orthogonal_to_the_planes() {
        let scene = Scene::default_scene();
        let site = scene.site().as_paper().unwrap();
        let normals = site.foundation.normals();
        for (k, plane) in [PaperPlane::Horizontal, PaperPlane::One, PaperPlane::Two]
            .into_iter()
            .enumerate()
        {
            let n = normals[k];
            assert!((n.norm() - 1.0).abs() < 1e-15);
            // Two points of the plane: the difference is orthogonal to n.
            let p = |x: f64, z: f64| Vector3::new(x, height(site, plane, x, z), z);
            // The site's general plane is the same plane.
            let general = scene.site().planes()[k];
            assert!((general.height(7.0, 1.0) - height(site, plane, 7.0, 1.0)).abs() < 1e-12);
            let d1 = p(7.0, 1.0) - p(5.0, -2.0);
            assert!(n.dot(&d1).abs() < 1e-12);
        }
    }
}
