//! Expands the paper's law-of-sines relations into polynomial coefficients and writes them to
//! `$OUT_DIR/coeffs.rs`, which `src/coeffs/mod.rs` includes. See `codegen/`.

fn main() {
    let out_dir = std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR for build scripts");
    let path = std::path::Path::new(&out_dir).join("coeffs.rs");
    let code = slideroute_codegen::generate();
    std::fs::write(&path, code).expect("write generated coefficients to OUT_DIR");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=codegen/src");
}
