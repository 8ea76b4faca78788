//! All roots of many pose systems, one after another on one core, each pose's eigenvalues
//! continued from the pose before it.
//!
//! A pose's x-roots are the eigenvalues of its resultant's companion matrix (`roots/eigen.rs`).
//! Those of a pose solved before it in the batch, as real quadratic factors (its companion
//! matrix's invariant subspaces of dimension two, `numeric/bairstow.rs`), start Newton's method
//! for this pose's factors; the roots so found are kept only where they are certified (each
//! within a disk holding exactly one root, the disks disjoint, no two roots within 10⁻⁶), and
//! otherwise the pose is solved by the Francis QR iteration as [`eigen::solve`] solves it,
//! which also gives the next pose its start. The first pose of a batch has no start: QR.
//! y is the common root of the two quadratics, polished where it is not yet a root to 10⁻¹²,
//! on the terms of [`eigen`]'s recovery of y (which takes over where those fail). A certified
//! root lies within its disk (at most 10⁻⁶ relative) of a root of the resultant before its last
//! Newton step; measured against QR's eigenvalues on the default scene's poses, within 10⁻⁹
//! (not to the last bit). A batch's results depend on its poses and their order, never on the
//! thread that solves it. Derivation: `derivations/06-roots-and-tracking.md`
//! ("Many poses").

use super::eigen::{self, Coeffs, FixedRoots};
use crate::numeric::bairstow::{self, Factors};
use num_complex::Complex64 as C;

/// The start a batch carries from one pose to the next.
#[derive(Debug, Clone, Copy)]
struct Seed {
    /// The degree of the resultant it factors.
    deg: usize,
    factors: Factors,
}

/// A batch solver: what one pose hands the next, and counts of how poses were solved.
#[derive(Debug, Default)]
pub struct BatchSolver {
    seed: Option<Seed>,
    /// Poses whose roots were certified from the pose before (since [`BatchSolver::new`]).
    pub continued: usize,
    /// Poses solved by the QR iteration.
    pub by_qr: usize,
}

impl BatchSolver {
    /// A solver with nothing carried.
    pub fn new() -> Self {
        Self::default()
    }

    /// The roots of each system (p, q) of `systems` into `out` (cleared first, in order), the
    /// roots of `eigen::solve` (`roots/eigen.rs`) to the eigenvalues' accuracy. The first
    /// system starts afresh.
    pub fn solve(&mut self, systems: &[(Coeffs, Coeffs)], out: &mut Vec<FixedRoots>) {
        out.clear();
        self.seed = None;
        out.extend(systems.iter().map(|(p, q)| self.one(p, q)));
    }

    /// The roots of one system, continued from the last.
    fn one(&mut self, p: &Coeffs, q: &Coeffs) -> FixedRoots {
        let r = eigen::resultant(p, q);
        if r.deg == 0 {
            return eigen::assign_y_fixed(p, q, &[], r.at_infinity, false);
        }
        let monic = &r.monic[..r.deg];
        let (mut wr, mut wi) = ([0.0; 8], [0.0; 8]);
        let mut factors = [(0.0, 0.0); 4];
        let certified = self
            .seed
            .filter(|s| s.deg == r.deg)
            .and_then(|s| bairstow::roots(monic, &s.factors, &mut wr, &mut wi, &mut factors));
        let n = match certified {
            Some(n) => {
                self.continued += 1;
                n
            }
            None => {
                // Afresh, as `eigen::solve`: balanced Francis QR on the companion matrix.
                self.by_qr += 1;
                let Some(n) = eigen::companion_eigenvalues(monic, &mut wr, &mut wi) else {
                    self.seed = None;
                    return FixedRoots::from(&eigen::solve(p, q));
                };
                if !bairstow::factors_of(&wr[..n], &wi[..n], &mut factors) {
                    self.seed = None;
                    return eigen::assign_y_fixed(
                        p,
                        q,
                        &xs_of(&wr, &wi)[..n],
                        r.at_infinity,
                        false,
                    );
                }
                n
            }
        };
        self.seed = Some(Seed {
            deg: r.deg,
            factors,
        });
        let xs = &xs_of(&wr, &wi)[..n];
        match certified {
            Some(_) => eigen::assign_y_distinct(p, q, xs, r.at_infinity)
                .unwrap_or_else(|| eigen::assign_y_fixed(p, q, xs, r.at_infinity, false)),
            None => eigen::assign_y_fixed(p, q, xs, r.at_infinity, false),
        }
    }
}

