rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        gravity: [0.0, -9.81],
    }
}

fn main() {}
