//! Uncertain scene values: the probability of sliding against its closed form.

use slideroute::Scene;
use slideroute::probabilistic::{Sampling, Uncertain, sample_scene, sample_values};

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
        .filter(|v| {
            let r = slideroute::run(&sample_scene(scene, keys, v).unwrap()).unwrap();
            !r.factor_of_safety.unwrap().at_least_one()
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
        let e = sample_scene(&scene, std::slice::from_ref(&u), &values[0]).unwrap_err();
        assert!(e.key.contains(key), "{e}");
        assert!(e.to_string().contains(why), "{e}");
    }
}

/// The scene shipped with an `[uncertain]` table.
fn uncertain_scene() -> Scene {
    Scene::from_file(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like-uncertain.toml"),
    )
    .unwrap()
}

#[test]
fn a_scene_names_its_distributions_in_an_uncertain_table_read_in_key_order() {
    let s = uncertain_scene();
    let keys: Vec<&str> = s.uncertain().iter().map(|u| u.key.as_str()).collect();
    assert_eq!(
        keys,
        [
            "foundation.zeta_deg",
            "friction.mu_k",
            "loads.eccentricity_m"
        ]
    );
    assert_eq!(s.uncertain()[1].distribution.to_string(), "normal:0.4:0.05");
    // Without the table, nothing is uncertain.
    assert!(Scene::default_scene().uncertain().is_empty());
}

#[test]
fn a_wrong_distribution_in_the_scene_names_its_key() {
    let base = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like-uncertain.toml"),
    )
    .unwrap();
    for (from, to, key) in [
        (
            "\"normal:0.40:0.05\"",
            "\"normal:0.40:-1\"",
            "uncertain.\"friction.mu_k\"",
        ),
        (
            "\"uniform:22:28\"",
            "\"gauss:22:28\"",
            "uncertain.\"foundation.zeta_deg\"",
        ),
        ("\"friction.mu_k\" =", "\"mu_k\" =", "uncertain.\"mu_k\""),
    ] {
        let text = base.replace(from, to);
        let e = Scene::from_toml(&text, "u.toml").unwrap_err();
        assert_eq!(e.key, key, "{e}");
    }
    let text = base.replace("\"uniform:22:28\"", "25.0");
    let e = Scene::from_toml(&text, "u.toml").unwrap_err();
    assert!(e.key.starts_with("uncertain"), "{e}");
}

#[test]
fn a_range_of_the_design_run_apart_gives_the_rows_of_the_whole_run() {
    use slideroute::internals::analysis::probabilistic::{Design, run_values};
    let scene = flat();
    let uncertain: Vec<Uncertain> = vec![
        "friction.mu_k=normal:0.8:0.05".parse().unwrap(),
        "loads.eccentricity_m=uniform:-0.5:0.5".parse().unwrap(),
    ];
    let design = Design {
        scene: &scene,
        uncertain: &uncertain,
        samples: 40,
        seed: 3,
        sampling: Sampling::LatinHypercube,
    };
    let whole = design.run(|| {}, || false);
    let values = design.values();
    let mut parts = Vec::new();
    for (k, chunk) in values.chunks(7).enumerate() {
        parts.extend(run_values(
            &scene,
            &uncertain,
            7 * k,
            chunk.to_vec(),
            || {},
            || false,
        ));
    }
    assert_eq!(whole, parts);
    assert_eq!(
        whole.iter().map(|s| s.index).collect::<Vec<_>>(),
        (0..40).collect::<Vec<_>>()
    );
}

#[test]
fn the_summary_counts_sliding_samples_and_ranks_the_friction_first() {
    use slideroute::internals::analysis::probabilistic::{Design, Limits, summarise};
    let scene = flat();
    let uncertain: Vec<Uncertain> = vec![
        "friction.mu_k=normal:0.8:0.05".parse().unwrap(),
        "block.mass_kg=uniform:0.99e6:1.01e6".parse().unwrap(),
    ];
    let design = Design {
        scene: &scene,
        uncertain: &uncertain,
        samples: 200,
        seed: 11,
        sampling: Sampling::LatinHypercube,
    };
    let rows = design.run(|| {}, || false);
    let s = summarise(&design, Limits::default(), &rows);
    let slid = rows
        .iter()
        .filter(|r| match &r.outcome {
            slideroute::Outcome::Route(x) => x.factor_of_safety_value().unwrap() < 1.0,
            _ => false,
        })
        .count();
    assert_eq!(s.routes, 200);
    assert_eq!(s.probability_of_sliding.value, slid as f64 / 200.0);
    // The factor of safety is μ W / H: ranked by μ alone, whatever the mass's ±1 % does.
    let rho = s.rank_correlations[0].with_factor_of_safety.unwrap();
    let rho_mass = s.rank_correlations[1].with_factor_of_safety.unwrap();
    assert!(rho > 0.95 && rho_mass.abs() < rho, "{rho} {rho_mass}");
}
