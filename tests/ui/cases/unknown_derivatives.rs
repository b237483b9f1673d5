rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        derivatives: vector,
    }
}

fn main() {}
