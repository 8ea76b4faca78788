//! The eigenvalue solver finds every finite root: the same set as an independent method —
//! Newton's method from a dense grid of complex starting points, deduplicated.

use crate::common::scene;
use num_complex::Complex64 as C;
use slideroute::Displacement;
use slideroute::Mode;
use slideroute::internals::roots::{self, eigen, system};

fn ev(c: &eigen::Coeffs, x: C, y: C) -> (C, C, C) {
    let (mut v, mut dx, mut dy) = (C::new(0.0, 0.0), C::new(0.0, 0.0), C::new(0.0, 0.0));
    for (i, row) in c.iter().enumerate() {
        for (j, &k) in row.iter().enumerate() {
            v += x.powu(i as u32) * y.powu(j as u32) * k;
            if i > 0 {
                dx += x.powu(i as u32 - 1) * y.powu(j as u32) * (k * i as f64);
            }
            if j > 0 {
                dy += x.powu(i as u32) * y.powu(j as u32 - 1) * (k * j as f64);
            }
        }
    }
    (v, dx, dy)
}

/// Distinct roots reached by Newton from a log-polar grid of complex starts.
fn newton_grid(p: &eigen::Coeffs, q: &eigen::Coeffs) -> Vec<(C, C)> {
    let mut starts = Vec::new();
    for &r in &[
        0.03, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0,
    ] {
        for k in 0..8 {
            let a = std::f64::consts::TAU * (k as f64 + 0.37) / 8.0;
            starts.push(C::from_polar(r, a));
        }
    }
    let mut found: Vec<(C, C)> = Vec::new();
    for &x0 in &starts {
        for &y0 in &starts {
            let (mut x, mut y) = (x0, y0);
            let mut ok = false;
            for _ in 0..80 {
                let (vp, px, py) = ev(p, x, y);
                let (vq, qx, qy) = ev(q, x, y);
                let det = px * qy - py * qx;
                if det.norm() == 0.0 {
                    break;
                }
                let dx = (vp * qy - vq * py) / det;
                let dy = (px * vq - qx * vp) / det;
                x -= dx;
                y -= dy;
                if !(x.is_finite() && y.is_finite()) || x.norm() > 1e8 {
                    break;
                }
                if dx.norm().max(dy.norm()) < 1e-13 * (1.0 + x.norm().max(y.norm())) {
                    ok = true;
                    break;
                }
            }
            if ok
                && !found
                    .iter()
                    .any(|(a, b)| (a - x).norm().max((b - y).norm()) < 1e-7)
            {
                found.push((x, y));
            }
        }
    }
    found
}

#[test]
fn eigen_roots_equal_newton_grid_roots_on_random_scenes() {
    let cases = [
        (10.0, 0.4, 0.5, 20.0, 25.0, 30.0, 0.5, 0.1, 1.7),
        (10.0, 0.3, 0.2, 5.0, 8.0, 10.0, 1.2, -0.3, -2.3),
        (30.0, 0.6, 0.7, 40.0, 35.0, 60.0, 4.0, 1.0, 5.0),
        (5.0, 0.5, 0.4, 2.0, 3.0, 45.0, 0.2, 0.05, 0.8),
        (12.0, 0.2, 0.9, 60.0, 65.0, 75.0, 1.0, 0.4, -4.0),
        (8.0, 0.7, 0.3, 15.0, 30.0, 5.0, 2.0, -0.5, 7.0),
    ];
    for (l, fx, fz, xi, ze, ka, x, z, th) in cases {
        let s = scene(l, fx, fz, xi, ze, ka);
        let d = Displacement::new(x, z, f64::to_radians(th));
        for mode in [Mode::SmallAngle, Mode::Exact] {
            let (p, q) = system::biquadratic(s.site(), d, mode);
            let eig = eigen::solve(&p, &q);
            let grid = newton_grid(&p, &q);
            assert_eq!(
                eig.roots.len(),
                grid.len(),
                "{mode:?} at {d:?}: eigen {:?} vs grid {grid:?}",
                eig.roots
            );
            for g in &grid {
                assert!(
                    eig.roots
                        .iter()
                        .any(|r| (r.x - g.0).norm().max((r.y - g.1).norm())
                            < 1e-7 * (1.0 + g.0.norm().max(g.1.norm()))),
                    "{mode:?}: grid root {g:?} missing from the eigen roots"
                );
            }
            let all = roots::solve_all(s.site(), d, mode).unwrap();
            assert_eq!(
                all.finite_roots + all.roots_at_infinity,
                roots::bezout_count(mode)
            );
        }
    }
}

#[test]
fn small_angle_has_eight_finite_roots_and_eight_at_infinity() {
    // Generic case: the mixed volume of (15)'s Newton polygons is 8 (derivations/06).
    let s = scene(10.0, 0.4, 0.5, 20.0, 25.0, 30.0);
    let all = roots::solve_all(
        s.site(),
        Displacement::new(0.7, 0.2, 0.04),
        Mode::SmallAngle,
    )
    .unwrap();
    assert_eq!(all.finite_roots, 8);
    assert_eq!(all.roots_at_infinity, 8);
}
