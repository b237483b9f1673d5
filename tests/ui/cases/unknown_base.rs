rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        base: floating_ish,
    }
}

fn main() {}
