//! `--fma` on `rne emit` and `rne stats` (the macro's `fma: true`, docs/design.md §3): the emitted
//! code sums products through `Real::mul_add`, the operation counts stay and the critical
//! path shortens.

mod common;

fn rne(args: &[&str]) -> String {
    common::rne(args).unwrap_or_else(|e| panic!("{args:?}: {e}"))
}

/// The `rne stats --json` entry of `kernel`.
fn stats(fma: bool, kernel: &str) -> serde_json::Value {
    let mut args = vec!["stats", "puma560", "--json"];
    if fma {
        args.push("--fma");
    }
    let report: serde_json::Value = serde_json::from_str(&rne(&args)).unwrap();
    report["kernels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|k| k["kernel"] == kernel)
        .unwrap_or_else(|| panic!("no {kernel} in {report}"))
        .clone()
}

#[test]
fn emit_with_fma_sums_products_through_mul_add() {
    let args = ["emit", "planar-elbow", "--outputs", "inverse_dynamics"];
    let plain = rne(&args);
    let fused = rne(&[&args[..], &["--fma"]].concat());
    assert!(!plain.contains("mul_add"), "{plain}");
    assert!(fused.contains("mul_add"), "{fused}");
}

#[test]
fn stats_with_fma_keeps_the_counts_and_shortens_the_critical_path() {
    for kernel in ["inverse_dynamics", "inverse_dynamics_derivatives"] {
        let (plain, fused) = (stats(false, kernel), stats(true, kernel));
        for field in ["mul", "add", "div"] {
            assert_eq!(plain[field], fused[field], "{kernel} {field}");
        }
        let path = |k: &serde_json::Value| k["critical_path"].as_u64().unwrap();
        assert!(
            path(&fused) < path(&plain),
            "{kernel}: {} cycles fused, {} plain",
            path(&fused),
            path(&plain)
        );
    }
}
