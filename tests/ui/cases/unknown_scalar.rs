rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        scalar: f16,
    }
}

fn main() {}
