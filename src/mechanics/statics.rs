//! Frictionless normal reactions, paper eqs. (25)–(27).
//!
//! N_i^S = c_i n̂_i with the three magnitudes fixed by (26): ΣF·j' = 0, ΣM·i' = 0, ΣM·k' = 0
//! (the paper's hydraulic force lies along i' and its couple along j', so only the weight and
//! the reactions enter; uplift, the water's pitch and pseudo-static forces enter too where a
//! scene has them). A statically determinate 3×3 linear system.

use super::ContactGeometry;
use super::loads::Applied;
use nalgebra::{Matrix3, Vector3};

/// The three normal magnitudes c0, c1, c2 (N); a non-positive one means that contact lifts off.
/// `None` if the system is singular (the frame is degenerate).
pub fn frictionless_normals(geom: &ContactGeometry, applied: &Applied) -> Option<[f64; 3]> {
    let f = &geom.frame;
    let mut a = Matrix3::zeros();
    for i in 0..3 {
        let n = geom.n[i];
        let m = geom.r[i].cross(&n);
        a[(0, i)] = n.dot(&f.j);
        a[(1, i)] = m.dot(&f.i);
        a[(2, i)] = m.dot(&f.k);
    }
    // Right-hand side: minus the loads' contributions (weight along j', couple about i', k').
    let (force, moment) = (applied.total_force(), applied.total_moment());
    let b = Vector3::new(-force.dot(&f.j), -moment.dot(&f.i), -moment.dot(&f.k));
    // Cramer's rule on the 3×3 (the columns' cross products): a fraction of an LU's cost, and
    // as accurate at this size for the well-conditioned frames where the route runs.
    let (c0, c1, c2) = (a.column(0), a.column(1), a.column(2));
    let det = c0.dot(&c1.cross(&c2));
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let c = [
        b.dot(&c1.cross(&c2)) / det,
        c0.dot(&b.cross(&c2)) / det,
        c0.dot(&c1.cross(&b)) / det,
    ];
    c.iter().all(|v| v.is_finite()).then_some(c)
}

/// The paper's ratios (27): m1 = |N1^S|/|N0^S|, m2 = |N2^S|/|N0^S|.
pub fn ratios(c: &[f64; 3]) -> [f64; 3] {
    [1.0, c[1] / c[0], c[2] / c[0]]
}
