#![deny(deprecated)]

rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        velocities: zero,
    }
}

fn main() {}
