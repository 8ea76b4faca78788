//! Which uncertain value matters: Spearman's rank correlation of each sampled value
//! with the factor of safety and with the travel — the sensitivity tornado's bars. Ranks, not
//! values, so that a monotone effect of any shape counts fully and an infinite factor of safety
//! (a block no multiple of the loads starts) is simply the largest.

#[cfg(test)]
use super::Sample;
#[cfg(test)]
use crate::analysis::runner::RouteResult;

/// Spearman's ρ of paired values: the Pearson correlation of their ranks, ties given their
/// mean rank. Pairs with a NaN are left out; `None` with fewer than three pairs or where either
/// side is constant.
pub fn spearman(pairs: &[(f64, f64)]) -> Option<f64> {
    let kept: Vec<(f64, f64)> = pairs
        .iter()
        .copied()
        .filter(|(a, b)| !a.is_nan() && !b.is_nan())
        .collect();
    if kept.len() < 3 {
        return None;
    }
    let ra = ranks(&kept.iter().map(|p| p.0).collect::<Vec<_>>());
    let rb = ranks(&kept.iter().map(|p| p.1).collect::<Vec<_>>());
    pearson(&ra, &rb)
}

/// Ranks 1…n, ties given their mean rank.
fn ranks(v: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&i, &j| v[i].total_cmp(&v[j]));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && v[order[j + 1]] == v[order[i]] {
            j += 1;
        }
        let mean = 0.5 * ((i + 1) + (j + 1)) as f64;
        for &k in &order[i..=j] {
            r[k] = mean;
        }
        i = j + 1;
    }
    r
}

fn pearson(a: &[f64], b: &[f64]) -> Option<f64> {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma) * (x - ma);
        sbb += (y - mb) * (y - mb);
    }
    (saa > 0.0 && sbb > 0.0).then(|| (sab / (saa * sbb).sqrt()).clamp(-1.0, 1.0))
}

/// One uncertain value's rank correlations, over the samples whose route ran.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Sensitivity {
    /// The uncertain scene key.
    pub key: String,
    /// With the factor of safety (absent where it cannot be had: too few samples, or one side
    /// constant).
    pub with_factor_of_safety: Option<f64>,
    /// With the travel.
    pub with_travel: Option<f64>,
}

/// The rank correlations of each of `keys` with the factor of safety and the travel, of samples
/// held in a list (`Tally` computes them without one).
#[cfg(test)]
pub fn sensitivities(keys: &[String], samples: &[Sample]) -> Vec<Sensitivity> {
    let routes: Vec<(&[f64], &RouteResult)> = samples
        .iter()
        .filter_map(|s| Some((s.values.as_slice(), s.outcome.route()?)))
        .collect();
    keys.iter()
        .enumerate()
        .map(|(k, key)| {
            let with = |f: &dyn Fn(&RouteResult) -> f64| {
                let pairs: Vec<(f64, f64)> = routes.iter().map(|(v, r)| (v[k], f(r))).collect();
                spearman(&pairs)
            };
            Sensitivity {
                key: key.clone(),
                with_factor_of_safety: with(&|r| r.factor_of_safety_value().unwrap_or(f64::NAN)),
                with_travel: with(&|r| r.travel_m),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_monotone_relation_of_any_shape_has_rank_correlation_one() {
        let pairs: Vec<(f64, f64)> = (1..50)
            .map(|i| (f64::from(i), f64::from(i).exp()))
            .collect();
        assert_eq!(spearman(&pairs), Some(1.0));
        let falling: Vec<(f64, f64)> = pairs.iter().map(|&(a, b)| (a, -b)).collect();
        assert_eq!(spearman(&falling), Some(-1.0));
        // An infinite value is simply the largest.
        let mut with_inf = pairs.clone();
        with_inf.push((100.0, f64::INFINITY));
        assert_eq!(spearman(&with_inf), Some(1.0));
    }

    #[test]
    fn spearman_matches_a_hand_count_with_ties() {
        // x ranks 1, 2, 3, 4; y = 1, 3, 3, 2 ranks 1, 3.5, 3.5, 2. Mean ranks 2.5 both;
        // deviations x: −1.5, −0.5, 0.5, 1.5; y: −1.5, 1, 1, −0.5.
        // Σdxdy = 2.25 − 0.5 + 0.5 − 0.75 = 1.5; Σdx² = 5; Σdy² = 2.25 + 1 + 1 + 0.25 = 4.5.
        let pairs = [(1.0, 1.0), (2.0, 3.0), (3.0, 3.0), (4.0, 2.0)];
        let want = 1.5 / (5.0_f64 * 4.5).sqrt();
        assert!((spearman(&pairs).unwrap() - want).abs() < 1e-15);
    }

    #[test]
    fn too_few_or_constant_values_have_no_rank_correlation() {
        assert_eq!(spearman(&[(1.0, 2.0), (2.0, 3.0)]), None);
        assert_eq!(spearman(&[(1.0, 2.0), (2.0, 2.0), (3.0, 2.0)]), None);
        assert_eq!(
            spearman(&[(1.0, f64::NAN), (2.0, 2.0), (3.0, 1.0), (4.0, 0.0)]),
            Some(-1.0)
        );
    }
}
