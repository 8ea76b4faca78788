//! The integration tests, one crate (one binary links the library once, not
//! thirteen times). Each module is one concern; `common` holds the hand derivations and helpers
//! they share. Data files live beside this folder: `tests/corpus/` (malformed scenes) and
//! `tests/reference/` (the stored routes).
//!
//! The Drake cross-check is `#[ignore]`d here and run by CI after `crosscheck/setup.sh`:
//! `cargo test --workspace drake_crosscheck -- --ignored`.

mod common;

mod anchors;
mod architecture;
mod base_contact;
mod cast_base;
mod cli;
mod coefficients_match_derivation;
mod dam_loads;
mod docs;
mod drake_crosscheck;
mod exact_relations_at_direct_poses;
mod faces;
mod general_pose;
mod ground_motion;
mod hostile;
mod memory;
mod newmark_exact;
mod paper_misprints;
mod reactions_paper;
mod readme;
mod record_files;
mod report_browser;
mod rigid_body;
mod roots_against_direct;
mod roots_completeness;
mod roots_traps;
mod route;
mod route_reference;
mod route_view;
mod scene_fuzz;
mod touches_against_parry;
mod uncertainty;
