rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        outptus: [inverse_dynamics],
    }
}

fn main() {}
