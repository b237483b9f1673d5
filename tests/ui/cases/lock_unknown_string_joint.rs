rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        lock: { "joint 8": 0.0 },
    }
}

fn main() {}
