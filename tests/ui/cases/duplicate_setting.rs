rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        scalar: f64,
        scalar: f32,
    }
}

fn main() {}
