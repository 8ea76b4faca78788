//! All roots of many pose systems at once: [`eigen::solve`] for a batch, its companion
//! matrices' eigenvalues found together (`numeric/hessenberg_lanes.rs`: balancing and Francis
//! QR in lockstep across matrices, every lane's arithmetic that of one matrix alone).
//!
//! The resultant and the recovery of y are [`eigen`]'s own, one system at a time, into fixed
//! storage; the buffers are the solver's and are reused from one batch to the next. A system
//! whose iteration does not converge is solved alone by [`eigen::solve`], as it would have
//! been (which falls back to the 8×8 pencil). The roots are therefore those of
//! [`eigen::solve`], to the last bit.

use super::eigen::{self, Coeffs, FixedRoots, Resultant};
use crate::numeric::hessenberg::{Hessenberg, MAX_SWEEPS};
use crate::numeric::hessenberg_lanes::{self, Eigenvalues, Scratch};
use num_complex::Complex64 as C;

/// The systems solved together: their buffers (about 1.5 kB a system) stay in the nearest
/// cache.
const SUBBATCH: usize = 32;

/// The buffers of a batch solve, kept for the next batch.
#[derive(Default)]
pub struct BatchSolver {
    /// Each system's resultant.
    resultants: Vec<Resultant>,
    /// The companion matrices of the resultants of positive degree, in order.
    companions: Vec<Hessenberg>,
    /// Their eigenvalues.
    eigenvalues: Vec<Eigenvalues>,
    scratch: Scratch,
}

impl BatchSolver {
    /// A solver with empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// The roots of each system (p, q) of `systems` into `out` (cleared first, in order), as
    /// the one-system eigenvalue solve (`roots/eigen.rs`) gives them.
    pub fn solve(&mut self, systems: &[(Coeffs, Coeffs)], out: &mut Vec<FixedRoots>) {
        self.solve_within(systems, out, MAX_SWEEPS);
    }

    /// [`BatchSolver::solve`], a system's iteration in the batch given up after `max_sweeps`
    /// sweeps without a deflation (tests reach the fallback through it).
    pub(crate) fn solve_within(
        &mut self,
        systems: &[(Coeffs, Coeffs)],
        out: &mut Vec<FixedRoots>,
        max_sweeps: usize,
    ) {
        out.clear();
        // A few at a time, so that the buffers stay in the nearest cache.
        for part in systems.chunks(SUBBATCH) {
            self.solve_part(part, out, max_sweeps);
        }
    }

    /// The roots of `systems`, appended to `out`.
    fn solve_part(
        &mut self,
        systems: &[(Coeffs, Coeffs)],
        out: &mut Vec<FixedRoots>,
        max_sweeps: usize,
    ) {
        self.resultants.clear();
        self.companions.clear();
        for (p, q) in systems {
            let r = eigen::resultant(p, q);
            if r.deg > 0 {
                self.companions
                    .push(Hessenberg::companion(&r.monic[..r.deg]));
            }
            self.resultants.push(r);
        }
        hessenberg_lanes::eigenvalues(
            &self.companions,
            &mut self.eigenvalues,
            &mut self.scratch,
            max_sweeps,
        );
        let mut eigenvalues = self.eigenvalues.iter();
        for ((p, q), r) in systems.iter().zip(&self.resultants) {
            let found = if r.deg == 0 {
                Some(([0.0; 8], [0.0; 8], 0))
            } else {
                eigenvalues.next().copied().flatten()
            };
            out.push(match found {
                Some((wr, wi, n)) => {
                    let mut xs = [C::new(0.0, 0.0); 8];
                    for k in 0..n {
                        xs[k] = C::new(wr[k], wi[k]);
                    }
                    eigen::assign_y_fixed(p, q, &xs[..n], r.at_infinity, false)
                }
                // Not converged in the batch: this system alone, as before.
                None => FixedRoots::from(&eigen::solve(p, q)),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Displacement;
    use crate::model::Mode;
    use crate::roots::system;
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

    /// The same roots in the same order to the last bit, the same count at infinity.
    fn assert_same(systems: &[(Coeffs, Coeffs)], batch: &[FixedRoots]) {
        assert_eq!(batch.len(), systems.len());
        for ((p, q), got) in systems.iter().zip(batch) {
            let alone = eigen::solve(p, q);
            assert_eq!(got.at_infinity, alone.at_infinity, "{p:?} {q:?}");
            assert_eq!(got.roots().len(), alone.roots.len(), "{p:?} {q:?}");
            for (g, a) in got.roots().iter().zip(&alone.roots) {
                let bits = |r: &eigen::RawRoot| {
                    [r.x.re, r.x.im, r.y.re, r.y.im, r.residual].map(f64::to_bits)
                };
                assert_eq!(bits(g), bits(a), "{p:?} {q:?}: {g:?} against {a:?}");
            }
        }
    }

    #[test]
    fn batched_roots_of_random_poses_equal_the_roots_solved_one_at_a_time() {
        let ds = poses(3000);
        for mode in [Mode::Exact, Mode::SmallAngle] {
            let systems = systems(mode, &ds);
            let mut out = Vec::new();
            BatchSolver::new().solve(&systems, &mut out);
            assert_same(&systems, &out);
        }
    }

    #[test]
    fn a_system_whose_batched_iteration_fails_is_solved_alone() {
        let systems = systems(Mode::Exact, &poses(200));
        let mut solver = BatchSolver::new();
        let (mut out, mut failed) = (Vec::new(), Vec::new());
        // Three sweeps without a deflation: too few for some of these matrices.
        solver.solve_within(&systems, &mut out, 3);
        hessenberg_lanes::eigenvalues(&solver.companions, &mut failed, &mut Scratch::default(), 3);
        let gave_up = failed.iter().filter(|e| e.is_none()).count();
        assert!(gave_up > 0, "every matrix converged in three sweeps");
        assert_same(&systems, &out);
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
                // Compared as written out: every number to the last digit (and NaN as NaN).
                let alone = crate::roots::solve_all(&site, d, mode);
                assert_eq!(
                    format!("{got:?}"),
                    format!("{alone:?}"),
                    "{mode:?} at {d:?}"
                );
            }
        }
    }

    fn coeffs() -> impl Strategy<Value = Coeffs> {
        proptest::array::uniform3(proptest::array::uniform3(-2.0..2.0f64))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Batches of arbitrary systems, some of them degenerate (a coefficient row zero, so
        /// the resultant's degree drops), give the roots of one system at a time.
        #[test]
        fn batched_roots_of_arbitrary_systems_equal_the_roots_solved_one_at_a_time(
            mut systems in proptest::collection::vec((coeffs(), coeffs()), 1..23),
            zero_rows in proptest::collection::vec((0usize..23, 0usize..2, 0usize..3), 0..6),
        ) {
            let n = systems.len();
            for (k, eq, row) in zero_rows {
                let (p, q) = &mut systems[k % n];
                let c = if eq == 0 { p } else { q };
                c[row] = [0.0; 3];
            }
            let mut out = Vec::new();
            BatchSolver::new().solve(&systems, &mut out);
            assert_same(&systems, &out);
        }
    }
}
