rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        forward_dynamics: cholesky,
        friction: maybe,
    }
}

fn main() {}