/// The roots (re, im) as complex numbers.
fn xs_of(wr: &[f64; 8], wi: &[f64; 8]) -> [C; 8] {
    std::array::from_fn(|k| C::new(wr[k], wi[k]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Displacement;
    use crate::model::Mode;
    use crate::roots::{AllRoots, system};
    use crate::scene::Scene;
    use proptest::prelude::*;

    /// Random poses of the default scene: X in [0, 0.5] m, Z in [−0.2, 0.2] m, θ in [−3°, 3°]
    /// (a fixed linear congruential sequence), and a few special ones (θ = 0, the origin).
    fn poses(count: usize) -> Vec<Displacement> {
        let mut s = 31u64;
        let mut uniform = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut ds: Vec<Displacement> = (0..count)
            .map(|_| {
                Displacement::new(
                    0.5 * uniform(),
                    0.4 * uniform() - 0.2,
                    (6.0 * uniform() - 3.0f64).to_radians(),
                )
            })
            .collect();
        ds.extend([
            Displacement::new(0.0, 0.0, 0.0),
            Displacement::new(0.3, 0.0, 0.0),
            Displacement::new(0.3, 0.1, 0.0),
        ]);
        ds
    }

    fn systems(mode: Mode, ds: &[Displacement]) -> Vec<(Coeffs, Coeffs)> {
        let site = Scene::default_scene().site().clone();
        ds.iter()
            .map(|&d| system::biquadratic(&site, d, mode))
            .collect()
    }

    /// The same number of roots, at infinity too; each root within `tol` (relative, in x and
    /// y) of a distinct root solved alone, its residual at most 10⁻¹² where that one's is.
    /// Where the batch solved a pose by QR, the roots are those alone to the last bit.
    fn assert_same(systems: &[(Coeffs, Coeffs)], batch: &[FixedRoots], tol: f64) {
        assert_eq!(batch.len(), systems.len());
        for ((p, q), got) in systems.iter().zip(batch) {
            let alone = eigen::solve(p, q);
            assert_eq!(got.at_infinity, alone.at_infinity, "{p:?} {q:?}");
            assert_eq!(got.roots().len(), alone.roots.len(), "{p:?} {q:?}");
            let mut taken = [false; 8];
            for g in got.roots() {
                let k = (0..alone.roots.len())
                    .filter(|&k| !taken[k])
                    .min_by(|&i, &j| {
                        let gap = |a: &eigen::RawRoot| (a.x - g.x).norm() + (a.y - g.y).norm();
                        gap(&alone.roots[i]).total_cmp(&gap(&alone.roots[j]))
                    })
                    .unwrap();
                taken[k] = true;
                let a = &alone.roots[k];
                let size = 1.0 + a.x.norm().max(a.y.norm());
                assert!(
                    (a.x - g.x).norm().max((a.y - g.y).norm()) <= tol * size,
                    "{p:?} {q:?}: {g:?} against {a:?}"
                );
                assert!(g.residual <= a.residual.max(1e-12), "{g:?} against {a:?}");
            }
        }
    }

    #[test]
    fn batched_roots_of_random_poses_are_the_roots_solved_one_at_a_time() {
        let ds = poses(3000);
        for mode in [Mode::Exact, Mode::SmallAngle] {
            let systems = systems(mode, &ds);
            let (mut solver, mut out) = (BatchSolver::new(), Vec::new());
            solver.solve(&systems, &mut out);
            assert_same(&systems, &out, 1e-9);
            // Nearly every pose of the exact system continued from the one before (else this
            // tests QR alone); the small-angle system's roots are nearly double in pairs (its
            // structural multiplicity), and most of its poses go to QR.
            let most = match mode {
                Mode::Exact => 100,
                Mode::SmallAngle => 0,
            };
            assert!(
                solver.continued > 100 && solver.continued >= most * solver.by_qr,
                "{mode:?}: {} continued, {} by QR",
                solver.continued,
                solver.by_qr
            );
        }
    }

    #[test]
    fn a_pose_unlike_the_one_before_is_solved_afresh_as_alone() {
        let site = Scene::default_scene().site().clone();
        // Near θ = 0 the small-angle system's roots come in pairs closer than 10⁻⁶: the second
        // pose's roots, continued from the first's (of the same degree), are not certified.
        let near = Displacement::new(0.2, 0.05, 1f64.to_radians());
        let double = Displacement::new(0.2, 0.05, 1e-5f64.to_radians());
        let systems: Vec<_> = [near, double]
            .iter()
            .map(|&d| system::biquadratic(&site, d, Mode::SmallAngle))
            .collect();
        let degree = |(p, q): &(Coeffs, Coeffs)| eigen::resultant(p, q).deg;
        assert_eq!(degree(&systems[0]), degree(&systems[1]));
        let (mut solver, mut out) = (BatchSolver::new(), Vec::new());
        solver.solve(&systems, &mut out);
        // The first afresh (nothing before it); the second's roots not certified.
        assert_eq!((solver.continued, solver.by_qr), (0, 2));
        for ((p, q), got) in systems.iter().zip(&out) {
            assert_eq!(*got, FixedRoots::from(&eigen::solve(p, q)));
        }
        // The same pose twice: the second continued from the first.
        let twice = [systems[0], systems[0]];
        solver.solve(&twice, &mut out);
        assert_eq!((solver.continued, solver.by_qr), (1, 3));
        assert_same(&twice, &out, 1e-12);
    }

    #[test]
    fn a_batch_does_not_depend_on_the_batch_before() {
        let systems = systems(Mode::Exact, &poses(100));
        let (mut solver, mut first, mut again) = (BatchSolver::new(), Vec::new(), Vec::new());
        solver.solve(&systems, &mut first);
        solver.solve(&systems[50..], &mut again);
        solver.solve(&systems, &mut again);
        assert_eq!(first, again);
    }

    #[test]
    fn poses_solved_in_a_batch_are_classified_and_selected_as_one_at_a_time() {
        let site = Scene::default_scene().site().clone();
        let mut ds = poses(400);
        // Far off the branch (no admissible root), and not a displacement at all.
        ds.extend([
            Displacement::new(1.0, 0.0, (-30f64).to_radians()),
            Displacement::new(f64::NAN, 0.0, 0.0),
        ]);
        for mode in [Mode::Exact, Mode::SmallAngle] {
            let batch = crate::roots::solve_all_batch(&site, &ds, mode, &mut BatchSolver::new());
            assert_eq!(batch.len(), ds.len());
            for (&d, got) in ds.iter().zip(&batch) {
                let alone = crate::roots::solve_all(&site, d, mode);
                let (got, alone) = match (got, alone) {
                    (Ok(g), Ok(a)) => (g, a),
                    (g, a) => {
                        assert_eq!(format!("{g:?}"), format!("{a:?}"), "{mode:?} at {d:?}");
                        continue;
                    }
                };
                let at = format!("{mode:?} at {d:?}");
                assert_eq!(
                    (got.finite_roots, got.roots_at_infinity, got.roots.len()),
                    (
                        alone.finite_roots,
                        alone.roots_at_infinity,
                        alone.roots.len()
                    ),
                    "{at}"
                );
                assert_eq!(got.selection_error, alone.selection_error, "{at}");
                let flags = |r: &crate::roots::Root| {
                    (r.multiplicity, r.real, r.spurious, r.admissible, r.why_not)
                };
                let gap = |g: &crate::roots::Root, a: &crate::roots::Root| {
                    (g.alpha - a.alpha).norm().max((g.beta - a.beta).norm())
                        / (1.0 + a.alpha.norm() + a.beta.norm())
                };
                // Each root the nearest of those alone, with the same flags (a conjugate pair
                // may come in either order).
                for g in &got.roots {
                    let a = alone
                        .roots
                        .iter()
                        .min_by(|a, b| gap(g, a).total_cmp(&gap(g, b)))
                        .unwrap();
                    assert!(gap(g, a) <= 1e-9, "{at}: {g:?} against {a:?}");
                    assert_eq!(flags(g), flags(a), "{at}");
                }
                let selected = |r: &AllRoots| r.selected.map(|k| r.roots[k].clone());
                match (selected(got), selected(&alone)) {
                    (Some(g), Some(a)) => assert!(gap(&g, &a) <= 1e-9, "{at}"),
                    (g, a) => assert_eq!(g, a, "{at}"),
                }
            }
        }
    }

    fn coeffs() -> impl Strategy<Value = Coeffs> {
        proptest::array::uniform3(proptest::array::uniform3(-2.0..2.0f64))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Batches of arbitrary systems, some of them degenerate (a coefficient row zero, so
        /// the resultant's degree drops), give the roots of one system at a time, each within
        /// its certified disk (10⁻⁶).
        #[test]
        fn batched_roots_of_arbitrary_systems_are_the_roots_solved_one_at_a_time(
            mut systems in proptest::collection::vec((coeffs(), coeffs()), 1..23),
            zero_rows in proptest::collection::vec((0usize..23, 0usize..2, 0usize..3), 0..6),
            repeat in 0usize..3,
        ) {
            let n = systems.len();
            for (k, eq, row) in zero_rows {
                let (p, q) = &mut systems[k % n];
                let c = if eq == 0 { p } else { q };
                c[row] = [0.0; 3];
            }
            // Each system followed by itself, slightly moved, `repeat` times: continued where
            // certified.
            let systems: Vec<(Coeffs, Coeffs)> = systems
                .iter()
                .flat_map(|&(p, q)| {
                    (0..=repeat).map(move |k| {
                        // One coefficient moved (scaling all of p would move no root).
                        let mut q = q;
                        q[0][0] += 1e-3 * k as f64;
                        (p, q)
                    })
                })
                .collect();
            let mut out = Vec::new();
            BatchSolver::new().solve(&systems, &mut out);
            assert_same(&systems, &out, 1e-6);
        }
    }
}
