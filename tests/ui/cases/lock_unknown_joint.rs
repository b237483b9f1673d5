rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        lock: { q1: 0.0, q9: 1.0 },
    }
}

fn main() {}
