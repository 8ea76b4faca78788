//! Uncertain scene values (issue #17): the probability of sliding against its closed form.

use slideroute::stages::scene::Scene;
use slideroute::stages::uncertainty::{Sampling, Uncertain, run_sample, sample_values};

/// The paper-like block on 0.01° dips with the push through its centre of mass: it slides
/// when μ W < H, so with μ ~ normal(m, s) the probability of sliding is Φ((H/W − m)/s).
fn flat() -> Scene {
    let text =
        crate::common::paper_like_on_level_planes().replace("t_end_s = 20.0", "t_end_s = 0.001");
    Scene::from_toml(&text, "flat").unwrap()
}

/// Φ from Abramowitz & Stegun 26.2.17 (error under 7.5e-8), apart from the library's own.
fn phi(x: f64) -> f64 {
    let t = 1.0 / (1.0 + 0.231_641_9 * x.abs());
    let poly = t
        * (0.319_381_530
            + t * (-0.356_563_782
                + t * (1.781_477_937 + t * (-1.821_255_978 + t * 1.330_274_429))));
    let tail = (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt() * poly;
    if x >= 0.0 { 1.0 - tail } else { tail }
}

/// The estimated probability of sliding (factor of safety below 1) from `n` samples.
fn p_sliding(scene: &Scene, mu: &Uncertain, n: usize, seed: u64, sampling: Sampling) -> f64 {
    let keys = std::slice::from_ref(mu);
    let values = sample_values(keys, n, seed, sampling);
    let slid = values
        .iter()
        .enumerate()
        .filter(|(k, v)| {
            let r = run_sample(scene, keys, *k, v).unwrap();
            r.factor_of_safety.unwrap() < 1.0
        })
        .count();
    slid as f64 / n as f64
}

#[test]
fn the_probability_of_sliding_is_phi_of_the_margin_for_both_samplers() {
    let scene = flat();
    let (m, s) = (0.8, 0.05);
    let mu: Uncertain = format!("friction.mu_k=normal:{m}:{s}").parse().unwrap();
    let want = phi((8e6 / 9.81e6 - m) / s);
    let n = 300;
    let se = (want * (1.0 - want) / n as f64).sqrt();
    for sampling in [Sampling::MonteCarlo, Sampling::LatinHypercube] {
        let got = p_sliding(&scene, &mu, n, 7, sampling);
        assert!(
            (got - want).abs() < 3.0 * se,
            "{sampling:?}: {got} against {want} (standard error {se})"
        );
    }
}

#[test]
fn a_latin_hypercube_estimates_it_closer_than_plain_monte_carlo() {
    let scene = flat();
    let mu: Uncertain = "friction.mu_k=normal:0.8:0.05".parse().unwrap();
    let want = phi((8e6 / 9.81e6 - 0.8) / 0.05);
    let rms = |sampling: Sampling| {
        let sq: f64 = (1..=8)
            .map(|seed| (p_sliding(&scene, &mu, 60, seed, sampling) - want).powi(2))
            .sum();
        (sq / 8.0).sqrt()
    };
    let (mc, lhs) = (rms(Sampling::MonteCarlo), rms(Sampling::LatinHypercube));
    assert!(lhs < mc, "LHS {lhs} against MC {mc}");
}

#[test]
fn an_uncertain_key_the_scene_cannot_take_is_named() {
    let scene = flat();
    for (key, why) in [
        ("friction.mu_q", "mu_q"),
        ("friction.mu_k", "zero or positive"),
    ] {
        let u: Uncertain = format!("{key}=normal:-5:0.1").parse().unwrap();
        let values = sample_values(std::slice::from_ref(&u), 1, 1, Sampling::MonteCarlo);
        let e = run_sample(&scene, std::slice::from_ref(&u), 0, &values[0]).unwrap_err();
        assert!(e.key.contains(key), "{e}");
        assert!(e.to_string().contains(why), "{e}");
    }
}
