//! Kernels compiled twice, for the build's target and with AVX and AVX2, the second called
//! where the processor has them (`rne_runtime::cpu`, whose docs say why).
//!
//! Only large kernels are. `rne bench --quick` on an AMD EPYC (Zen 4, AVX-512), the portable
//! build before and with this dispatch (first for AVX alone and every kernel of 1800
//! instructions or more, two runs each):
//! - UR5's forward-dynamics derivatives (3250 instructions): 663 → 518–523 ns;
//! - the Panda arm's inverse-dynamics derivatives (5470): 1340–1376 → 1016–1019 ns, its
//!   forward-dynamics derivatives (8260): 1870–1875 → 1454–1475 ns;
//! - UR5's inverse-dynamics derivatives (1910): 252 → 265–268 ns, slower: the call and the
//!   copy of the result cost more than AVX saves on a kernel that spills little.
//!
//! With AVX2 enabled as well (three interleaved runs against AVX alone, a noisy machine:
//! the lower two of each), UR5's forward-dynamics derivatives took 447–482 ns against 515,
//! the Panda arm's derivatives the same. Building everything for AVX instead
//! (`-C target-feature=+avx,+avx2`) made the Jacobians of every frame (460–900 instructions)
//! about 10 % slower and the Panda arm's inverse dynamics (740) 18 % slower.
//!
//! The threshold was 2500 instructions until an AMD EPYC of the Zen 3 generation (AVX2, no
//! AVX-512) timed the kernels between 1400 and 2500 faster dispatched (`rne bench --quick`,
//! three interleaved runs of each build, the first of each discarded as noisy): UR5's
//! inverse-dynamics derivatives 485–486 → 418–420 ns, UR5's regressor (about 1480) 400–405 →
//! 286–294 ns, the Panda arm's regressor 537–546 → 484–486 ns; the Zen 4 above had UR5's
//! inverse-dynamics derivatives 5 % slower dispatched.

/// The fewest instructions a kernel has for it to be compiled for AVX and AVX2 too.
pub const DISPATCH_FROM: usize = 1400;

/// The body of a kernel function whose own body would be `body`, given its `generics`
/// (`<T: …>` or nothing), `parameters` (`name: type, ` each), return type `ret` and the
/// parameters' `names`: on x86-64 builds without AVX, `body` moves into an always-inlined
/// inner function `evaluate`, called through `with_avx2`, compiled with AVX and AVX2,
/// where `runtime::cpu::has_avx2()`, else directly.
pub fn dispatching_body(
    generics: &str,
    parameters: &str,
    ret: &str,
    names: &[&str],
    body: &str,
    runtime: &str,
) -> String {
    let call = format!(
        "{}({})",
        if generics.is_empty() { "" } else { "::<T>" },
        names.join(", ")
    );
    format!(
        "#[inline(always)]\nfn evaluate{generics}({parameters}) -> {ret} {{\n{body}}}\n\
         #[cfg(all(target_arch = \"x86_64\", not(target_feature = \"avx2\")))]\n{{\n\
         /// # Safety\n/// Only where the processor runs AVX and AVX2.\n\
         #[target_feature(enable = \"avx,avx2\")]\n\
         unsafe fn with_avx2{generics}({parameters}) -> {ret} {{\nevaluate{call}\n}}\n\
         if {runtime}::cpu::has_avx2() {{\n\
         // SAFETY: the processor runs AVX and AVX2.\n\
         return unsafe {{ with_avx2{call} }};\n}}\n}}\n\
         evaluate{call}\n"
    )
}

#[cfg(test)]
mod tests {
    use super::dispatching_body;

    #[test]
    fn a_dispatching_body_calls_the_avx_copy_only_where_the_processor_has_it() {
        let body = dispatching_body(
            "<T: rt::Real>",
            "p: &Params, q: &[T; NQ], ",
            "[T; NV]",
            &["p", "q"],
            "let t0 = q[0];\n[t0]\n",
            "rt",
        );
        let block: syn::Block = syn::parse_str(&format!("{{{body}}}")).expect("Rust");
        let text = quote::quote!(#block).to_string();
        for part in [
            "# [inline (always)] fn evaluate < T : rt :: Real > (p : & Params , q : & [T ; NQ] ,) -> [T ; NV] { let t0 = q [0] ; [t0] }",
            "# [cfg (all (target_arch = \"x86_64\" , not (target_feature = \"avx2\")))]",
            "# [target_feature (enable = \"avx,avx2\")] unsafe fn with_avx2 < T : rt :: Real >",
            "if rt :: cpu :: has_avx2 () { return unsafe { with_avx2 :: < T > (p , q) } ; }",
        ] {
            assert!(text.contains(part), "{part} in {text}");
        }
        assert!(text.ends_with("evaluate :: < T > (p , q) }"), "{text}");
    }
}
