//! Compile errors of `derive_dynamics!`, pinned with trybuild: each bad input gives a clear
//! error with a span on the offending token, or naming the spec's file, line, link and field.

#[test]
fn macro_errors_are_clear_compile_errors_and_a_valid_module_compiles() {
    // trybuild compiles the cases in a project of its own; the macro falls back to this
    // crate's directory for the robot paths of `cases/*.rs`.
    std::env::set_var("RNE_CODEGEN_MANIFEST_DIR", env!("CARGO_MANIFEST_DIR"));
    let cases = trybuild::TestCases::new();
    cases.compile_fail("cases/*.rs");
    cases.pass("cases/pass/*.rs");
}
