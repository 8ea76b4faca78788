//! The emitted module is valid Rust: it parses, and rustc compiles it as a library with
//! warnings denied.

use std::process::Command;

#[test]
fn emitted_code_parses_as_a_rust_file() {
    let code = slideroute_codegen::generate();
    syn::parse_file(&code).expect("generated code parses");
    assert!(code.starts_with("// @generated"));
}

#[test]
fn emitted_code_compiles_without_warnings() {
    let code = slideroute_codegen::generate();
    let dir = std::env::temp_dir().join(format!("slideroute-codegen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let src = dir.join("coeffs.rs");
    std::fs::write(&src, &code).expect("write generated code");
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".to_string());
    let out = Command::new(rustc)
        .args(["--edition", "2024", "--crate-type", "lib", "-D", "warnings"])
        .arg("--out-dir")
        .arg(&dir)
        .arg(&src)
        .output()
        .expect("run rustc");
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        out.status.success(),
        "rustc rejected the generated code:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn generation_is_deterministic() {
    assert_eq!(
        slideroute_codegen::generate(),
        slideroute_codegen::generate()
    );
}
