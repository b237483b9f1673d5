rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        at_rest: true,
        velocities: zero,
    }
}

fn main() {}
